// The integrator interface (render/integrator.h): the registry of integrator_list.inc, the
// scene assembly's fallback for names it lacks, and pbrt-v3's ambient occlusion integrator
// against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

Built BuildText(const std::string &name, const std::string &text, int res, int spp) {
    return BuildSceneFile(WriteSceneText("integrator", name, text), SizedSettings(res, res, spp));
}

TEST(Integrator, TheRegistryNamesEachIntegratorOnce) {
    std::vector<std::string> names = IntegratorNames();
    for (const char *n : {"whitted", "distribution", "directlighting", "path", "volpath",
                          "ambientocclusion", "ao", "bdpt", "sppm", "mlt"})
        EXPECT_EQ(std::count(names.begin(), names.end(), n), 1) << n;
    EXPECT_EQ(names.size(), 10u);
}

TEST(Integrator, AnUnknownIntegratorRendersWithWhittedAndSaysWhere) {
    Built b = BuildText("nosuchintegrator.pbrt",
                        "Integrator \"nosuchintegrator\" \"integer maxdepth\" [ 3 ]\nWorldBegin\n"
                        "LightSource \"point\"\nShape \"sphere\"\nWorldEnd\n",
                        4, 1);
    EXPECT_STREQ(b.scene.IntegratorName(), "whitted");
    EXPECT_EQ(b.scene.trace.maxDepth, 3);
    bool warned = false;
    for (const Warning &w : b.warnings)
        warned |=
            w.loc.line == 1 &&
            w.message.find("\"nosuchintegrator\" is rendered with Whitted") != std::string::npos;
    EXPECT_TRUE(warned);
}

// pbrt-v4's teaching integrators render with the one whose image they converge to (path, or
// volpath for simplevolpath: delta tracking without light sampling), with their own
// parameters read (no "unused parameter" warning) and a warning that says what differs.
TEST(Integrator, PbrtV4TeachingIntegratorsRenderWithTheirStandIn) {
    const std::pair<const char *, const char *> cases[] = {{"simplepath", "path"},
                                                           {"randomwalk", "path"},
                                                           {"lightpath", "path"},
                                                           {"simplevolpath", "volpath"}};
    for (auto [type, with] : cases) {
        SCOPED_TRACE(type);
        Built b = BuildText(std::string(type) + ".pbrt",
                            "Integrator \"" + std::string(type) +
                                "\" \"integer maxdepth\" 3 \"bool samplelights\" false\n"
                                "WorldBegin\nLightSource \"point\"\nShape \"sphere\"\n",
                            4, 1);
        EXPECT_STREQ(b.scene.IntegratorName(), with);
        EXPECT_EQ(b.scene.trace.maxDepth, 3);
        std::string all;
        for (const Warning &w : b.warnings) all += w.ToString() + "\n";
        ASSERT_EQ(b.warnings.size(), 1u) << all;
        EXPECT_NE(b.warnings[0].message.find("is rendered with \"" + std::string(with) +
                                             "\": the same image"),
                  std::string::npos)
            << all;
    }
}

// A camera between a floor and a disk of radius 1 at height 1 above the point it sees: the disk
// hides the cone of half-angle 45 degrees about the normal, so ambient occlusion (the integral
// of visibility times cos over the hemisphere, pbrt-v3's convention) is pi cos^2(45) = pi / 2.
std::string DiskAbove(const std::string &integrator) {
    return "LookAt 0 0.5 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 0.5 ]\n" +
           integrator +
           "\nWorldBegin\n"
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point P\" [-50 0 -50  50 0 -50  50 0 50  -50 0 50]\n"
           "AttributeBegin\nTranslate 0 1 0\nRotate 90 1 0 0\nShape \"disk\" \"float radius\" 1\n"
           "AttributeEnd\nWorldEnd\n";
}

TEST(AmbientOcclusion, DiskAboveHidesHalfTheCosineWeightedSky) {
    for (const char *cos : {"true", "false"}) {
        SCOPED_TRACE(cos);
        Built b = BuildText("disk.pbrt",
                            DiskAbove(std::string("Integrator \"ambientocclusion\" ") +
                                      "\"integer nsamples\" 64 \"bool cossample\" " + cos),
                            1, 64);
        EXPECT_STREQ(b.scene.IntegratorName(), "ambientocclusion");
        RenderStats stats;
        const Image img = Render(b.scene, &stats);
        // 64 x 64 stratified directions per pixel.
        EXPECT_NEAR(img.GetRGB(0, 0).g, Pi / 2, 0.01 * Pi);
        EXPECT_EQ(stats.rays.shadow, 64u * 64u);
    }
}

// pbrt-v4's ambient occlusion (a file read by its rules: here its Film "rgb") is pbrt-v3's over
// pi, so that nothing occluding is 1, and its "maxdistance" ignores farther occluders: the disk
// at distance 1 to 1.41 hides half the cosine-weighted sky, and nothing within 0.9. pbrt-v4's
// own image of such a scene (a floor, a wall and two spheres, maxdistance 1.5) is within 0.08%
// of Prism's, its own noise 0.16%.
TEST(AmbientOcclusion, PbrtV4DividesByPiAndReadsMaxDistance) {
    for (const char *maxDistance : {"", "\"float maxdistance\" 0.9", "\"float maxdistance\" 2"}) {
        SCOPED_TRACE(maxDistance);
        Built b =
            BuildText("diskv4.pbrt",
                      "Film \"rgb\"\n" + DiskAbove(std::string("Integrator \"ambientocclusion\" ") +
                                                   "\"integer nsamples\" 64 " + maxDistance),
                      1, 64);
        EXPECT_EQ(b.scene.IntegratorName(), std::string("ambientocclusion"));
        const Image img = Render(b.scene, nullptr);
        const bool near = std::string(maxDistance).find("0.9") != std::string::npos;
        EXPECT_NEAR(img.GetRGB(0, 0).g, near ? 1.0 : 0.5, 0.01);
    }
}

TEST(AmbientOcclusion, AnOpenHemisphereIsPiAndAMissIsBlack) {
    // Without the disk every cosine-weighted direction escapes: each adds pi / n exactly.
    Built open = BuildText("open.pbrt",
                           "LookAt 0 0.5 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 20\n"
                           "Integrator \"ao\" \"integer nsamples\" 8\nWorldBegin\n"
                           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
                           "  \"point P\" [-50 0 -50  50 0 -50  50 0 50  -50 0 50]\nWorldEnd\n",
                           4, 2);
    const Image img = Render(open.scene, nullptr);
    for (float v : img.pixels) EXPECT_NEAR(v, Pi, 1e-5);
    Built miss = BuildText("miss.pbrt",
                           "LookAt 0 0.5 0  0 1 0  0 0 1\nCamera \"perspective\"\n"
                           "Integrator \"ao\"\nWorldBegin\nShape \"sphere\" \"float radius\" 0.1\n"
                           "WorldEnd\n",
                           4, 1);
    const Image black = Render(miss.scene, nullptr);
    for (float v : black.pixels) EXPECT_EQ(v, 0.f);
}

TEST(AmbientOcclusion, SampleCountOutOfRangeIsALocatedError) {
    try {
        BuildText("bad.pbrt", "Integrator \"ao\"\n  \"integer nsamples\" 0\nWorldBegin\nWorldEnd\n",
                  4, 1);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("bad.pbrt:2:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("nsamples 0 out of range"), std::string::npos);
    }
}

}  // namespace
}  // namespace prism
