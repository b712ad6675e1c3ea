// The sppm integrator (Integrator "sppm", stochastic progressive photon mapping): a furnace and
// a caustic off a mirror against their closed forms, agreement with path on a diffuse room, a
// glass caustic that sppm resolves where path at equal time is noise, the same image for 1 and
// 2 threads, the frame hook's intermediate images, and its parameters' errors.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

RenderScene BuildText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return BuildSceneText("prism_sppm", name, text, opts);
}

Image RenderText(const std::string &name, const std::string &text, RenderStats *stats = nullptr,
                 uint32_t seed = 0) {
    return RenderWithSeed(BuildText(name, text), seed, stats);
}

double MeanOf(const Image &img, int x0, int x1, int y0, int y1, int c = 1) {
    double s = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) s += img.At(x, y, c);
    return s / (double(x1 - x0) * double(y1 - y0));
}

// Mean |a - b| over mean |b|, over the pixels of [x0, x1) x [y0, y1) and all channels, after
// averaging blocks of `block` x `block` pixels (box filtering, as the pbrt-v3 comparisons do).
double RelL1(const Image &a, const Image &b, int block, int x0, int x1, int y0, int y1) {
    double d = 0, m = 0;
    for (int by = y0; by + block <= y1; by += block)
        for (int bx = x0; bx + block <= x1; bx += block)
            for (int c = 0; c < 3; ++c) {
                double sa = 0, sb = 0;
                for (int y = by; y < by + block; ++y)
                    for (int x = bx; x < bx + block; ++x) sa += a.At(x, y, c), sb += b.At(x, y, c);
                d += std::abs(sa - sb);
                m += std::abs(sb);
            }
    return d / m;
}
double RelL1(const Image &a, const Image &b, int block) {
    return RelL1(a, b, block, 0, a.width, 0, a.height);
}

std::string Sppm(int iterations, int photons, float radius, int maxDepth = 5) {
    return "Integrator \"sppm\" \"integer numiterations\" [" + std::to_string(iterations) +
           "] \"integer photonsperiteration\" [" + std::to_string(photons) +
           "] \"float radius\" [" + std::to_string(radius) + "] \"integer maxdepth\" [" +
           std::to_string(maxDepth) + "]\n";
}

// The camera inside a closed sphere of albedo a whose inside emits Le: every vertex sees
// Le + a·(what it receives), so sppm's estimate (emission and direct light at the visible
// point, photons after one to maxdepth - 1 bounces) is Le (1 + a + ... + a^maxdepth). On a
// sphere the disk of radius r holds exactly the area pi r^2 of the cap within distance r, so
// the density estimate has no bias either.
TEST(SppmIntegrator, FurnaceIsTheGeometricSeries) {
    const float a = 0.5f;
    const int depth = 5;
    const std::string scene =
        "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n" +
        Sppm(16, 4000, 0.5f, depth) +
        "Camera \"perspective\" \"float fov\" [90]\nWorldBegin\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
        "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\nShape \"sphere\" \"float radius\" [3]\n"
        "AttributeEnd\n";
    RenderStats stats;
    const Image img = RenderText("furnace", scene, &stats);
    const double expected = (1 - std::pow(double(a), depth + 1)) / (1 - a);
    EXPECT_NEAR(MeanOf(img, 0, 16, 0, 16), expected, 0.01 * expected);
    EXPECT_EQ(stats.spp, 16);
    EXPECT_GT(stats.rays.reflection, 0u) << "photons bounce";
}

