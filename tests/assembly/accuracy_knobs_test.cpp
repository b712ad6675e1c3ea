// The accuracy knobs of BuildSettings (`prism study`, docs/SHAPES.md "Offset modes"), end to
// end through BuildRenderScene and Render: the ray-weight cutoff (bit-identical at 0, rays
// saved and counted above), the offset modes on Whitted's 1e5-radius floor (acne with a fixed
// epsilon or none, none with error bounds), and the BVH flags reaching Embree.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "assembly/build_scene.h"
#include "image/image_compare.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

std::string WriteScene(const std::string &name, const std::string &text) {
    return WriteSceneText("prism_accuracy_knobs", name, text);
}

std::string ReadText(const std::string &path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

bool BitIdentical(const Image &a, const Image &b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

BuildSettings Small(Vec2i res, int spp) {
    BuildSettings opts;
    opts.resolution = res;
    opts.spp = spp;
    return opts;
}

// Cutoff 0 is the renderer without the cutoff: every pixel bit for bit, and nothing counted
// as saved. (The same image as before the knob existed was checked against the previous
// binary when it was added; tests/golden guards it from then on.) A positive cutoff below
// every throughput takes the cutoff's code path yet traces the same rays: the same image.
TEST(AccuracyKnobs, CutoffZeroIsBitIdentical) {
    const std::string scene = Source + "/scenes/whitted.pbrt";  // mirror and glass spheres
    BuildSettings opts = Small({96, 72}, 2);
    Rendered plain = RenderSceneFile(scene, opts);
    opts.rayCutoff = 0;
    Rendered zero = RenderSceneFile(scene, opts);
    EXPECT_TRUE(BitIdentical(plain.image, zero.image));
    EXPECT_EQ(zero.stats.rays.cutoff, 0u);
    EXPECT_EQ(zero.stats.rays.reflection, plain.stats.rays.reflection);
    EXPECT_EQ(zero.stats.rays.refraction, plain.stats.rays.refraction);
    EXPECT_GT(plain.stats.rays.reflection, 0u);
    EXPECT_GT(plain.stats.rays.refraction, 0u);
    opts.rayCutoff = 1e-30f;
    Rendered tiny = RenderSceneFile(scene, opts);
    EXPECT_TRUE(BitIdentical(plain.image, tiny.image));
}

// A cutoff drops the rays whose throughput is at most the cutoff, counts them, and changes
// the image by about the cutoff (each dropped ray would have brought back its throughput
// times a radiance of order 1 in this scene).
TEST(AccuracyKnobs, CutoffSavesRaysAndChangesLittle) {
    const std::string scene = Source + "/scenes/whitted.pbrt";
    BuildSettings opts = Small({96, 72}, 2);
    Rendered full = RenderSceneFile(scene, opts);
    opts.rayCutoff = 1e-2f;
    Rendered cut = RenderSceneFile(scene, opts);
    const RayCounters &a = full.stats.rays, &b = cut.stats.rays;
    EXPECT_GT(b.cutoff, 0u);
    EXPECT_LT(b.reflection + b.refraction, a.reflection + a.refraction);
    EXPECT_LT(b.Total(), a.Total());
    EXPECT_EQ(b.camera, a.camera);
    ImageDiff d = CompareImages(full.image, cut.image, 0.1f);
    EXPECT_GT(d.maxAbs, 0.0);
    EXPECT_LE(d.maxAbs, 5e-2);
    EXPECT_LE(d.meanAbs, 1e-3);
    EXPECT_EQ(d.badPixels, 0);
}

// Two facing mirrors of reflectance 0.5 and a camera ray along their normal: the n-th
// reflection ray carries throughput 0.5^n. With cutoff 0.1 the rays of throughput 0.5, 0.25
// and 0.125 are traced and the next one (0.0625) is dropped, which ends the path.
TEST(AccuracyKnobs, CutoffFollowsTheThroughputDownThePath) {
    std::string file = WriteScene("mirror_corridor", R"(
LookAt 0 0 0  1 0 0  0 1 0
Camera "perspective" "float fov" [ 10 ]
Film "image" "integer xresolution" [ 1 ] "integer yresolution" [ 1 ]
Sampler "stratified" "integer xsamples" [ 1 ] "integer ysamples" [ 1 ]
Integrator "whitted" "integer maxdepth" [ 20 ]
WorldBegin
LightSource "point" "point3 from" [ 0 3 0 ] "rgb I" [ 10 10 10 ]
Material "mirror" "rgb Kr" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "integer indices" [ 0 1 2  0 2 3 ]
  "point3 P" [ 1 -5 -5   1 5 -5   1 5 5   1 -5 5 ]
Shape "trianglemesh" "integer indices" [ 0 1 2  0 2 3 ]
  "point3 P" [ -1 -5 -5   -1 5 -5   -1 5 5   -1 -5 5 ]
WorldEnd
)");
    BuildSettings opts;
    Rendered all = RenderSceneFile(file, opts);
    EXPECT_EQ(all.stats.rays.reflection, 19u);  // depths 1 to 19 under maxdepth 20
    EXPECT_EQ(all.stats.rays.cutoff, 0u);
    opts.rayCutoff = 0.1f;
    Rendered cut = RenderSceneFile(file, opts);
    EXPECT_EQ(cut.stats.rays.reflection, 3u);
    EXPECT_EQ(cut.stats.rays.cutoff, 1u);
    opts.rayCutoff = 0.125f;  // "more than the cutoff": 0.125 itself is dropped
    EXPECT_EQ(RenderSceneFile(file, opts).stats.rays.reflection, 2u);
}

// Whitted's floor (r = 1e5) with a sphere on it, lit from above. The floor can shadow nothing
// there, so the same scene with the floor hidden from shadow rays ("shadowalpha" 0) is the
// acne-free reference at the same settings; "bad pixels" are those off by more than 0.1
// against it (as `prism study` counts them).
struct AcneCase {
    std::string scene, reference;
    AcneCase(const std::string &name, std::string text) {
        scene = WriteScene(name, text);
        const std::string floor = "Shape \"sphere\" \"float radius\" [ 100000 ]";
        size_t at = text.find(floor);
        EXPECT_NE(at, std::string::npos);
        if (at != std::string::npos) text.insert(at + floor.size(), " \"float shadowalpha\" [ 0 ]");
        reference = WriteScene(name + "_reference", text);
    }
    int64_t BadPixels(BuildSettings opts, RayOffset offset) const {
        Image ref = RenderSceneFile(reference, opts).image;
        opts.offset = offset;
        Image img = RenderSceneFile(scene, opts).image;
        return CompareImages(ref, img, 0.1f).badPixels;
    }
};

RayOffset Offset(OffsetMode mode, float epsilon = 1e-4f) { return {mode, epsilon}; }

// scenes/bigsphere_acne.pbrt: the floor and a sphere of radius 300 seen from 5 km. Hit points
// some 5000 units from the camera are rounded by up to 2.4e-4 in camera-centred float
// coordinates, so a fixed 1e-4 offset leaves shadow rays inside the sphere (acne) while 1e-3
// clears the rounding; the error-bound offset gives none, and no offset acne everywhere.
TEST(AccuracyKnobs, FixedEpsilonGivesAcneOnTheHugeFloorSceneErrorBoundsNone) {
    AcneCase c("bigsphere_acne", ReadText(Source + "/scenes/bigsphere_acne.pbrt"));
    BuildSettings opts = Small({160, 120}, 1);
    EXPECT_EQ(c.BadPixels(opts, Offset(OffsetMode::ErrorBounds)), 0);
    EXPECT_GT(c.BadPixels(opts, Offset(OffsetMode::FixedEpsilon, 1e-4f)), 50);
    EXPECT_EQ(c.BadPixels(opts, Offset(OffsetMode::FixedEpsilon, 1e-3f)), 0);
    EXPECT_GT(c.BadPixels(opts, Offset(OffsetMode::None)), 1000);
}

// The same floor at unit scale (a sphere of radius 1 seen from 6 units): the camera-centred hit
// points are accurate to about 1e-7 and the sphere's intersector rejects roots within their
// own error bound of t = 0 (docs/SHAPES.md), so even a fixed 1e-4 gives no acne; without
// an offset there is acne, and the error-bound offset gives none.
TEST(AccuracyKnobs, AtUnitScaleOnlyNoOffsetGivesAcne) {
    AcneCase c("bigsphere_unit", ReadText(Source + "/scenes/bigsphere_unit.pbrt"));
    BuildSettings opts;
    EXPECT_EQ(c.BadPixels(opts, Offset(OffsetMode::ErrorBounds)), 0);
    EXPECT_EQ(c.BadPixels(opts, Offset(OffsetMode::FixedEpsilon, 1e-4f)), 0);
    EXPECT_GT(c.BadPixels(opts, Offset(OffsetMode::None)), 1000);
}

TEST(AccuracyKnobs, BadSettingsAreErrors) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Source + "/scenes/bigsphere_acne.pbrt", diag);
    BuildSettings opts = Small({8, 6}, 1);
    opts.rayCutoff = -1;
    EXPECT_THROW(BuildRenderScene(desc, opts, diag), SceneError);
    opts.rayCutoff = 0;
    opts.offset = Offset(OffsetMode::FixedEpsilon, 0);
    EXPECT_THROW(BuildRenderScene(desc, opts, diag), SceneError);
    opts.offset = Offset(OffsetMode::None, 0);  // the epsilon of other modes is not read
    EXPECT_NO_THROW(BuildRenderScene(desc, opts, diag));
}

// BuildSettings::robust and bvhQuality reach the Embree scene; Auto keeps its choice by work.
TEST(AccuracyKnobs, BvhFlagsReachTheAccel) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Source + "/scenes/whitted.pbrt", diag);
    BuildSettings opts = Small({8, 6}, 1);
    RenderScene plain = BuildRenderScene(desc, opts, diag);
    EXPECT_FALSE(plain.accel->Robust());
    EXPECT_EQ(plain.accel->BuildQuality(), BvhQuality::Medium);  // 48 samples, 2 triangles
    opts.robust = true;
    for (BvhQuality q : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High}) {
        opts.bvhQuality = q;
        RenderScene s = BuildRenderScene(desc, opts, diag);
        EXPECT_TRUE(s.accel->Robust());
        EXPECT_EQ(s.accel->BuildQuality(), q);
        // The same image whatever the BVH, up to the last bits of ROBUST's watertight
        // triangle test.
        ImageDiff d = CompareImages(Render(s, nullptr), Render(plain, nullptr), 0.01f);
        EXPECT_EQ(d.badPixels, 0);
        EXPECT_LE(d.maxAbs, 1e-3);
    }
}

}  // namespace
}  // namespace prism
