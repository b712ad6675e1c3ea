// End-to-end tests of the prism executable: rendering, determinism, ray queries and the
// handling of malformed input (exit status, located message, no output file).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "image/image.h"
#include "image/image_compare.h"
#include "image/image_io.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

struct RunResult {
    int exitCode = -1;
    std::string out, err;
};

std::string ReadFile(const fs::path &p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

fs::path TempDir(const std::string &name) {
    fs::path d = fs::path(::testing::TempDir()) / ("prism_cli_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// Runs prism with the given arguments (shell-quoted by the caller) in directory `cwd`.
RunResult RunPrism(const std::string &args, const fs::path &cwd) {
    fs::path outFile = cwd / "stdout.txt", errFile = cwd / "stderr.txt";
    std::string cmd = "cd '" + cwd.string() + "' && '" + std::string(PRISM_BINARY) + "' " + args +
                      " >'" + outFile.string() + "' 2>'" + errFile.string() + "' </dev/null";
    int status = std::system(cmd.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadFile(outFile);
    r.err = ReadFile(errFile);
    fs::remove(outFile);
    fs::remove(errFile);
    return r;
}

const std::string Source = PRISM_SOURCE_DIR_FOR_TESTS;

TEST(Cli, RendersWhittedAtSmallSize) {
    fs::path dir = TempDir("whitted");
    RunResult r = RunPrism("render '" + Source + "/scenes/whitted.pbrt' --res 64x48 -o out.exr --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image img = ReadImage((dir / "out.exr").string());
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
    Image golden = ReadImage(Source + "/tests/golden/whitted_64x48.exr");
    ImageDiff d = CompareImages(img, golden, 0.05f);
    // The golden image was rendered by Prism itself after visual inspection; small
    // tolerances absorb compiler and ISA differences.
    EXPECT_LT(d.rmse, 0.01) << "mean abs " << d.meanAbs << " max " << d.maxAbs;
    EXPECT_LT(d.badPixels, 10);
}

TEST(Cli, ImageIsIndependentOfThreadCount) {
    fs::path dir = TempDir("threads");
    std::string scene = "'" + Source + "/scenes/whitted.pbrt' --res 64x48 --spp 4 --quiet";
    ASSERT_EQ(RunPrism("render " + scene + " --threads 1 -o one.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render " + scene + " --threads 2 -o two.exr", dir).exitCode, 0);
    Image a = ReadImage((dir / "one.exr").string()), b = ReadImage((dir / "two.exr").string());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_TRUE(a.pixels == b.pixels) << "images differ between 1 and 2 threads";
}

TEST(Cli, RenderReportsStatistics) {
    fs::path dir = TempDir("stats");
    RunResult r = RunPrism("render '" + Source + "/scenes/whitted.pbrt' --res 32x24 -o s.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("BVH build"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("refraction"), std::string::npos);
    EXPECT_NE(r.err.find("Mrays/s"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "s.png"));
}

TEST(Cli, BadInputFailsCleanly) {
    fs::path bad = fs::path(Source) / "tests/bad";
    std::ifstream cases(bad / "cases.txt");
    ASSERT_TRUE(cases) << "missing tests/bad/cases.txt";
    std::string line;
    int n = 0;
    while (std::getline(cases, line)) {
        if (line.empty() || line[0] == '#') continue;
        auto bar1 = line.find(" | "), bar2 = line.find(" | ", bar1 + 3);
        ASSERT_NE(bar2, std::string::npos) << line;
        std::string file = line.substr(0, bar1);
        int status = std::stoi(line.substr(bar1 + 3, bar2 - bar1 - 3));
        std::string fragment = line.substr(bar2 + 3);
        fs::path dir = TempDir("bad");
        std::string scenePath = (bad / file).string();
        RunResult r = RunPrism("render '" + scenePath + "' -o out.png --res 16x16", dir);
        EXPECT_EQ(r.exitCode, status) << file << ": " << r.err;
        if (fragment[0] == '@') fragment = scenePath + ":" + fragment.substr(1);
        EXPECT_NE(r.err.find(fragment), std::string::npos)
            << file << ": expected \"" << fragment << "\" in: " << r.err;
        // Exactly one error line.
        size_t errors = 0;
        for (size_t p = r.err.find("error:"); p != std::string::npos; p = r.err.find("error:", p + 1))
            ++errors;
        EXPECT_EQ(errors, 1u) << file << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << file << " left an output file";
        for (const auto &e : fs::directory_iterator(dir))
            ADD_FAILURE() << file << " left " << e.path();
        ++n;
    }
    EXPECT_GE(n, 6);
}

TEST(Cli, BadOptionsExitWithStatus2) {
    fs::path dir = TempDir("opts");
    std::string scene = "'" + Source + "/scenes/whitted.pbrt'";
    EXPECT_EQ(RunPrism("render " + scene + " --res 0x10 -o a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " --spp 0 -o a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " -o a.xyz", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("render " + scene + " -o no/such/dir/a.png", dir).exitCode, 2);
    EXPECT_EQ(RunPrism("frobnicate", dir).exitCode, 2);
    EXPECT_FALSE(fs::exists(dir / "a.png"));
}

TEST(Cli, InfoDescribesScene) {
    fs::path dir = TempDir("info");
    RunResult r = RunPrism("info '" + Source + "/scenes/quadrics.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("shapes:     13 ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("torus 2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("triangles:  2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("lights:     2 (point 1, spot 1)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bounds:"), std::string::npos);
    EXPECT_NE(r.out.find("warnings:   0"), std::string::npos);
    EXPECT_EQ(RunPrism("info missing.pbrt", dir).exitCode, 2);
}

TEST(Cli, TraceReportsHitsMissesAndLimits) {
    fs::path dir = TempDir("trace");
    std::ofstream(dir / "s.pbrt") << "Camera \"perspective\"\nWorldBegin\n"
                                     "AttributeBegin\nTranslate 0 0 5\nShape \"sphere\" \"float radius\" 1\nAttributeEnd\n"
                                     "AttributeBegin\nReverseOrientation\nTranslate 10 0 5\nShape \"sphere\"\nAttributeEnd\n"
                                     "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point3 P\" [-1 -1 20  1 -1 20  0 1 20]\n"
                                     "WorldEnd\n";
    std::ofstream(dir / "rays.txt") << "# origin direction [tmin tmax]\n"
                                       "0 0 0  0 0 1\n"
                                       "0 0 0  0 0 2   # unnormalized: t halves\n"
                                       "0 5 0  0 0 1\n"
                                       "0 0 0  0 0 1  0 3.5\n"
                                       "0 0 0  0 0 1  4.5 100\n"
                                       "10 0 0  0 0 1\n"
                                       "0 0 10  0 0 1\n";
    RunResult r = RunPrism("trace s.pbrt --rays rays.txt --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::vector<std::string> got;
    for (std::string l; std::getline(lines, l);) got.push_back(l);
    ASSERT_EQ(got.size(), 7u) << r.out;
    EXPECT_EQ(got[0], "hit 4 0 0 4 0 0 -1 0 0");
    EXPECT_EQ(got[1], "hit 2 0 0 4 0 0 -1 0 0");
    EXPECT_EQ(got[2], "miss");
    EXPECT_EQ(got[3], "miss");                         // tmax stops before the sphere
    EXPECT_EQ(got[4], "hit 6 0 0 6 0 0 1 0 0");        // tmin skips the near side
    EXPECT_EQ(got[5], "hit 4 10 0 4 0 0 1 1 0");       // ReverseOrientation flips n
    EXPECT_EQ(got[6], "hit 10 0 0 20 0 0 1 2 0");      // triangle: (p1-p0) x (p2-p0)
    RunResult occ = RunPrism("trace s.pbrt --rays rays.txt --occluded --quiet", dir);
    ASSERT_EQ(occ.exitCode, 0);
    EXPECT_EQ(occ.out, "1\n1\n0\n0\n1\n1\n1\n");
    std::ofstream(dir / "bad.txt") << "0 0 0 0 0 1\n0 0 0 0 1\n";
    RunResult bad = RunPrism("trace s.pbrt --rays bad.txt -o out.txt", dir);
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("bad.txt:2:"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "out.txt"));
}

}  // namespace
}  // namespace prism
