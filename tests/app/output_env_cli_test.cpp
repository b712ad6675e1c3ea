// End-to-end tests of exposure and tone mapping (--exposure, --tonemap, Film "exposure" and
// "tonemap") and of lighting (the studio rig of light-less models, --env, --env-rotate,
// --env-mode) through the prism executable.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/vecmath.h"
#include "image/image.h"
#include "image/image_io.h"
#include "image/tonemap.h"
#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

void Write(const fs::path &p, const std::string &text) { std::ofstream(p) << text; }

// A white Lambertian sphere lit by a point light, seen head-on by a y-up camera.
const char *kSphereScene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "image" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ] %FILM%
Sampler "random" "integer pixelsamples" [ 4 ]
Integrator "whitted"
WorldBegin
LightSource "point" "point3 from" [ 0 4 5 ] "rgb I" [ 40 40 40 ]
Material "matte" "rgb Kd" [ 1 1 1 ]
Shape "sphere" "float radius" [ 1 ]
WorldEnd
)";

std::string SphereScene(const std::string &film = "") {
    std::string s = kSphereScene;
    s.replace(s.find("%FILM%"), 6, film);
    return s;
}

// A UV sphere of radius 1 at the origin as OBJ (no materials, no lights, no camera).
std::string ObjSphere() {
    const int nu = 32, nv = 16;
    std::string s;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i < nu; ++i) {
            double th = Pi * j / nv, ph = 2 * Pi * i / nu;
            s += "v " + std::to_string(std::sin(th) * std::cos(ph)) + " " +
                 std::to_string(std::cos(th)) + " " + std::to_string(-std::sin(th) * std::sin(ph)) +
                 "\n";
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            int a = j * nu + i + 1, b = j * nu + (i + 1) % nu + 1, c = a + nu, d = b + nu;
            s += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) +
                 " " + std::to_string(b) + "\n";
        }
    return s;
}

double MeanLuminance(const Image &img, int x0, int x1, int y0, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += img.GetRGB(x, y).Luminance();
    return sum / ((x1 - x0) * (y1 - y0));
}

TEST(OutputCli, ExposureScalesEveryOutputExactly) {
    fs::path dir = TempDir("exposure");
    const std::string scene = "render '" + Source + "/scenes/whitted.pbrt' --res 32x24 -q ";
    ASSERT_EQ(RunPrism(scene + "-o a.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism(scene + "--exposure 1 -o b.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism(scene + "--exposure -1.5 -o c.exr", dir).exitCode, 0);
    // EXR stays linear: a tone map is not applied to it.
    ASSERT_EQ(RunPrism(scene + "--tonemap aces -o d.exr", dir).exitCode, 0);
    Image a = ReadImage((dir / "a.exr").string()), b = ReadImage((dir / "b.exr").string());
    Image c = ReadImage((dir / "c.exr").string()), d = ReadImage((dir / "d.exr").string());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    const float s = std::exp2(-1.5f);
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        ASSERT_EQ(b.pixels[i], 2 * a.pixels[i]) << i;
        ASSERT_EQ(c.pixels[i], a.pixels[i] * s) << i;
    }
    EXPECT_EQ(d.pixels, a.pixels);
}

