// The bidirectional path tracer (Integrator "bdpt", render/bdpt_integrator.h): a furnace with a
// closed form (also cropped, where light tracing's importance is normalized over the crop),
// agreement with Prism's path tracer under every kind of light, a room lit through a small
// opening where it beats the path tracer at equal samples, and the same image for any thread
// count and through FrameTiles (prism-mpi's merge), splats included.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

RenderScene BuildText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return BuildSceneText("bdpt", name, text, opts);
}

// The camera inside a closed sphere of albedo a whose inside emits 1: Le (1 + a + ... +
// a^maxdepth).
std::string Furnace(float a, int maxDepth, int spp, const std::string &film = "") {
    const std::string kd = std::to_string(a);
    return "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [12] " + film +
           "\nSampler \"stratified\" \"integer xsamples\" [" + std::to_string(spp) +
           "] \"integer ysamples\" [1]\nIntegrator \"bdpt\" \"integer maxdepth\" [" +
           std::to_string(maxDepth) +
           "]\nCamera \"perspective\" \"float fov\" [70]\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
           "Material \"matte\" \"rgb Kd\" [" +
           kd + " " + kd + " " + kd + "]\nShape \"sphere\" \"float radius\" [3]\nAttributeEnd\n";
}

TEST(Bdpt, FurnaceIsTheGeometricSeries) {
    for (int depth : {0, 1, 4}) {
        const float a = 0.6f;
        const double expected = (1 - std::pow(double(a), depth + 1)) / (1 - a);
        RenderScene scene = BuildText("furnace" + std::to_string(depth), Furnace(a, depth, 64));
        EXPECT_STREQ(scene.IntegratorName(), "bdpt");
        EXPECT_NEAR(MeanValue(RenderWithSeed(scene, 0)), expected, 3e-3 * expected)
            << "maxdepth " << depth;
    }
    // A crop window: light tracing lands only on the crop's pixels, normalized over them.
    RenderScene crop =
        BuildText("furnace_crop", Furnace(0.6f, 2, 64, "\"float cropwindow\" [0.25 0.75 0 0.5]"));
    EXPECT_NEAR(MeanValue(RenderWithSeed(crop, 0)), 1.96, 3e-3 * 1.96);
}

// A diffuse box with a sphere and a box in it, lit by `light`, viewed from inside.
std::string Room(const std::string &integrator, const std::string &light, int spp,
                 const std::string &ceiling, bool glass = true) {
    return "LookAt 1.6 1.4 1.8  -0.8 1.2 -1.6  0 1 0\nCamera \"perspective\" \"float fov\" [70]\n"
           "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"
           "Sampler \"random\" \"integer pixelsamples\" [" +
           std::to_string(spp) + "]\n" + integrator + "\nWorldBegin\n" + light +
           "\nMaterial \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" + ceiling +
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3  4 5 6 4 6 7  8 9 10 8 10 11"
           "  12 13 14 12 14 15  16 17 18 16 18 19]\n"
           "  \"point P\" [-2 0 -2 2 0 -2 2 0 2 -2 0 2   -2 0 -2 2 0 -2 2 4 -2 -2 4 -2"
           "   -2 0 2 2 0 2 2 4 2 -2 4 2   2 0 -2 2 0 2 2 4 2 2 4 -2   -2 0 -2 -2 0 2 -2 4 2"
           " -2 4 -2]\n"
           "AttributeBegin\nMaterial \"plastic\" \"rgb Kd\" [0.1 0.25 0.6] \"rgb Ks\" [0.4 0.4 0.4]"
           " \"float roughness\" [0.05]\nTranslate -0.6 0.6 -0.9\nShape \"sphere\" \"float "
           "radius\" [0.6]\nAttributeEnd\n" +
           (glass ? "AttributeBegin\nMaterial \"glass\"\nTranslate 0.8 0.4 -0.4\nShape "
                    "\"sphere\" \"float radius\" [0.4]\nAttributeEnd\n"
                  : "");
}

const char *Ceiling =
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-2 4 -2 2 4 -2 2 4 2 -2 4 2]\n";

// The ceiling around an opening of half-width h at its centre, and a quad light above it.
std::string Opening(float h) {
    const std::string a = std::to_string(-h), b = std::to_string(h);
    return "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3 4 5 6 4 6 7 8 9 10 8 10 11 "
           "12 13 14 12 14 15]\n  \"point P\" [-2 4 -2 2 4 -2 2 4 " +
           a + " -2 4 " + a + "  -2 4 " + b + " 2 4 " + b + " 2 4 2 -2 4 2  -2 4 " + a + " " + a +
           " 4 " + a + " " + a + " 4 " + b + " -2 4 " + b + "  " + b + " 4 " + a + " 2 4 " + a +
           " 2 4 " + b + " " + b + " 4 " + b + "]\n";
}

