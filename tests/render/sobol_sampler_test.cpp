// pbrt's "sobol" sampler (render/sobol_sampler.h): the sequence against Boost.Random's Sobol
// generator and against Prism's own first two dimensions, each dimension's stratification, the
// pixels' points, and the sampler from a scene file.
#include "render/sobol_sampler.h"

#include <gtest/gtest.h>

#include <boost/random/sobol.hpp>
#include <set>

#include "support/image_stats.h"
#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

// Boost draws the points in Gray-code order from the second on: its point n is point g ^ (g >> 1)
// here, g = n + 1. A separate implementation of the same direction numbers, so the recurrence
// is checked, not copied.
TEST(SobolSampler, MatchesBoostsSobolSequence) {
    const int dims = 200;
    boost::random::sobol boost(dims);
    for (uint64_t g = 1; g <= 2048; ++g)
        for (int d = 0; d < dims; ++d) {
            const uint64_t want = boost();  // 64-bit engine value: the top 32 bits are ours
            ASSERT_EQ(SobolPoint(g ^ (g >> 1), uint32_t(d)), uint32_t(want >> 32))
                << "point " << g << " dimension " << d;
        }
}

TEST(SobolSampler, FirstTwoDimensionsAreTheZeroTwoSequence) {
    for (uint32_t n = 0; n < 5000; n += 7) {
        EXPECT_EQ(SobolPoint(n, 0), SobolBits0(n));
        EXPECT_EQ(SobolPoint(n, 1), SobolBits1(n));
    }
}

// Every dimension's first 2^k points fall one in each interval [i/2^k, (i+1)/2^k).
TEST(SobolSampler, EveryDimensionIsStratified) {
    const int k = 9;
    for (uint32_t d = 0; d < SobolDimensions; d += 3) {
        std::set<uint32_t> cells;
        for (uint32_t n = 0; n < (1u << k); ++n) cells.insert(SobolPoint(n, d) >> (32 - k));
        ASSERT_EQ(cells.size(), size_t(1) << k) << d;
    }
}

// A pixel's points lie in it (dimensions 0 and 1 scaled by the film's power-of-two size), and
// no two pixels or samples share one.
TEST(SobolSampler, PixelPointsLieInTheirPixel) {
    for (auto [w, h] : {std::pair{1, 1}, {8, 8}, {13, 5}, {40, 70}}) {
        const SobolFrame f = SobolFrame::ForResolution(w, h, SobolScramble::Owen);
        std::set<uint64_t> seen;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (uint64_t s = 0; s < 8; ++s) {
                    const uint64_t index = f.Index(x, y, s);
                    ASSERT_TRUE(seen.insert(index).second) << x << " " << y << " " << s;
                    const double u = double(SobolPoint(index, 0)) * 0x1p-32 * f.scale,
                                 v = double(SobolPoint(index, 1)) * 0x1p-32 * f.scale;
                    ASSERT_EQ(int(u), x) << w << "x" << h << " sample " << s;
                    ASSERT_EQ(int(v), y) << w << "x" << h << " sample " << s;
                    const Vec2f o = f.PixelOffset(index, x, y);
                    ASSERT_GE(o.x, 0.f);
                    ASSERT_LT(o.x, 1.f);
                    ASSERT_NEAR(o.y, v - y, 1e-6);
                }
    }
}

// From a file: pbrt's "sobol" renders without warnings as its own pattern (a power-of-two
// count; another count is rounded up, with a warning), and converges to the stratified
// sampler's image.
TEST(SobolSampler, FromSceneFile) {
    const std::string scene =
        "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
        "Sampler \"sobol\" \"integer pixelsamples\" 64\nIntegrator \"path\"\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [0.5 0.5 0.5]\n"
        "LightSource \"point\" \"point3 from\" [1 2 -2] \"rgb I\" [5 5 5]\n"
        "Material \"diffuse\"\nShape \"sphere\" \"float radius\" 1\n"
        "Translate 0 -1 0\nShape \"disk\" \"float radius\" 3\n";
    BuildSettings s = SizedSettings(24, 24, 0);
    const Rendered sobol = RenderSceneText("sobol", "sobol.pbrt", scene, s);
    EXPECT_TRUE(sobol.warnings.empty()) << sobol.warnings[0].ToString();
    EXPECT_EQ(sobol.scene.sampler.pattern, SamplePattern::Sobol);
    EXPECT_EQ(sobol.scene.sampler.spp, 64);
    std::string stratified = scene;
    stratified.replace(stratified.find("\"sobol\""), 7, "\"stratified\"");
    stratified.replace(stratified.find("\"integer pixelsamples\" 64"), 25,
                       "\"integer xsamples\" 32 \"integer ysamples\" 32");
    const Rendered reference = RenderSceneText("sobol", "ref.pbrt", stratified, s);
    EXPECT_LT(RelL1(sobol.image, reference.image), 0.03);
    EXPECT_NEAR(MeanValue(sobol.image), MeanValue(reference.image),
                0.01 * MeanValue(reference.image));

    std::string odd = scene;
    odd.replace(odd.find("64"), 2, "20");
    const Built built = BuildSceneFile(WriteSceneText("sobol", "odd.pbrt", odd), s);
    EXPECT_EQ(built.scene.sampler.spp, 32);
    ASSERT_EQ(built.warnings.size(), 1u);
    EXPECT_NE(built.warnings[0].message.find("rounded up to 32"), std::string::npos);
}

}  // namespace
}  // namespace prism
