// `prism trace`, `prism info` and `prism render` on CSG scenes (Prism extension,
// docs/FORMAT.md).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// "hit t px py pz nx ny nz shape prim" → the numbers.
std::vector<double> Numbers(const std::string &line) {
    std::istringstream in(line);
    std::string word;
    in >> word;
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
}

TEST(CsgCli, TraceReportsTheResultSurface) {
    fs::path dir = TempDir("trace");
    // A sphere of radius 1 at z = 5 minus a sphere of radius 0.5 at z = 4 (Shape directives 0
    // and 1), then a plain sphere at x = 10 (directive 2).
    std::ofstream(dir / "s.pbrt") << R"(Camera "perspective"
WorldBegin
CSGBegin "difference"
  AttributeBegin Translate 0 0 5 Shape "sphere" "float radius" 1 AttributeEnd
  AttributeBegin Translate 0 0 4 Shape "sphere" "float radius" 0.5 AttributeEnd
CSGEnd
AttributeBegin Translate 10 0 5 Shape "sphere" AttributeEnd
WorldEnd
)";
    std::ofstream(dir / "rays.txt") << "0 0 0  0 0 1\n"
                                       "0.6 0 0  0 0 1\n"
                                       "0 0 0  0 0 1  0 4.4\n"
                                       "3 0 0  0 0 1\n"
                                       "10 0 0  0 0 1\n"
                                       "0 0 4  0 0 1\n";
    RunResult r = RunPrism("trace s.pbrt --rays rays.txt --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::vector<std::string> got;
    for (std::string l; std::getline(lines, l);) got.push_back(l);
    ASSERT_EQ(got.size(), 6u) << r.out;
    auto expect = [&](int i, std::vector<double> want) {
        std::vector<double> v = Numbers(got[size_t(i)]);
        ASSERT_EQ(got[size_t(i)].substr(0, 3), "hit") << got[size_t(i)];
        ASSERT_EQ(v.size(), want.size()) << got[size_t(i)];
        for (size_t k = 0; k < v.size(); ++k) EXPECT_NEAR(v[k], want[k], 1e-5) << got[size_t(i)];
    };
    // The carved surface of the small sphere, its normal turned into the hollow.
    expect(0, {4.5, 0, 0, 4.5, 0, 0, -1, 1, 0});
    // Outside the hollow: the big sphere.
    expect(1, {4.2, 0.6, 0, 4.2, 0.6, 0, -0.8, 0, 0});
    EXPECT_EQ(got[2], "miss");  // tmax stops in the hollow
    EXPECT_EQ(got[3], "miss");
    expect(4, {4, 10, 0, 4, 0, 0, -1, 2, 0});
    // From inside the hollow: out of it, into the solid.
    expect(5, {0.5, 0, 0, 4.5, 0, 0, -1, 1, 0});
    RunResult occ = RunPrism("trace s.pbrt --rays rays.txt --occluded --quiet", dir);
    ASSERT_EQ(occ.exitCode, 0);
    EXPECT_EQ(occ.out, "1\n1\n0\n0\n1\n1\n");

    RunResult info = RunPrism("info s.pbrt", dir);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("csg:        1 objects, 1 nodes (difference 1) over 2 operand shapes "
                            "(sphere 2)"),
              std::string::npos)
        << info.out;
}

TEST(CsgCli, SceneRenders) {
    fs::path dir = TempDir("render");
    RunResult r =
        RunPrism("render '" + Source + "/scenes/csg.pbrt' --res 64x48 -o out.png --quiet", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out.png"));
    RunResult info = RunPrism("info '" + Source + "/scenes/csg.pbrt'", dir);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("csg:        3 objects, 4 nodes"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("warnings:   0"), std::string::npos) << info.out;
}

}  // namespace
}  // namespace prism