// A diffuse floor (z = 0, albedo kd) under a point light of intensity I at height h, below a
// mirror ceiling at height H. With maxdepth 2 the floor receives direct light (the camera
// pass's light sample) and the light's mirror image at height 2H - h (photons: light ->
// mirror -> floor), nothing more: L(x, y) = kd/pi · I (h / d1^3 + (2H - h) / d2^3), with d1
// and d2 the distances to the light and its image.
TEST(SppmIntegrator, MirrorCausticMatchesClosedForm) {
    const float kd = 0.5f, I = 1, h = 1, H = 1.5f;
    const std::string scene =
        "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n" +
        Sppm(24, 30000, 0.04f, 2) +
        "LookAt 0 0 0.5  0 0 0  0 1 0\n"
        "Camera \"orthographic\" \"float screenwindow\" [-0.5 0.5 -0.5 0.5]\nWorldBegin\n"
        "LightSource \"point\" \"point from\" [0 0 1] \"rgb I\" [1 1 1]\n"
        "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
        "  \"point P\" [-50 -50 0  50 -50 0  50 50 0  -50 50 0]\n"
        "Material \"mirror\" \"rgb Kr\" [1 1 1]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 2 1 0 3 2]\n"
        "  \"point P\" [-50 -50 1.5  50 -50 1.5  50 50 1.5  -50 50 1.5]\n";
    const Image img = RenderText("mirror", scene);
    double expected = 0, got = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const double px = (x + 0.5) / 16 - 0.5, py = (y + 0.5) / 16 - 0.5;
            const double r2 = px * px + py * py;
            const double d1 = std::sqrt(r2 + h * h), d2 = std::sqrt(r2 + (2 * H - h) * (2 * H - h));
            expected += kd / Pi * I * (h / (d1 * d1 * d1) + (2 * H - h) / (d2 * d2 * d2));
            got += img.At(x, y, 1);
        }
    EXPECT_NEAR(got, expected, 0.02 * expected);
    // The caustic is a quarter of it: without photons the image would be 20% darker.
    EXPECT_GT(got, 0.9 * expected);
}

// A diffuse room (floor, back wall, a matte sphere, a quad light and a point light).
std::string DiffuseRoom(const std::string &integrator, int res) {
    return "Film \"image\" \"integer xresolution\" [" + std::to_string(res) +
           "] \"integer yresolution\" [" + std::to_string(res) +
           "]\nSampler \"stratified\" \"integer xsamples\" [16] \"integer ysamples\" [16]\n" +
           integrator + kLitFloorFromLookAt +
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point P\" [-3 0 2  3 0 2  3 3 2  -3 3 2]\n"
           "Material \"matte\" \"rgb Kd\" [0.3 0.6 0.3]\n"
           "AttributeBegin\nTranslate 0 0.6 0\nShape \"sphere\" \"float radius\" [0.6]\n"
           "AttributeEnd\n";
}

TEST(SppmIntegrator, AgreesWithPathOnADiffuseRoom) {
    const int res = 24;
    const Image path = RenderText("room_path", DiffuseRoom("Integrator \"path\"\n", res));
    const Image sppm = RenderText("room_sppm", DiffuseRoom(Sppm(64, 20000, 0.15f), res));
    // Two path renders with other seeds give path's own noise at this spp; sppm's difference
    // is its noise plus its bias, both a few percent over 4x4 blocks.
    const Image path2 =
        RenderText("room_path", DiffuseRoom("Integrator \"path\"\n", res), nullptr, 7);
    const double own = RelL1(path2, path, 4), diff = RelL1(sppm, path, 4);
    EXPECT_LT(diff, 0.05) << "path's own noise " << own;
    EXPECT_NEAR(MeanOf(sppm, 0, res, 0, res), MeanOf(path, 0, res, 0, res),
                0.03 * MeanOf(path, 0, res, 0, res));
}

// scenes/sppm-caustic.pbrt at 48x36 with its point light made a small sphere light: the
// caustic in front of the glass sphere is lit only through it (light -> glass -> glass ->
// floor). Path finds it only when a BSDF sample from the floor refracts through the sphere
// into the small light (fireflies); photons carry it.
std::string GlassCaustic(const std::string &integrator) {
    return "LookAt 0 2.2 -4.5  0 0.55 0  0 1 0\nCamera \"perspective\" \"float fov\" [38]\n"
           "Film \"image\" \"integer xresolution\" [48] \"integer yresolution\" [36]\n" +
           integrator +
           "WorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [400 400 400]\n"
           "Translate 0.35 3 0.3\nShape \"sphere\" \"float radius\" [0.05]\nAttributeEnd\n"
           "Material \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n"
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point P\" [-4 0 -4  4 0 -4  4 0 4  -4 0 4]\n"
           "Material \"glass\" \"float index\" [1.5]\n"
           "AttributeBegin\nTranslate 0 0.6 0\nShape \"sphere\" \"float radius\" [0.6]\n"
           "AttributeEnd\n";
}

