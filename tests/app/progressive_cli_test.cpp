// `prism render --time-limit S` and `--stats`, and `prism batch --time-limit S`, from the
// command line (the passes and the estimate themselves: tests/render/progressive_test.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/process.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// A sphere under an area light: soft shadows, so samples differ.
void WriteScene(const fs::path &p) {
    std::ofstream(p)
        << "LookAt 0 1 -4  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
           "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 24\n"
           "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [5 5 5]\n"
           "Translate 0 3 0\nShape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point3 P\" [-9 0 -9  9 0 -9  9 0 9  -9 0 9]\n"
           "Translate 0 0.5 0\nShape \"sphere\" \"float radius\" 0.5\nWorldEnd\n";
}

TEST(TimeLimitCli, RendersPassesAndPrintsTheNoise) {
    fs::path dir = TempDir("render");
    WriteScene(dir / "s.pbrt");
    RunResult r = RunPrism("render s.pbrt -o s.png --no-progress --time-limit 1 --stats", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("time limit 1s: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("noise: relative standard error "), std::string::npos) << r.err;
    EXPECT_GT(fs::file_size(dir / "s.png"), 100u);

    // With --spp the passes stop at that many samples.
    r = RunPrism("render s.pbrt -o t.exr --no-progress --time-limit 100 --spp 8", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("time limit 100s: 3 passes (2+2+4 = 8 spp)"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("noise:"), std::string::npos) << "no --stats, no noise line";

    // --stats alone: the estimate of a plain render; 1 spp has none.
    r = RunPrism("render s.pbrt -o u.png --no-progress --spp 4 --stats", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("noise: relative standard error "), std::string::npos) << r.err;
    r = RunPrism("render s.pbrt -o u.png --no-progress --spp 1 --stats", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("noise: no estimate (it needs at least 2 spp)"), std::string::npos);
}

TEST(TimeLimitCli, BadCombinationsAreUsageErrors) {
    fs::path dir = TempDir("bad");
    WriteScene(dir / "s.pbrt");
    RunResult r = RunPrism("render s.pbrt -o s.png --time-limit 1 --target-error 0.05", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--target-error and --time-limit"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "s.png"));
    r = RunPrism("render s.pbrt -o s.png --time-limit -1", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir / "s.png"));
}

TEST(TimeLimitCli, BatchPassesTheLimitToEachScene) {
    fs::path dir = TempDir("batch");
    fs::create_directories(dir / "in");
    WriteScene(dir / "in/a.pbrt");
    WriteScene(dir / "in/b.pbrt");
    RunResult r = RunPrism(
        "batch in -o out --quiet --time-limit 0.5 --integrator path --texture-filter point", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string report = test::ReadFile(dir / "out/report.json");
    EXPECT_NE(report.find("\"status\": \"ok\""), std::string::npos) << report;
    EXPECT_TRUE(fs::exists(dir / "out/in_a.png"));
    EXPECT_TRUE(fs::exists(dir / "out/in_b.png"));
    // Each render spent about its half second in passes (without the limit these 32x24
    // renders take milliseconds).
    size_t at = report.find("\"render_seconds\": ");
    ASSERT_NE(at, std::string::npos) << report;
    EXPECT_GT(std::stod(report.substr(at + 18)), 0.4) << report;
    // --integrator reaches the renders too (the path tracer's indirect light changes the
    // image); a bad value is refused before any render.
    ASSERT_EQ(RunPrism("batch in -o w --quiet --spp 4 --integrator whitted", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("batch in -o p --quiet --spp 4 --integrator path", dir).exitCode, 0);
    EXPECT_NE(test::ReadFile(dir / "w/in_a.png"), test::ReadFile(dir / "p/in_a.png"));
    r = RunPrism("batch in -o bad --quiet --integrator nosuchintegrator", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir / "bad/in_a.png"));
}

}  // namespace
}  // namespace prism