TEST(OutputCli, DefaultToneMapFollowsTheSceneFormat) {
    fs::path dir = TempDir("defaults");
    auto pixels = [&](const std::string &args, const std::string &out) {
        RunResult r = RunPrism("render " + args + " --res 24x18 --spp 1 -q -o " + out, dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        ReadImageOptions ro;
        ro.encoding = ReadImageOptions::Encoding::Linear;  // the 8-bit codes / 255
        return ReadImage((dir / out).string(), ro).pixels;
    };
    // pbrt: none (clamp), as pbrt-v3.
    std::string pbrt = "'" + Source + "/scenes/whitted.pbrt'";
    EXPECT_EQ(pixels(pbrt, "p.png"), pixels(pbrt + " --tonemap none", "pn.png"));
    EXPECT_NE(pixels(pbrt, "p.png"), pixels(pbrt + " --tonemap neutral", "pk.png"));
    // OBJ and glTF: neutral.
    Write(dir / "sphere.obj", ObjSphere());
    EXPECT_EQ(pixels("sphere.obj", "o.png"), pixels("sphere.obj --tonemap neutral", "on.png"));
    EXPECT_NE(pixels("sphere.obj", "o.png"), pixels("sphere.obj --tonemap none", "onn.png"));
    std::string gltf = "'" + Source + "/tests/fuzz/corpus/gltf/triangle.gltf'";
    EXPECT_EQ(pixels(gltf, "g.png"), pixels(gltf + " --tonemap neutral", "gn.png"));
    EXPECT_NE(pixels(gltf, "g.png"), pixels(gltf + " --tonemap none", "gnn.png"));
    RunResult r = RunPrism("render sphere.obj --res 24x18 --spp 1 --no-progress -o s.png", dir);
    EXPECT_NE(r.err.find("tone map neutral"), std::string::npos) << r.err;
}

// An OBJ lit by an emitter of its own comes in arbitrary units: its 8-bit output is exposed
// automatically (the log-average luminance of the lit pixels to 0.18); EXR stays linear unless
// --exposure auto is asked for; a pbrt scene and a scene under the studio rig are not touched.
TEST(OutputCli, AutoExposureForObjEmitters) {
    fs::path dir = TempDir("autoexposure");
    Write(dir / "lamp.mtl",
          "newmtl lamp\nKd 0 0 0\nKe 0.02 0.02 0.02\nnewmtl white\nKd 0.8 0.8 0.8\n");
    Write(dir / "lamp.obj", "mtllib lamp.mtl\nusemtl white\n" + ObjSphere() +
                                "usemtl lamp\nv -1 2 -1\nv 1 2 -1\nv 1 2 1\nv -1 2 1\n"
                                "f -4 -3 -2 -1\n");
    auto render = [&](const std::string &extra, const std::string &out) {
        RunResult r = RunPrism(
            "render lamp.obj --res 32x24 --spp 2 --no-progress -o " + out + " " + extra, dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return r.err;
    };
    std::string err = render("", "auto.png");
    EXPECT_NE(err.find("EV (auto)"), std::string::npos) << err;
    render("--exposure 0", "zero.png");
    ReadImageOptions ro;
    ro.encoding = ReadImageOptions::Encoding::Linear;
    Image a = ReadImage((dir / "auto.png").string(), ro);
    Image z = ReadImage((dir / "zero.png").string(), ro);
    EXPECT_GT(MeanLuminance(a, 0, 32, 0, 24), 4 * MeanLuminance(z, 0, 32, 0, 24));
    // EXR: linear by default, auto only when asked.
    render("", "lin.exr");
    render("--exposure 0", "lin0.exr");
    render("--exposure auto", "auto.exr");
    Image l = ReadImage((dir / "lin.exr").string()), l0 = ReadImage((dir / "lin0.exr").string());
    Image ae = ReadImage((dir / "auto.exr").string());
    EXPECT_EQ(l.pixels, l0.pixels);
    const float scale = std::exp2(AutoExposureEV(l));
    ASSERT_EQ(ae.pixels.size(), l.pixels.size());
    for (size_t i = 0; i < l.pixels.size(); i += 97)
        EXPECT_FLOAT_EQ(ae.pixels[i], l.pixels[i] * scale);
    // The studio rig (no emitter) and pbrt scenes keep exposure 0.
    Write(dir / "plain.obj", ObjSphere());
    RunResult r = RunPrism("render plain.obj --res 16x12 --spp 1 --no-progress -o p.png", dir);
    EXPECT_EQ(r.err.find("(auto)"), std::string::npos) << r.err;
    r = RunPrism("render '" + Source + "/scenes/whitted.pbrt' --res 16x12 --no-progress -o w.png",
                 dir);
    EXPECT_EQ(r.err.find("(auto)"), std::string::npos) << r.err;
    // A bad value is a usage error.
    r = RunPrism("render lamp.obj --exposure bright -o x.png", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("must be auto or a number of EV"), std::string::npos) << r.err;
}

// A uniform environment of radiance L over a white Lambertian sphere (its own light replaced):
// every pixel, sphere or background, is L; in the PNG, the operator applied to L.
TEST(OutputCli, FurnaceUnderAUniformEnvironment) {
    fs::path dir = TempDir("furnace");
    Write(dir / "sphere.pbrt", SphereScene());
    ASSERT_EQ(RunPrism("render sphere.pbrt -q --env 0.5,0.25,1 -o f.exr", dir).exitCode, 0);
    Image f = ReadImage((dir / "f.exr").string());
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            RGB c = f.GetRGB(x, y);
            ASSERT_NEAR(c.r, 0.5, 1e-4) << x << "," << y;
            ASSERT_NEAR(c.g, 0.25, 1e-4) << x << "," << y;
            ASSERT_NEAR(c.b, 1.0, 1e-4) << x << "," << y;
        }
    // add: the point light shines too.
    ASSERT_EQ(
        RunPrism("render sphere.pbrt -q --env 0.5,0.25,1 --env-mode add -o a.exr", dir).exitCode,
        0);
    Image a = ReadImage((dir / "a.exr").string());
    EXPECT_GT(a.GetRGB(12, 10).g, 0.25 + 0.1);
    EXPECT_NEAR(a.GetRGB(0, 0).g, 0.25, 1e-4);  // background: the environment alone

    for (const char *op : {"neutral", "aces", "filmic", "none"}) {
        std::string out = std::string(op) + ".png";
        RunResult r = RunPrism(
            "render sphere.pbrt -q --env 2,0.5,0.1 --tonemap " + std::string(op) + " -o " + out,
            dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        ToneMap tm;
        ASSERT_TRUE(ParseToneMap(op, &tm));
        RGB want = ApplyToneMap(tm, RGB(2.f, 0.5f, 0.1f));
        ReadImageOptions ro;
        ro.encoding = ReadImageOptions::Encoding::Linear;
        Image png = ReadImage((dir / out).string(), ro);
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(std::lround(png.At(12, 12, c) * 255), LinearToSrgb8(want[c])) << op << c;
    }
}

TEST(OutputCli, FilmExposureAndToneMapExtension) {
    fs::path dir = TempDir("film");
    Write(dir / "plain.pbrt", SphereScene());
    Write(dir / "film.pbrt",
          SphereScene("\"float exposure\" [ 1 ] \"string tonemap\" [ \"aces\" ]"));
    auto png = [&](const std::string &args) {
        RunResult r = RunPrism("render " + args + " -q -o out.png", dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return ReadImage((dir / "out.png").string()).pixels;
    };
    EXPECT_EQ(png("film.pbrt"), png("plain.pbrt --exposure 1 --tonemap aces"));
    // The command line replaces the Film's values.
    EXPECT_EQ(png("film.pbrt --exposure 0 --tonemap none"), png("plain.pbrt"));
    Write(dir / "bad.pbrt", SphereScene("\"string tonemap\" [ \"reinhard\" ]"));
    RunResult bad = RunPrism("render bad.pbrt -q -o bad.png", dir);
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("bad.pbrt:3:"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("tonemap"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad.png"));
}

// A light-less OBJ gets the studio rig: three lights, a well-lit model on a dim background.
TEST(LightingCli, LightLessObjGetsTheStudioRig) {
    fs::path dir = TempDir("rig");
    Write(dir / "sphere.obj", ObjSphere());
    RunResult info = RunPrism("info sphere.obj", dir);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("lights:     3 (distant 2, infinite 1)"), std::string::npos)
        << info.out;
    RunResult r = RunPrism("render sphere.obj --res 48x48 --spp 4 --no-progress -o r.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const size_t effects = r.err.find("effects: ");
    ASSERT_NE(effects, std::string::npos) << r.err;
    EXPECT_NE(r.err.substr(effects, r.err.find('\n', effects) - effects).find("environment"),
              std::string::npos)
        << r.err;
    Image img = ReadImage((dir / "r.exr").string());
    double mean = MeanLuminance(img, 0, 48, 0, 48);
    EXPECT_GT(mean, 0.15);
    EXPECT_LT(mean, 0.8);
    double centre = MeanLuminance(img, 20, 28, 16, 24);  // the model (default material)
    double corner = MeanLuminance(img, 0, 4, 0, 4);      // the background: the environment
    EXPECT_NEAR(corner, 0.15, 1e-3);
    EXPECT_GT(centre, 0.25);
    EXPECT_LT(centre, 1.0);
}

// An environment map with a bright patch at the right (+x, u = 3/4) lights the sphere's right
// side; turned by 180 degrees, its left. A bright top row lights the top.
TEST(LightingCli, EnvironmentMapAndRotation) {
    fs::path dir = TempDir("envmap");
    Write(dir / "sphere.obj", ObjSphere());
    Image side(8, 4, 3), top(8, 4, 3);
    for (int y = 1; y <= 2; ++y)
        for (int x = 5; x <= 6; ++x) side.SetRGB(x, y, RGB(50.f));
    for (int x = 0; x < 8; ++x) top.SetRGB(x, 0, RGB(20.f));
    WriteImage((dir / "side.exr").string(), side);
    WriteImage((dir / "side.hdr").string(), side);
    WriteImage((dir / "top.exr").string(), top);
    auto render = [&](const std::string &args) {
        RunResult r =
            RunPrism("render sphere.obj --res 48x48 --spp 4 -q " + args + " -o e.exr", dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return ReadImage((dir / "e.exr").string());
    };
    Image right = render("--env side.exr");
    EXPECT_GT(MeanLuminance(right, 24, 48, 0, 48), 3 * MeanLuminance(right, 0, 24, 0, 48));
    Image left = render("--env side.exr --env-rotate 180");
    EXPECT_GT(MeanLuminance(left, 0, 24, 0, 48), 3 * MeanLuminance(left, 24, 48, 0, 48));
    // -90 (clockwise seen from above): the patch turns from +x to +z, behind the camera, and
    // lights the sphere's front evenly.
    Image front = render("--env side.exr --env-rotate -90");
    double fl = MeanLuminance(front, 0, 24, 0, 48), fr = MeanLuminance(front, 24, 48, 0, 48);
    EXPECT_NEAR(fl / fr, 1.0, 0.35);
    EXPECT_GT(MeanLuminance(front, 20, 28, 20, 28), 2 * MeanLuminance(right, 20, 28, 20, 28));
    Image up = render("--env top.exr");
    EXPECT_GT(MeanLuminance(up, 0, 48, 0, 24), 3 * MeanLuminance(up, 0, 48, 24, 48));
    // .hdr is read through OpenImageIO; the same map gives the same light.
    Image hdr = render("--env side.hdr");
    EXPECT_NEAR(MeanLuminance(hdr, 24, 48, 0, 48), MeanLuminance(right, 24, 48, 0, 48),
                1e-3 * MeanLuminance(right, 24, 48, 0, 48));
}

TEST(LightingCli, BadEnvironmentIsAnErrorBeforeAnyOutput) {
    fs::path dir = TempDir("badenv");
    Write(dir / "sphere.pbrt", SphereScene());
    Write(dir / "garbage.exr", "this is not an OpenEXR file\n");
    struct Case {
        std::string args, message;
    };
    for (const Case &c : std::vector<Case>{
             {"--env missing.exr", "does not exist"},
             {"--env 1,2", "--env expects"},
             {"--env 1,2,3,4", "--env expects"},
             {"--env 1,nan,1", "--env expects"},
             {"--env -1,0,0", "--env expects"},
             {"--env 1,x,1", "--env expects"},
             {"--env sky.png", "--env expects"},
             {"--env-rotate 10", "need --env"},
             {"--env-mode add", "need --env"},
             {"--env 1,1,1 --env-mode both", "env-mode"},
             {"--env garbage.exr", "garbage.exr"},
             {"--tonemap reinhard", "tonemap"},
             {"--exposure 100", "exposure"},
         }) {
        RunResult r = RunPrism("render sphere.pbrt " + c.args + " -o out.png", dir);
        EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << c.args;
    }
    // batch checks --env once, before any scene.
    RunResult b = RunPrism("batch sphere.pbrt -o out --env missing.hdr", dir);
    EXPECT_EQ(b.exitCode, 2) << b.err;
    EXPECT_NE(b.err.find("does not exist"), std::string::npos) << b.err;
}

TEST(LightingCli, BatchPassesExposureAndEnvironmentOn) {
    fs::path dir = TempDir("batch");
    fs::create_directories(dir / "scenes");
    Write(dir / "scenes" / "sphere.pbrt", SphereScene());
    RunResult r =
        RunPrism("batch scenes -o out --format exr --quiet --exposure 1 --env 0.25,0.25,0.25", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image img = ReadImage((dir / "out" / "scenes_sphere.exr").string());
    for (float v : img.pixels) ASSERT_NEAR(v, 0.5, 1e-4);
}

// --env is the operator's choice, not the scene's: a map outside a --confine'd scene folder is
// read, while the scene's own files stay confined (an image texture beside the map is refused).
TEST(LightingCli, EnvironmentMapIsNotConfinedWithTheScene) {
    fs::path dir = TempDir("envconfine");
    fs::create_directories(dir / "scene");
    Write(dir / "scene" / "sphere.obj", ObjSphere());
    Image side(8, 4, 3);
    for (int y = 1; y <= 2; ++y)
        for (int x = 5; x <= 6; ++x) side.SetRGB(x, y, RGB(50.f));
    WriteImage((dir / "side.exr").string(), side);
    RunResult r =
        RunPrism("render scene/sphere.obj --confine --res 16x16 -q --env side.exr -o e.exr", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "e.exr"));
    Write(dir / "scene" / "tex.pbrt", R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
Film "image" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
WorldBegin
Texture "t" "spectrum" "imagemap" "string filename" "../other.exr"
Material "matte" "texture Kd" "t"
Shape "sphere"
WorldEnd
)");
    r = RunPrism("render scene/tex.pbrt --confine -q --env side.exr -o f.exr", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("scene/tex.pbrt:5:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("outside the confined folder"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "f.exr"));
}

}  // namespace
}  // namespace prism
