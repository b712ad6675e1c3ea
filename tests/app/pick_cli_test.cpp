// `prism pick SCENE X Y [--json]`: the camera ray through a pixel centre and what it hits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/process.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// A unit sphere at the origin (Shape on line 6), a mirror sphere beside it (line 9), seen from
// z = -5 with a 60 degree field of view on a 21x21 image.
const char *const kScene = R"(LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective" "float fov" 60
Film "image" "integer xresolution" 21 "integer yresolution" 21
WorldBegin
LightSource "point" "point from" [0 5 -5]
Shape "sphere" "float radius" 1
AttributeBegin
  Material "mirror"
  Translate 2 0 0 Shape "sphere" "float radius" 0.5
AttributeEnd
WorldEnd
)";

// The numbers of the first JSON array after `key` in `s` (from `from`).
std::vector<double> ArrayAfter(const std::string &s, const std::string &key, size_t from = 0) {
    size_t k = s.find("\"" + key + "\": [", from);
    std::vector<double> v;
    if (k == std::string::npos) return v;
    size_t p = s.find('[', k) + 1, e = s.find(']', p);
    std::string body = s.substr(p, e - p);
    for (char *c = body.data(); *c;) {
        char *end;
        double x = std::strtod(c, &end);
        if (end == c) {
            ++c;
            continue;
        }
        v.push_back(x);
        c = end;
    }
    return v;
}

// The analytic hit of the pixel-centre ray of pixel (x, y) with the unit sphere.
std::vector<double> AnalyticHit(int x, int y) {
    const double tanHalf = std::tan(30.0 * M_PI / 180.0);
    double sx = ((x + 0.5) / 21.0 * 2 - 1) * tanHalf, sy = (1 - (y + 0.5) / 21.0 * 2) * tanHalf;
    double len = std::sqrt(sx * sx + sy * sy + 1);
    double d[3] = {sx / len, sy / len, 1 / len}, o[3] = {0, 0, -5};
    double b = o[2] * d[2], c = 25 - 1;  // |o + t d|^2 = 1
    double t = -b - std::sqrt(b * b - c);
    return {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
}

TEST(PickCli, NamesTheShapeAndItsAnalyticHitPoint) {
    fs::path dir = TempDir("sphere");
    std::ofstream(dir / "s.pbrt") << kScene;
    for (auto [x, y] : {std::pair{10, 10}, std::pair{12, 8}, std::pair{8, 11}}) {
        RunResult r =
            RunPrism("pick s.pbrt " + std::to_string(x) + " " + std::to_string(y) + " --json", dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find("\"type\": \"sphere\""), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("s.pbrt\", \"line\": 6, \"column\": 1"), std::string::npos) << r.out;
        std::vector<double> p = ArrayAfter(r.out, "point"), want = AnalyticHit(x, y);
        ASSERT_EQ(p.size(), 3u) << r.out;
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[size_t(i)], want[size_t(i)], 1e-6) << r.out;
        // The shading normal of a unit sphere is the hit point.
        std::vector<double> n = ArrayAfter(r.out, "shadingNormal");
        ASSERT_EQ(n.size(), 3u);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(n[size_t(i)], want[size_t(i)], 1e-5);
    }
    // The text form names the same declaration.
    RunResult t = RunPrism("pick s.pbrt 10 10", dir);
    ASSERT_EQ(t.exitCode, 0) << t.err;
    EXPECT_NE(t.out.find("shape: sphere at s.pbrt:6:1"), std::string::npos) << t.out;
    EXPECT_NE(t.out.find("default matte"), std::string::npos) << t.out;
}

TEST(PickCli, FollowsTheMirrorAndPrintsValidJson) {
    fs::path dir = TempDir("mirror");
    std::ofstream(dir / "s.pbrt") << kScene;
    // Pixel 18 of row 10 looks at the mirror sphere at x = 2 (its centre projects to x = 17.8).
    RunResult r = RunPrism("pick s.pbrt 18 10 --json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("s.pbrt\", \"line\": 9"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"type\": \"mirror\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("s.pbrt\", \"line\": 8"), std::string::npos) << r.out;  // Material
    EXPECT_NE(r.out.find("\"kind\": \"reflection\""), std::string::npos) << r.out;
    if (std::system("python3 -c 'import json' >/dev/null 2>&1") == 0) {
        std::ofstream(dir / "out.json") << r.out;
        EXPECT_EQ(std::system(("python3 -c 'import json,sys; json.load(open(sys.argv[1]))' '" +
                               (dir / "out.json").string() + "'")
                                  .c_str()),
                  0)
            << r.out;
    }
}

TEST(PickCli, NamesObjObjectsAndMaterials) {
    fs::path dir = TempDir("obj");
    std::ofstream(dir / "quad.mtl") << "newmtl red\nKd 0.8 0.1 0.1\n";
    std::ofstream(dir / "quad.obj") << "mtllib quad.mtl\no panel\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\n"
                                       "v -1 1 0\nusemtl red\nf 1 2 3 4\n";
    RunResult r = RunPrism("pick quad.obj 10 10 --res 21x21 --json", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\"name\": \"panel\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"name\": \"red\""), std::string::npos) << r.out;
}

TEST(PickCli, PixelOutsideTheImageIsAUsageError) {
    fs::path dir = TempDir("outside");
    std::ofstream(dir / "s.pbrt") << kScene;
    RunResult r = RunPrism("pick s.pbrt 21 0", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("outside the 21x21 image"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prism
