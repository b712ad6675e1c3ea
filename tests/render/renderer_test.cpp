// The tile driver (render/renderer.h): with a cancel flag the driver renders each tile one
// camera packet at a time, reading the flag before each; the image must not change.
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "assembly/build_scene.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

// A sphere over a floor, a mirror and an area light; 37x29 leaves partial tiles and packets.
// Each test writes files of its own (`test`): ctest runs tests in parallel.
std::string Scene(const std::string &filter, const std::string &test) {
    return test::WriteTestFile(
        test::ScratchDir("renderer") / (test + "_" + filter + ".pbrt"),
        "LookAt 0 1.5 -5  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n"
        "PixelFilter \"" +
            filter +
            "\"\n"
            "WorldBegin\n"
            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 6 6 6 ]\nTranslate 0.5 3 0\n"
            "Shape \"sphere\" \"float radius\" 0.7\nAttributeEnd\n"
            "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
            "  \"point3 P\" [ -10 0 -10  10 0 -10  10 0 10  -10 0 10 ]\n"
            "AttributeBegin\nMaterial \"mirror\"\nTranslate 1.2 0.5 0\n"
            "Shape \"sphere\" \"float radius\" 0.4\nAttributeEnd\n"
            "Translate 0 0.6 0\nShape \"sphere\" \"float radius\" 0.6\nWorldEnd\n");
}

RenderScene Build(const std::string &filter, const std::string &integrator,
                  const std::string &test) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Scene(filter, test), diag);
    BuildSettings s;
    s.resolution = Vec2i(37, 29);
    s.spp = 3;
    s.integrator = integrator;
    return BuildRenderScene(desc, s, diag);
}

TEST(Renderer, ACancelFlagThatStaysDownChangesNoBit) {
    for (const char *filter : {"box", "gaussian"})
        for (const char *integrator : {"", "whitted", "path"}) {
            SCOPED_TRACE(std::string(filter) + " " + integrator);
            RenderScene scene = Build(filter, integrator, "flag_down");
            RenderStats plainStats, flagStats;
            Image plain = Render(scene, &plainStats);
            volatile int cancel = 0;
            Image flagged = Render(scene, &flagStats, {}, &cancel);
            ASSERT_EQ(plain.pixels.size(), flagged.pixels.size());
            EXPECT_EQ(std::memcmp(plain.pixels.data(), flagged.pixels.data(),
                                  plain.pixels.size() * sizeof(float)),
                      0);
            EXPECT_FALSE(flagStats.cancelled);
            EXPECT_EQ(plainStats.rays.camera, flagStats.rays.camera);
        }
}

TEST(Renderer, ARaisedCancelFlagRendersNothing) {
    RenderScene scene = Build("box", "", "flag_up");
    RenderStats stats;
    volatile int cancel = 1;
    Render(scene, &stats, {}, &cancel);
    EXPECT_TRUE(stats.cancelled);
    EXPECT_EQ(stats.rays.camera, 0u);
}

// prism-mpi's tile runs (FrameTiles) read the cancel flag as Render does: a raised flag stops
// a run within one camera packet (its workers used to render every tile they were handed to
// the end after SIGINT), and a flag that stays down changes no tile.
TEST(Renderer, FrameTilesHonourTheCancelFlag) {
    RenderScene scene = Build("box", "", "frame_tiles");
    FrameTiles frame(scene);
    const int n = frame.NumTiles();
    ASSERT_GT(n, 1);
    std::vector<FilmTile> plain, flagged;
    RayCounters plainRays, flagRays, upRays;
    EXPECT_TRUE(frame.RenderTiles(0, n, &plain, &plainRays));
    volatile int cancel = 0;
    EXPECT_TRUE(frame.RenderTiles(0, n, &flagged, &flagRays, &cancel));
    EXPECT_EQ(plainRays.camera, flagRays.camera);
    ASSERT_EQ(plain.size(), flagged.size());
    for (size_t t = 0; t < plain.size(); ++t) {
        const auto a = plain[t].Sums(), b = flagged[t].Sums();
        ASSERT_EQ(a.size_bytes(), b.size_bytes());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size_bytes()), 0) << "tile " << t;
    }
    cancel = 1;
    std::vector<FilmTile> stopped;
    EXPECT_FALSE(frame.RenderTiles(0, n, &stopped, &upRays, &cancel));
    EXPECT_EQ(upRays.camera, 0u);
}

}  // namespace
}  // namespace prism