const char *LightAbove =
    "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [40 40 40]\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-0.5 4.5 -0.5 0.5 4.5 -0.5 0.5 4.5 0.5 -0.5 4.5 0.5]\nAttributeEnd\n";

TEST(Bdpt, AgreesWithPathUnderEveryLight) {
    // Each light type, in a room the path tracer converges on: the means agree, and the images
    // differ by no more than two path renders with different seeds do (their noise).
    const std::pair<const char *, std::string> lights[] = {
        {"area",
         "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4]\n"
         "Translate 0 3.2 0\nShape \"sphere\" \"float radius\" [0.3]\nAttributeEnd"},
        {"point", "LightSource \"point\" \"point from\" [0 3 0] \"rgb I\" [4 4 4]"},
        {"spot",
         "LightSource \"spot\" \"point from\" [0 3.5 0] \"point to\" [0 0 0] \"rgb I\" "
         "[10 10 10] \"float coneangle\" [40]"},
    };
    for (const auto &[name, light] : lights) {
        RenderScene bdpt = BuildText(std::string("agree_bdpt_") + name,
                                     Room("Integrator \"bdpt\"", light, 64, Ceiling));
        RenderScene path = BuildText(std::string("agree_path_") + name,
                                     Room("Integrator \"path\"", light, 64, Ceiling));
        const Image b = RenderWithSeed(bdpt, 0), p1 = RenderWithSeed(path, 0),
                    p2 = RenderWithSeed(path, 1);
        EXPECT_NEAR(MeanValue(b), MeanValue(p1), 0.015 * MeanValue(p1)) << name;
        EXPECT_LT(RelL1(b, p1), 1.2 * RelL1(p2, p1)) << name;
    }
}

TEST(Bdpt, AgreesWithPathUnderTheSkyAndTheSun) {
    // Infinite and distant lights: a sphere and a box on a plane under a sky and a sun.
    const std::string scene =
        "LookAt 0 2 6  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [40]\n"
        "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"
        "Sampler \"random\" \"integer pixelsamples\" [64]\nINTEGRATOR\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [0.4 0.5 0.7]\n"
        "LightSource \"distant\" \"point from\" [1 3 2] \"point to\" [0 0 0] \"rgb L\" [2 2 2]\n"
        "Material \"matte\" \"rgb Kd\" [0.6 0.6 0.6]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
        "  \"point P\" [-4 0 -4 4 0 -4 4 0 4 -4 0 4]\n"
        "Material \"plastic\" \"rgb Kd\" [0.5 0.2 0.1] \"float roughness\" [0.1]\n"
        "Translate 0 0.7 0\nShape \"sphere\" \"float radius\" [0.7]\n";
    auto with = [&](const std::string &integrator) {
        std::string s = scene;
        return s.replace(s.find("INTEGRATOR"), 10, integrator);
    };
    RenderScene bdpt = BuildText("sky_bdpt", with("Integrator \"bdpt\""));
    RenderScene path = BuildText("sky_path", with("Integrator \"path\""));
    const Image b = RenderWithSeed(bdpt, 0), b2 = RenderWithSeed(bdpt, 1),
                p1 = RenderWithSeed(path, 0), p2 = RenderWithSeed(path, 1);
    EXPECT_NEAR(MeanValue(b), MeanValue(p1), 0.015 * MeanValue(p1));
    // Apart by no more than the noisier of the two is from itself (here bdpt: the path
    // tracer's light choice splits the samples evenly between the sky and the sun).
    EXPECT_LT(RelL1(b, p1), 1.2 * std::max(RelL1(p2, p1), RelL1(b2, b)));
}

TEST(Bdpt, BeatsPathThroughASmallOpening) {
    // The room lit only through a 0.3 x 0.3 opening in its ceiling: at equal samples per pixel,
    // bdpt's noise (two renders with different seeds apart) is below the path tracer's (0.72
    // of it when written: half the variance), and both converge to the same mean.
    RenderScene bdpt =
        BuildText("gap_bdpt", Room("Integrator \"bdpt\"", LightAbove, 16, Opening(0.15f), false));
    RenderScene path =
        BuildText("gap_path", Room("Integrator \"path\"", LightAbove, 16, Opening(0.15f), false));
    const Image b1 = RenderWithSeed(bdpt, 0), b2 = RenderWithSeed(bdpt, 1);
    const Image p1 = RenderWithSeed(path, 0), p2 = RenderWithSeed(path, 1);
    const double bdptNoise = RelL1(b1, b2), pathNoise = RelL1(p1, p2);
    EXPECT_LT(bdptNoise, 0.8 * pathNoise) << "bdpt " << bdptNoise << ", path " << pathNoise;
    const double mb = (MeanValue(b1) + MeanValue(b2)) / 2, mp = (MeanValue(p1) + MeanValue(p2)) / 2;
    EXPECT_NEAR(mb, mp, 0.05 * mp);
}

