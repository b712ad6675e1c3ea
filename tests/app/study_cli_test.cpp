// End-to-end tests of `prism study`: outputs, progress, and bad input (exit status 2, a clear
// message, no output directory).
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

class StudyCli : public test::FreshDirTest {};

TEST_F(StudyCli, WritesResultsReportAndProgress) {
    RunResult r = RunPrism("study " + Whitted +
                               " --knob spp --knob robust,bvh-quality --res 32x24 --repeats 1 "
                               "--ref-spp 8 --threads 2 --out out",
                           dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string csv = ReadFile(dir_ / "out/results.csv");
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line,
              "knob,value,time_s,build_s,rays,rmse,rel_l1,max_abs_err,psnr,bad_pixels,nan_count");
    std::vector<std::string> keys;
    while (std::getline(lines, line))
        keys.push_back(line.substr(0, line.find(',', line.find(',') + 1)));
    EXPECT_EQ(keys, (std::vector<std::string>{"spp,1", "spp,2", "spp,4", "robust,off", "robust,on",
                                              "bvh-quality,low", "bvh-quality,medium",
                                              "bvh-quality,high"}));
    std::string report = ReadFile(dir_ / "out/report.md");
    EXPECT_NE(report.find("## spp"), std::string::npos);
    EXPECT_NE(report.find("## bvh-quality"), std::string::npos);
    EXPECT_NE(report.find("For RMSE <= "), std::string::npos);
    EXPECT_NE(r.out.find("For RMSE <= "), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("setting 1 of 8: spp = 1"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("setting 8 of 8: bvh-quality = high"), std::string::npos) << r.err;
    // Plots when python3 with matplotlib is there, a warning otherwise; never a failure.
    if (r.err.find("plots skipped") == std::string::npos)
        EXPECT_TRUE(fs::exists(dir_ / "out/pareto.png")) << r.err;
    for (const auto &e : fs::directory_iterator(dir_ / "out"))
        EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left: " << e.path();
}

TEST_F(StudyCli, SkippedKnobIsExplained) {
    // quadrics.pbrt has only point and spot lights.
    RunResult r = RunPrism("study '" + test::Source +
                               "/scenes/quadrics.pbrt' --knob light-samples --res 16x12 "
                               "--repeats 1 --ref-spp 2 --out out",
                           dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("knob light-samples skipped: the scene has no area or infinite light"),
              std::string::npos)
        << r.err;
    EXPECT_NE(ReadFile(dir_ / "out/report.md").find("## Knobs not studied"), std::string::npos);
}

TEST_F(StudyCli, BadInputWritesNothing) {
    struct Case {
        std::string args, message;
    };
    std::ofstream(dir_ / "file") << "x";
    const std::string rest = " --repeats 1 --ref-spp 2";
    const Case cases[] = {
        {Whitted + " --knob sp --res 8x6 --out out" + rest,
         "error: --knob: unknown knob \"sp\" (known: spp, maxdepth"},
        {"missing.pbrt --res 8x6 --out out" + rest, "missing.pbrt"},
        {Whitted + " --res 0x10 --out out" + rest, "error: --res expects WxH"},
        {Whitted + " --levels 8,2 --res 8x6 --out out" + rest,
         "error: --levels: \"2\" is not a segment count"},
        {Whitted + " --repeats 0 --res 8x6 --out out --ref-spp 2", "--repeats"},
        {"--knob spp " + Whitted + " --res 8x6 --out out" + rest,
         "was read as a --knob; give the scene first"},
        {"--res 8x6 --out out" + rest, "error: a scene file is required"},
        {Whitted + " --res 8x6 --out file" + rest,
         "error: --out \"file\" exists and is not a directory"},
    };
    for (const Case &c : cases) {
        RunResult r = RunPrism("study " + c.args, dir_);
        EXPECT_EQ(r.exitCode, 2) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out")) << c.args;
    }
    EXPECT_EQ(ListDir(), (std::set<std::string>{"file"}));
}

}  // namespace
}  // namespace prism
