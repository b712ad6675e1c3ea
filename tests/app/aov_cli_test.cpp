// `prism render --aov` and Film "aovs": AOV layers beside RGB in one multi-channel EXR.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/bsdf_file.h"
#include "support/process.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

struct Exr {
    int width = 0, height = 0;
    std::vector<std::string> names;  // in the file's (alphabetical) order
    std::map<std::string, std::vector<float>> channels;
    std::map<std::string, std::string> strings;  // string attributes
};

Exr ReadExr(const fs::path &path) {
    Imf::InputFile in(path.c_str());
    Exr e;
    const Imath::Box2i dw = in.header().dataWindow();
    e.width = dw.max.x - dw.min.x + 1;
    e.height = dw.max.y - dw.min.y + 1;
    Imf::FrameBuffer fb;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
        e.names.push_back(it.name());
        e.channels[it.name()].resize(size_t(e.width) * size_t(e.height));
    }
    for (auto &[name, v] : e.channels)
        fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(v.data()), sizeof(float),
                                   sizeof(float) * size_t(e.width)));
    for (auto it = in.header().begin(); it != in.header().end(); ++it)
        if (const auto *s = dynamic_cast<const Imf::StringAttribute *>(&it.attribute()))
            e.strings[it.name()] = s->value();
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return e;
}

// A disk of radius 100 in the plane z = 5, seen straight on from the origin.
const char *const kPlane = R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 40
Film "image" "integer xresolution" 16 "integer yresolution" 12
Sampler "random" "integer pixelsamples" 1
WorldBegin
LightSource "point" "point from" [0 0 0]
Shape "disk" "float height" 5 "float radius" 100
WorldEnd
)";

// Two spheres overlapping in view (the nearer one is a mirror) over a matte floor, 16 spp and
// a wide Gaussian filter: edges blend in the beauty but never in the ids.
const char *const kSpheres = R"(LookAt 0 1 -6  0 0 0  0 1 0
Camera "perspective" "float fov" 35
Film "image" "integer xresolution" 40 "integer yresolution" 30
Sampler "halton" "integer pixelsamples" 16
PixelFilter "gaussian" "float xwidth" 2 "float ywidth" 2
Integrator "whitted"
WorldBegin
LightSource "point" "point from" [2 5 -5] "rgb I" [30 30 30]
Material "matte" "rgb Kd" [0.2 0.4 0.6]
AttributeBegin Translate 0.6 0 0 Shape "sphere" "float radius" 1 AttributeEnd
AttributeBegin Material "mirror" Translate -0.5 0 -1 Shape "sphere" "float radius" 0.8 AttributeEnd
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3]
  "point P" [-10 -1 -10  10 -1 -10  10 -1 10  -10 -1 10]
WorldEnd
)";

