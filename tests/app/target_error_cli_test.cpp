// `prism render --target-error E [--verify]` from the command line: the report lines, and the
// options it conflicts with (exit status 2, a message naming the option, no image).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

const std::string Whitted = ShellQuoted(Source + "/scenes/whitted.pbrt");

class TargetErrorCli : public test::FreshDirTest {};

TEST_F(TargetErrorCli, ReportsChoiceAndReachedError) {
    RunResult r = RunPrism(
        "render " + Whitted + " --res 48x36 --target-error 0.08 --verify --no-progress -o t.png",
        dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "t.png"));
    EXPECT_NE(r.err.find("target-error: chose spp "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("predicted rel. RMSE "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("target-error: reached rel. RMSE "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(target 0.08, "), std::string::npos) << r.err;
}

TEST_F(TargetErrorCli, ConflictingOptionsAreUsageErrors) {
    for (const char *opt : {"--spp 4", "--cutoff 0", "--light-samples 2"}) {
        RunResult r = RunPrism(
            "render " + Whitted + " --res 32x24 --target-error 0.05 " + opt + " -o c.png", dir_);
        EXPECT_EQ(r.exitCode, 2) << opt;
        std::string name = std::string(opt).substr(0, std::string(opt).find(' '));
        EXPECT_NE(r.err.find("--target-error chooses"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("drop " + name), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "c.png"));
    }
    RunResult v = RunPrism("render " + Whitted + " --res 32x24 --verify -o c.png", dir_);
    EXPECT_EQ(v.exitCode, 2);
    EXPECT_NE(v.err.find("--verify needs --target-error"), std::string::npos) << v.err;
    for (const char *bad : {"--target-error 0", "--target-error -1", "--target-error x"})
        EXPECT_EQ(RunPrism("render " + Whitted + " " + bad + " -o c.png", dir_).exitCode, 2) << bad;
    // Unreachable: a clear error, no image.
    RunResult u = RunPrism("render " + Whitted + " --res 32x24 --target-error 1e-6 -o c.png", dir_);
    EXPECT_EQ(u.exitCode, 2);
    EXPECT_NE(u.err.find("cannot be reached"), std::string::npos) << u.err;
    EXPECT_FALSE(fs::exists(dir_ / "c.png"));
    // A bad output path fails before the pilot (it would take seconds): no pilot line.
    RunResult o = RunPrism(
        "render " + Whitted + " --res 32x24 --target-error 0.05 -o missing/dir/c.png", dir_);
    EXPECT_EQ(o.exitCode, 2);
    EXPECT_NE(o.err.find("does not exist"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("target-error: chose"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace prism
