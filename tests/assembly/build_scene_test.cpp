// BuildRenderScene's settings: replacements of what the description says and the
// analytic-shape replacement hook (`prism render --tessellate`), without the command line.
#include "assembly/build_scene.h"

#include <gtest/gtest.h>

#include "scene/pbrt_parser.h"

namespace prism {
namespace {

SceneDescription Parse(const std::string &world, Diagnostics &diag) {
    return ParsePbrtString("WorldBegin\nLightSource \"point\"\n" + world, "build.pbrt", diag);
}

TEST(BuildScene, SettingsReplaceTheDescriptionsValues) {
    Diagnostics diag;
    SceneDescription d = Parse("Shape \"sphere\"\n", diag);
    BuildSettings s;
    RenderScene plain = BuildRenderScene(d, s, diag);
    EXPECT_EQ(plain.resolution.x, 1280);  // pbrt-v3's default film
    EXPECT_EQ(plain.resolution.y, 720);
    EXPECT_EQ(plain.trace.maxDepth, 5);
    s.resolution = {32, 16};
    s.spp = 3;
    s.maxDepth = 2;
    s.worldFromCamera = Translate(Vec3d(1, 2, 3));
    RenderScene r = BuildRenderScene(d, s, diag);
    EXPECT_EQ(r.resolution.x, 32);
    EXPECT_EQ(r.resolution.y, 16);
    EXPECT_EQ(r.sampler.spp, 3);
    EXPECT_EQ(r.trace.maxDepth, 2);
    // Camera-relative render space: the replaced camera's eye is the render-space origin.
    Vec3d eye = r.renderFromWorld.Point(Vec3d(1, 2, 3));
    EXPECT_NEAR(Length(eye), 0.0, 1e-12);
}

TEST(BuildScene, ResolutionSettingBeyondTheLimitIsBadInput) {
    Diagnostics diag;
    SceneDescription d = Parse("Shape \"sphere\"\n", diag);
    BuildSettings s;
    s.resolution = {MaxImageResolution + 1, 16};
    EXPECT_THROW(BuildRenderScene(d, s, diag), SceneError);
}

TEST(BuildScene, ReplacementHookSeesEveryAnalyticShape) {
    Diagnostics diag;
    SceneDescription d = Parse(
        "Shape \"sphere\"\nShape \"disk\"\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n",
        diag);
    BuildSettings s;
    s.resolution = {4, 4};
    std::vector<std::string> seen;
    s.replaceAnalyticShape = [&](const AnalyticShape &shape,
                                 const MeshCharge &) -> std::unique_ptr<TriangleMesh> {
        seen.push_back(shape.Name());
        return nullptr;  // keep the analytic shape
    };
    RenderScene r = BuildRenderScene(d, s, diag);
    EXPECT_EQ(seen, (std::vector<std::string>{"sphere", "disk"}));
    EXPECT_EQ(r.features.analyticShapes, 2);
    EXPECT_EQ(r.features.meshes, 1);
}

}  // namespace
}  // namespace prism
