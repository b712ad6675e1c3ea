// Progressive rendering (render/progressive.h, --time-limit) and the noise estimate of
// --stats (RenderStats::noiseVariance): pass sizes, the averaged image against a plain render
// and a converged reference, and the estimate against the error actually measured.
#include "render/progressive.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include "assembly/build_scene.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

// An area light over a floor and a sphere: soft shadows give every spp its noise.
std::string SoftScene() {
    return test::WriteTestFile(
        test::ScratchDir("progressive") / "soft.pbrt",
        "LookAt 0 1.5 -5  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n"
        "WorldBegin\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 6 6 6 ]\nTranslate 0.5 3 0\n"
        "Shape \"sphere\" \"float radius\" 0.7\nAttributeEnd\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "  \"point3 P\" [ -10 0 -10  10 0 -10  10 0 10  -10 0 10 ]\n"
        "Translate 0 0.6 0\nShape \"sphere\" \"float radius\" 0.6\nWorldEnd\n");
}

RenderScene Build(int spp, bool noise = false, const std::string &integrator = "") {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(SoftScene(), diag);
    BuildSettings s;
    s.resolution = Vec2i(40, 30);
    s.spp = spp;
    s.integrator = integrator;
    RenderScene scene = BuildRenderScene(desc, s, diag);
    scene.estimateNoise = noise;
    return scene;
}

double RelRmse(const Image &a, const Image &ref) {
    double d = 0, r = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        double e = double(a.pixels[i]) - double(ref.pixels[i]);
        d += e * e;
        r += double(ref.pixels[i]) * double(ref.pixels[i]);
    }
    return std::sqrt(d / r);
}

const Image &Reference() {
    static const Image ref = [] {
        RenderScene scene = Build(1024);
        return Render(scene, nullptr);
    }();
    return ref;
}

TEST(NextPassSpp, PassesDoubleTheTotalWithinTimeAndBudget) {
    EXPECT_EQ(NextPassSpp(0, 100, 10, 0), 2);  // the first pass: 2, to measure
    EXPECT_EQ(NextPassSpp(0, 1, 10, 0), 1);
    EXPECT_EQ(NextPassSpp(2, 100, 10, 0.01), 2);
    EXPECT_EQ(NextPassSpp(8, 100, 10, 0.01), 8);
    EXPECT_EQ(NextPassSpp(64, 100, 10, 0.01), 36);  // the budget left
    EXPECT_EQ(NextPassSpp(64, 1000, 1, 0.1), 9);    // 0.9 s left at 0.1 s per spp
    EXPECT_EQ(NextPassSpp(4, 1000, 0.15, 0.1), 0);  // one sample fits, but not two
    EXPECT_EQ(NextPassSpp(99, 100, 0.15, 0.1), 1);  // ... unless it ends the budget
    EXPECT_EQ(NextPassSpp(100, 100, 1e9, 0.1), 0);  // budget spent
    EXPECT_EQ(NextPassSpp(4, 1000, -1, 0.1), 0);    // time up
}

TEST(Progressive, OnePassIsThePlainRender) {
    RenderScene a = Build(2), b = Build(2);
    RenderStats st;
    Image plain = Render(a, nullptr);
    Image prog = RenderProgressive(b, {1e9, 2}, &st);
    ASSERT_EQ(st.passSpp, std::vector<int>{2});
    EXPECT_EQ(
        std::memcmp(plain.pixels.data(), prog.pixels.data(), plain.pixels.size() * sizeof(float)),
        0);
    EXPECT_EQ(st.spp, 2);
    // The passes change the sampler they render with, not the scene.
    EXPECT_EQ(b.sampler.spp, 2);
    EXPECT_EQ(b.sampler.seed, 0u);
}