TEST(Bdpt, SameImageForAnyThreadCountAndThroughFrameTiles) {
    RenderScene scene =
        BuildText("threads", Room("Integrator \"bdpt\"", LightAbove, 4, Opening(0.3f)));
    Image one = RenderOnThreads(scene, 1), two = RenderOnThreads(scene, 2);
    EXPECT_TRUE(one.pixels == two.pixels);
    EXPECT_GT(MeanValue(one), 0);
    // prism-mpi's path: tiles rendered apart, merged in order, splats with them.
    RenderStats stats;
    FrameTiles frame(scene);
    std::vector<FilmTile> tiles;
    RayCounters rays;
    frame.RenderTiles(0, frame.NumTiles(), &tiles, &rays);
    for (const FilmTile &t : tiles) frame.MergeNext(t);
    const Image merged = frame.Finish(&stats);
    EXPECT_TRUE(merged.pixels == one.pixels);
    // A render cancelled never: the packet path (a cancel flag that stays 0) sorts its splats
    // into the tile's order, so it is the same image too.
    volatile int never = 0;
    const Image packets = Render(scene, &stats, {}, &never);
    EXPECT_TRUE(packets.pixels == one.pixels);
}

// shadows-spot: a spot light exactly at the apex of its closed lamp cone, which glows and, as
// a blended emitter, casts no shadow (gltf_reader.cpp). bdpt (and sppm as shipped) must agree
// with path:
// - the cone made opaque (alphaMode OPAQUE, so it casts shadows): no light leaves it, all
//   three see the cone's own dim emission. The light's rays once hit the cone at t = 0, at
//   the apex, and scattered out through its outer side: bdpt was 160 times brighter.
// - as shipped: the light passes the cone on light subpaths and photons as on shadow rays
//   (Accel::Intersect's mask). Before, they hit it from inside and bdpt's connections then
//   let the light trapped in it out: bdpt was 3 (then 6) times brighter than path.
TEST(Bdpt, ALightOnAShadowlessOrOpaqueSurfaceAgreesWithPath) {
    const fs::path shared = fs::path(PRISM_SHARED_DIR) / "scenes" / "gltf-shadows-spot";
    PRISM_REQUIRE_SHARED(shared);
    const fs::path dir = test::ScratchDir("bdpt_apex");
    std::ifstream in(shared / "shadows-spot.gltf");
    const std::string shipped((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
    std::string opaque = shipped;
    const size_t at = opaque.find("\"BLEND\"");
    ASSERT_NE(at, std::string::npos);
    opaque.replace(at, 7, "\"OPAQUE\"");
    fs::copy_file(shared / "shadows-spot.bin", dir / "shadows-spot.bin",
                  fs::copy_options::overwrite_existing);
    for (const auto &[name, json] : {std::pair{"opaque", opaque}, std::pair{"shipped", shipped}}) {
        SCOPED_TRACE(name);
        const std::string file = test::WriteTestFile(dir / (std::string(name) + ".gltf"), json);
        double mean[3];
        const char *integrators[3] = {"path", "bdpt", "sppm"};
        for (int i = 0; i < 3; ++i) {
            BuildSettings opts;
            opts.integrator = integrators[i];
            opts.resolution = {48, 27};
            opts.spp = 16;
            Diagnostics diag(false);
            SceneDescription desc = LoadScene(file, diag);
            mean[i] = MeanValue(RenderWithSeed(BuildRenderScene(desc, opts, diag), 0));
        }
        EXPECT_GT(mean[0], 0);
        EXPECT_NEAR(mean[1], mean[0], 0.2 * mean[0]) << "bdpt";
        // (Made opaque, the cone is thin-walled, and sppm's photons inside it reach the
        // visible points outside within the search radius, as in pbrt-v3: that bias is
        // sppm's own, not the light's.)
        if (std::string(name) == "shipped") EXPECT_NEAR(mean[2], mean[0], 0.2 * mean[0]) << "sppm";
    }
}

}  // namespace
}  // namespace prism