TEST(AovCli, ChannelNamesDepthAndPositionOfAPlane) {
    fs::path dir = TempDir("plane");
    std::ofstream(dir / "plane.pbrt") << kPlane;
    RunResult r = RunPrism("render plane.pbrt -o out.exr --aov all -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Exr e = ReadExr(dir / "out.exr");
    std::set<std::string> names(e.names.begin(), e.names.end());
    for (const char *n : {"R",           "G",           "B",          "Z",          "P.X",
                          "P.Y",         "P.Z",         "N.X",        "N.Y",        "N.Z",
                          "Ng.X",        "Ng.Y",        "Ng.Z",       "albedo.R",   "albedo.G",
                          "albedo.B",    "uv.U",        "uv.V",       "shape_id",   "primitive_id",
                          "instance_id", "material_id", "direct.R",   "direct.G",   "direct.B",
                          "indirect.R",  "indirect.G",  "indirect.B", "variance.R", "variance.G",
                          "variance.B"})
        EXPECT_TRUE(names.count(n)) << n;
    ASSERT_EQ(e.width, 16);
    ASSERT_EQ(e.height, 12);
    const double tanHalf = std::tan(20.0 * M_PI / 180.0), aspect = 16.0 / 12.0;
    for (int y = 0; y < e.height; ++y)
        for (int x = 0; x < e.width; ++x) {
            size_t i = size_t(y) * size_t(e.width) + size_t(x);
            // Depth along the camera axis and the plane's z: exact.
            EXPECT_EQ(e.channels["Z"][i], 5.f);
            EXPECT_EQ(e.channels["P.Z"][i], 5.f);
            // x and y of the pixel-centre ray's hit (fov on the shorter axis, y).
            double sx = ((x + 0.5) / 16 * 2 - 1) * aspect * tanHalf;
            double sy = (1 - (y + 0.5) / 12 * 2) * tanHalf;
            EXPECT_NEAR(e.channels["P.X"][i], 5 * sx, 1e-5);
            EXPECT_NEAR(e.channels["P.Y"][i], 5 * sy, 1e-5);
            EXPECT_EQ(std::abs(e.channels["Ng.Z"][i]), 1.f);
            EXPECT_EQ(e.channels["shape_id"][i], 1.f);
            EXPECT_EQ(e.channels["material_id"][i], 1.f);  // the default matte
            EXPECT_NEAR(e.channels["albedo.G"][i], 0.5f, 1e-6);
        }
    EXPECT_NE(e.strings["prism/shape_id/manifest"].find("\"1\": \"disk at plane.pbrt:7:1\""),
              std::string::npos)
        << e.strings["prism/shape_id/manifest"];
    // oiiotool lists the same channels, when it is installed.
    if (std::system("oiiotool --help >/dev/null 2>&1") == 0) {
        std::string cmd = "oiiotool --info -v '" + (dir / "out.exr").string() + "' > '" +
                          (dir / "info.txt").string() + "'";
        ASSERT_EQ(std::system(cmd.c_str()), 0);
        std::string info = test::ReadFile(dir / "info.txt");
        for (const char *n : {"Z", "P.X", "N.Y", "albedo.B", "uv.U", "shape_id", "variance.R"})
            EXPECT_NE(info.find(n), std::string::npos) << n << "\n" << info;
    }
}

// The albedo AOV of the plane under `material`, rendered in the scratch folder `dir` (which
// holds the files the material reads).
Exr PlaneAlbedo(const fs::path &dir, const std::string &material) {
    std::string scene = kPlane;
    scene.replace(scene.find("Shape \"disk\""), 0, material + "\n");
    std::ofstream(dir / "plane.pbrt") << scene;
    RunResult r = RunPrism("render plane.pbrt -o out.exr --aov albedo -q", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return ReadExr(dir / "out.exr");
}

// A coateddiffuse's diffuse colour is its base's reflectance, under the coat.
TEST(AovCli, AlbedoOfACoatedDiffuseIsItsBaseReflectance) {
    Exr e = PlaneAlbedo(TempDir("coated"),
                        "Material \"coateddiffuse\" \"rgb reflectance\" [0.2 0.4 0.6]");
    ASSERT_GT(e.width, 0);
    for (size_t i = 0; i < size_t(e.width) * size_t(e.height); ++i) {
        ASSERT_NEAR(e.channels["albedo.R"][i], 0.2f, 1e-6);
        ASSERT_NEAR(e.channels["albedo.B"][i], 0.6f, 1e-6);
    }
}

// A tabulated BSDF has no diffuse colour: its albedo is the light it scatters of what arrives
// from the camera, here a Lambertian table's reflectance.
TEST(AovCli, AlbedoOfATabulatedBsdfIsItsDirectionalAlbedo) {
    const fs::path dir = TempDir("fourier");
    std::ofstream(dir / "lambert.bsdf", std::ios::binary) << LambertianFourierBsdf(0.6f);
    Exr e = PlaneAlbedo(dir, "Material \"fourier\" \"string bsdffile\" \"lambert.bsdf\"");
    ASSERT_GT(e.width, 0);
    for (size_t i = 0; i < size_t(e.width) * size_t(e.height); ++i)
        ASSERT_NEAR(e.channels["albedo.G"][i], 0.6f, 2e-3);
}

TEST(AovCli, IdsAreIntegersAtEdgesAndTheBeautyIsUnchanged) {
    fs::path dir = TempDir("spheres");
    std::ofstream(dir / "s.pbrt") << kSpheres;
    RunResult plain = RunPrism("render s.pbrt -o plain.exr -q", dir);
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    RunResult r = RunPrism(
        "render s.pbrt -o aov.exr -q --aov shape_id,primitive_id,instance_id,material_id,"
        "direct,indirect,variance,depth",
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Exr a = ReadExr(dir / "plain.exr"), b = ReadExr(dir / "aov.exr");
    EXPECT_EQ(a.names, (std::vector<std::string>{"B", "G", "R"}));
    for (const char *c : {"R", "G", "B"}) EXPECT_EQ(a.channels[c], b.channels[c]) << c;
    std::set<float> shapes;
    for (const char *c : {"shape_id", "primitive_id", "instance_id", "material_id"})
        for (float v : b.channels[c]) {
            EXPECT_EQ(v, std::round(v)) << c;
            if (std::string(c) == "shape_id") shapes.insert(v);
        }
    // Background, both spheres and the floor.
    EXPECT_EQ(shapes, (std::set<float>{0, 1, 2, 3}));
    // direct + indirect is the beauty; the mirror sphere has indirect light, the matte not.
    double indirect = 0;
    for (size_t i = 0; i < b.channels["R"].size(); ++i) {
        for (const char *c : {"R", "G", "B"})
            EXPECT_NEAR(b.channels[std::string("direct.") + c][i] +
                            b.channels[std::string("indirect.") + c][i],
                        b.channels[c][i], 1e-4 * (1 + b.channels[c][i]));
        indirect += b.channels["indirect.R"][i];
        EXPECT_GE(b.channels["variance.G"][i], 0.f);
    }
    EXPECT_GT(indirect, 0);
}

TEST(AovCli, AovNeedsAnExrOutputAndKnownNames) {
    fs::path dir = TempDir("usage");
    std::ofstream(dir / "plane.pbrt") << kPlane;
    RunResult r = RunPrism("render plane.pbrt -o out.png --aov depth", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("must end in .exr"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    r = RunPrism("render plane.pbrt -o out.exr --aov depth,colour", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown AOV \"colour\""), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(AovCli, FilmAovsInTheScene) {
    fs::path dir = TempDir("film");
    std::string scene = kPlane;
    scene.replace(scene.find("Film \"image\""), 12, "Film \"image\" \"string aovs\" \"depth,N\"");
    std::ofstream(dir / "plane.pbrt") << scene;
    RunResult r = RunPrism("render plane.pbrt -o out.exr -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Exr e = ReadExr(dir / "out.exr");
    EXPECT_EQ(e.names, (std::vector<std::string>{"B", "G", "N.X", "N.Y", "N.Z", "R", "Z"}));
    // A bad name is a scene error at the parameter.
    scene.replace(scene.find("depth,N"), 7, "depth,Q");
    std::ofstream(dir / "bad.pbrt") << scene;
    r = RunPrism("render bad.pbrt -o bad.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("bad.pbrt:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("unknown AOV \"Q\""), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prism