TEST(Progressive, PassesAverageToAConvergingImage) {
    RenderScene scene = Build(1);
    RenderStats st;
    Image img = RenderProgressive(scene, {1e9, 64}, &st);
    EXPECT_EQ(st.passSpp, (std::vector<int>{2, 2, 4, 8, 16, 32}));
    EXPECT_EQ(st.spp, 64);
    EXPECT_EQ(scene.sampler.spp, 1);  // the scene is left as built
    EXPECT_EQ(scene.sampler.seed, 0u);
    // Each pass draws new samples: 64 samples in passes are about as close to the reference
    // as one 64-spp render, and much closer than the first pass alone.
    RenderScene plain = Build(64), two = Build(2);
    double eProg = RelRmse(img, Reference());
    double ePlain = RelRmse(Render(plain, nullptr), Reference());
    double eTwo = RelRmse(Render(two, nullptr), Reference());
    EXPECT_LT(eProg, 0.35 * eTwo);
    EXPECT_LT(eProg, 1.5 * ePlain);
}

// The path integrator's sample streams take the pass seed too: its passes converge.
TEST(Progressive, PathIntegratorPassesDrawNewSamples) {
    RenderScene ref = Build(256, false, "path"), two = Build(2, false, "path");
    RenderScene scene = Build(1, false, "path");
    Image reference = Render(ref, nullptr);
    Image img = RenderProgressive(scene, {1e9, 32}, nullptr);
    EXPECT_LT(RelRmse(img, reference), 0.4 * RelRmse(Render(two, nullptr), reference));
}

TEST(Progressive, StopsWhenTheTimeRunsOut) {
    RenderScene scene = Build(1);
    RenderStats st;
    const double limit = 0.3;
    auto t0 = std::chrono::steady_clock::now();
    Image img = RenderProgressive(scene, {limit, MaxProgressiveSpp}, &st);
    double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(st.passSpp.size(), 2u);
    EXPECT_LT(st.spp, MaxProgressiveSpp);
    // Passes are sized to end before the limit; a generous bound for a loaded machine.
    EXPECT_LT(took, limit + 2.0);
    EXPECT_EQ(img.width, 40);
}

// The estimate predicts the error against the converged image: unbiased for independent
// samples, it errs high for stratified ones, never far below. The scene has no Sampler line:
// pbrt-v3's Halton sequence, for which it is 0.73x at 4 spp, 2.1x at 16 spp and 2.3x for
// passes.
TEST(NoiseEstimate, PredictsTheRelativeErrorAgainstAReference) {
    for (int spp : {4, 16}) {
        RenderScene scene = Build(spp, true);
        RenderStats st;
        Image img = Render(scene, &st);
        std::optional<double> rse = RelativeStandardError(img, st);
        ASSERT_TRUE(rse);
        EXPECT_EQ(st.noisePixels, 40u * 30u);
        double actual = RelRmse(img, Reference());
        EXPECT_GT(*rse / actual, 0.7) << spp << " spp";
        EXPECT_LT(*rse / actual, 3.5) << spp << " spp";
    }
    RenderScene scene = Build(1, true);
    RenderStats st;
    Image img = RenderProgressive(scene, {1e9, 16}, &st);
    std::optional<double> rse = RelativeStandardError(img, st);
    ASSERT_TRUE(rse);
    double actual = RelRmse(img, Reference());
    EXPECT_GT(*rse / actual, 0.8);
    EXPECT_LT(*rse / actual, 3.5);
    // One sample per pixel has no estimate.
    RenderScene one = Build(1, true);
    RenderStats s1;
    Image i1 = Render(one, &s1);
    EXPECT_FALSE(RelativeStandardError(i1, s1));
}

// The estimate does not change the image.
TEST(NoiseEstimate, LeavesTheImageAlone) {
    RenderScene a = Build(4, true), b = Build(4, false);
    Image ia = Render(a, nullptr), ib = Render(b, nullptr);
    EXPECT_EQ(std::memcmp(ia.pixels.data(), ib.pixels.data(), ia.pixels.size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace prism