TEST(SppmIntegrator, ShowsAGlassCausticWherePathIsNoise) {
    const std::string sppm = GlassCaustic(Sppm(32, 20000, 0.03f));
    // 256 spp of path took about as long as these 32 iterations (0.8 s on the 2-core VM); a
    // fixed count keeps the test deterministic.
    const std::string path = GlassCaustic(
        "Integrator \"path\"\nSampler \"stratified\" \"integer xsamples\" [256] "
        "\"integer ysamples\" [1]\n");
    const Image s1 = RenderText("caustic_sppm", sppm),
                s2 = RenderText("caustic_sppm", sppm, nullptr, 3);
    const Image p1 = RenderText("caustic_path", path),
                p2 = RenderText("caustic_path", path, nullptr, 3);
    // The sphere's shadow on the floor in front of it, with the caustic at its centre.
    const int x0 = 19, x1 = 27, y0 = 22, y1 = 27;
    double peak = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) peak = std::max(peak, double(s1.At(x, y, 1)));
    const double open = MeanOf(s1, 0, 48, 30, 36);  // the floor near the camera
    EXPECT_GT(peak, 3 * open) << "the caustic focuses light into the shadow";
    const double sppmNoise = RelL1(s2, s1, 1, x0, x1, y0, y1);
    const double pathNoise = RelL1(p2, p1, 1, x0, x1, y0, y1);
    EXPECT_LT(sppmNoise * 2, pathNoise);
    // Both estimate the same light: their means in the region agree within path's noise.
    const double sm = MeanOf(s1, x0, x1, y0, y1);
    EXPECT_NEAR(MeanOf(p1, x0, x1, y0, y1), sm, std::max(0.3, pathNoise) * sm);
}

TEST(SppmIntegrator, SameImageForOneAndTwoThreads) {
    RenderScene scene = BuildText("threads", DiffuseRoom(Sppm(3, 5000, 0.2f), 24));
    Image one = RenderOnThreads(scene, 1), two = RenderOnThreads(scene, 2);
    EXPECT_TRUE(one.pixels == two.pixels);
    EXPECT_GT(MeanOf(one, 0, 24, 0, 24), 0.0);
}

TEST(SppmIntegrator, IntermediateImagesAndCancel) {
    RenderScene scene = BuildText(
        "intermediate", DiffuseRoom("Integrator \"sppm\" \"integer numiterations\" [5] "
                                    "\"integer imagewritefrequency\" [2] \"float radius\" [0.2]\n",
                                    8));
    RenderOptions options;
    options.sampler = scene.sampler;
    int written = 0;
    options.intermediate = [&](const Image &img) {
        ++written;
        EXPECT_EQ(img.width, 8);
    };
    RenderStats stats;
    const Image img = Render(scene, options, &stats);
    EXPECT_EQ(written, 2);  // after iterations 2 and 4; the 5th is the render's own image
    EXPECT_EQ(stats.spp, 5);
    EXPECT_FALSE(stats.cancelled);
    // Cancelled before the first iteration: a black image, marked cancelled.
    const volatile int cancel = 1;
    options.cancel = &cancel;
    const Image none = Render(scene, options, &stats);
    EXPECT_TRUE(stats.cancelled);
    EXPECT_EQ(stats.spp, 0);
    EXPECT_EQ(MeanOf(none, 0, 8, 0, 8), 0.0);
}

// --spp (BuildSettings::spp) is sppm's iteration count, as in pbrt-v4: it wins over
// numiterations, and the render reports it as its spp.
TEST(SppmIntegrator, SppSetsTheIterations) {
    BuildSettings opts;
    opts.spp = 3;
    RenderScene scene = BuildText("spp", DiffuseRoom(Sppm(5, 2000, 0.2f), 8), opts);
    RenderOptions options;
    options.sampler = scene.sampler;
    RenderStats stats;
    Render(scene, options, &stats);
    EXPECT_EQ(stats.spp, 3);
}

TEST(SppmIntegrator, ParameterErrorsAreLocated) {
    for (const char *bad : {"\"integer numiterations\" [0]", "\"float radius\" [-1]",
                            "\"integer photonsperiteration\" [0]"}) {
        const std::string text =
            std::string("Integrator \"sppm\" ") + bad + "\nCamera \"perspective\"\nWorldBegin\n";
        EXPECT_THROW(BuildText("bad", text), SceneError) << bad;
    }
    RenderScene s = BuildText("named", DiffuseRoom(Sppm(1, 10, 1), 4));
    EXPECT_STREQ(s.IntegratorName(), "sppm");
    EXPECT_TRUE(s.integrator->RendersWholeFrame());
}

}  // namespace
}  // namespace prism
