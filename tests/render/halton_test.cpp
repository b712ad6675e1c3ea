// The Halton pattern (pbrt's "halton" sampler): every point of a pixel lies in that pixel
// (the film's tiling of bases 2 and 3, wrapping at 128 pixels), the unscrambled sequence is the
// radical inverse, each randomisation keeps a pixel's points stratified in every dimension's
// base, stays in [0, 1) and averages 1/2, PixelSamples' dimensions map to distinct Halton
// dimensions, and a progressive render's passes continue one sequence.
#include "render/halton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "render/light_sampling.h"

namespace prism {
namespace {

// The radical inverse written out digit by digit, most significant first.
double RefRadicalInverse(uint64_t base, uint64_t a) {
    std::vector<uint64_t> digits;
    while (a > 0) {
        digits.push_back(a % base);
        a /= base;
    }
    double v = 0, scale = 1.0 / double(base);
    for (uint64_t d : digits) {
        v += double(d) * scale;
        scale /= double(base);
    }
    return v;
}

// floor(radical inverse of a in base b x b^k), exactly: a's k lowest digits reversed.
int64_t LeadingDigits(uint64_t a, uint64_t base, int k) {
    int64_t r = 0;
    for (int i = 0; i < k; ++i) {
        r = r * int64_t(base) + int64_t(a % base);
        a /= base;
    }
    return r;
}

TEST(Halton, EveryPointOfAPixelLiesInIt) {
    for (auto [w, h] : {std::pair{8, 8}, {40, 30}, {1, 1}, {200, 7}, {130, 300}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        const HaltonFrame f = HaltonFrame::ForResolution(w, h, HaltonScramble::PermuteDigits);
        EXPECT_GE(f.scaleX, uint32_t(std::min(w, 128)));
        EXPECT_GE(f.scaleY, uint32_t(std::min(h, 128)));
        EXPECT_LT(f.scaleX, 2 * uint32_t(std::max(1, std::min(w, 128))));
        for (int y = 0; y < h; y += std::max(1, h / 9))
            for (int x = 0; x < w; x += std::max(1, w / 9))
                for (uint64_t i = 0; i < 20; ++i) {
                    const uint64_t index = f.PixelIndex(x, y) + i * f.stride;
                    // Dimension 0 scaled by 2^expX, dimension 1 by 3^expY: the pixel (mod the
                    // tiling), and the offset within it is what PixelOffset gives.
                    ASSERT_EQ(LeadingDigits(index, 2, f.expX), (x % 128) % int64_t(f.scaleX))
                        << x << " " << i;
                    ASSERT_EQ(LeadingDigits(index, 3, f.expY), (y % 128) % int64_t(f.scaleY))
                        << y << " " << i;
                    // The offset is the radical inverse of the digits past the pixel's.
                    const Vec2f o = f.PixelOffset(index);
                    EXPECT_NEAR(o.x, RefRadicalInverse(2, index >> f.expX), 1e-6);
                    EXPECT_NEAR(o.y, RefRadicalInverse(3, index / f.scaleY), 1e-6);
                }
    }
}

TEST(Halton, UnscrambledIsTheRadicalInverse) {
    const HaltonFrame f = HaltonFrame::ForResolution(16, 16, HaltonScramble::None);
    const uint64_t primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29};
    for (uint32_t d = 2; d < 10; ++d)
        for (uint64_t n :
             {uint64_t(0), uint64_t(1), uint64_t(7), uint64_t(123456), uint64_t(1) << 40})
            EXPECT_NEAR(HaltonSample(f, n, d), RefRadicalInverse(primes[d], n), 1e-6)
                << d << " " << n;
}

// A pixel's first b points (b the dimension's prime) fall in distinct intervals of width 1/b:
// the randomisations permute digits, so the stratification of the sequence is kept.
TEST(Halton, RandomisedDimensionsStayStratifiedAndUniform) {
    const uint64_t primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47};
    for (HaltonScramble s :
         {HaltonScramble::PermuteDigits, HaltonScramble::Owen, HaltonScramble::None}) {
        const HaltonFrame f = HaltonFrame::ForResolution(40, 30, s);
        double sum = 0;
        int count = 0;
        for (uint32_t d = 2; d < 15; ++d) {
            const uint64_t b = primes[d];
            for (auto [x, y] : {std::pair{0, 0}, {17, 23}, {39, 29}}) {
                std::set<int64_t> cells;
                for (uint64_t i = 0; i < b; ++i) {
                    const float v = HaltonSample(f, f.PixelIndex(x, y) + i * f.stride, d);
                    ASSERT_GE(v, 0.f);
                    ASSERT_LT(v, 1.f);
                    cells.insert(int64_t(std::floor(double(v) * double(b))));
                }
                EXPECT_EQ(cells.size(), b) << "dimension " << d << " scramble " << int(s);
            }
            for (uint64_t n = 0; n < 4000; ++n) {
                sum += HaltonSample(f, n + 1000, d);
                ++count;
            }
        }
        EXPECT_NEAR(sum / count, 0.5, 0.01) << int(s);
    }
    // The randomisations differ from the bare sequence and from each other, and a seed (a
    // progressive pass) changes them.
    const HaltonFrame p = HaltonFrame::ForResolution(8, 8, HaltonScramble::PermuteDigits);
    const HaltonFrame o = HaltonFrame::ForResolution(8, 8, HaltonScramble::Owen);
    const HaltonFrame n = HaltonFrame::ForResolution(8, 8, HaltonScramble::None);
    int differ = 0;
    for (uint64_t i = 1; i < 50; ++i) {
        differ += HaltonSample(p, i, 5) != HaltonSample(n, i, 5);
        differ += HaltonSample(o, i, 5) != HaltonSample(p, i, 5);
        differ += HaltonSample(p, i, 5, 1) != HaltonSample(p, i, 5, 2);
    }
    EXPECT_GT(differ, 140);
}

// The tabulated permutations give the points the per-point computation gives.
TEST(Halton, TabulatedPermutationsDrawTheSamePoints) {
    for (uint32_t seed : {0u, 77u}) {
        const HaltonFrame tab =
            HaltonFrame::ForResolution(40, 30, HaltonScramble::PermuteDigits, seed);
        ASSERT_TRUE(tab.permutations);
        HaltonFrame slow = tab;
        slow.permutations = nullptr;
        for (uint32_t d : {2u, 3u, 7u, 50u, 600u, 2047u})
            for (uint64_t n : {uint64_t(0), uint64_t(1), uint64_t(12345), uint64_t(987654321)})
                EXPECT_NEAR(HaltonSample(tab, n, d, seed), HaltonSample(slow, n, d, seed), 2e-7)
                    << d << " " << n;
        // Another seed than the tables' is computed per point.
        EXPECT_EQ(HaltonSample(tab, 99, 5, seed + 1), HaltonSample(slow, 99, 5, seed + 1));
    }
}

TEST(Halton, PixelSamplesDimensionsAreDistinct) {
    std::set<uint32_t> used;
    auto take = [&](uint32_t dim, bool twoD) {
        const uint32_t h = HaltonDim(dim, twoD);
        ASSERT_NE(h, NoHaltonDim) << dim;
        EXPECT_TRUE(used.insert(h).second) << dim;
        if (twoD) EXPECT_TRUE(used.insert(h + 1).second) << dim;
    };
    take(0, true);   // film
    take(1, false);  // time
    take(2, true);   // lens
    for (int b = 0; b < 100; ++b) {
        take(VertexDim(b, DimLightChoice), false);
        take(VertexDim(b, DimLight), true);
        take(VertexDim(b, DimScatter), true);
        take(VertexDim(b, DimScatterLobe), false);
        take(VertexDim(b, DimBsdf), true);
        take(VertexDim(b, DimBsdfLobe), false);
        take(VertexDim(b, DimRoulette), false);
    }
    // Dense: the film's pixel dimensions first, then every prime in order, ten per bounce.
    EXPECT_EQ(used.size(), 5u + 100 * 10);
    EXPECT_EQ(*used.rbegin(), 5u + 100 * 10 - 1);
    EXPECT_EQ(HaltonDim(VertexDim(0, DimLightChoice), false), 5u);
    // Anything else is left to the per-pixel patterns, never to a shared prime: the
    // all-lights strategy's per-light dimensions, a 1-D slot drawn as 2-D, bounces past the
    // primes.
    EXPECT_EQ(HaltonDim(VertexDim(0, DimLight) + 0x10000u, true), NoHaltonDim);
    EXPECT_EQ(HaltonDim(VertexDim(0, DimScatterLobe), true), NoHaltonDim);
    EXPECT_EQ(HaltonDim(VertexDim(1000, DimBsdf), true), NoHaltonDim);
    EXPECT_EQ(HaltonDim(5, true), NoHaltonDim);
}

// A pass that starts at sample k draws the points samples k, k + 1, ... of one render draw.
TEST(Halton, PassesContinueTheSequence) {
    HaltonFrame whole = HaltonFrame::ForResolution(16, 16, HaltonScramble::PermuteDigits);
    HaltonFrame pass = whole;
    pass.firstSample = 4;
    PixelSamples a{3, 5, 6, 8, SamplePattern::Halton, 0, {}};
    PixelSamples b{3, 5, 2, 4, SamplePattern::Halton, 0, {}};
    a.halton = &whole;
    b.halton = &pass;
    for (uint32_t d : {0u, 2u, VertexDim(0, DimLight), VertexDim(3, DimBsdf)}) {
        EXPECT_EQ(a.Get2D(d).x, b.Get2D(d).x) << d;
        EXPECT_EQ(a.Get2D(d).y, b.Get2D(d).y) << d;
    }
    for (uint32_t d : {1u, VertexDim(0, DimLightChoice), VertexDim(2, DimRoulette)})
        EXPECT_EQ(a.Get1D(d), b.Get1D(d)) << d;
    // The dimensions Halton leaves to the per-pixel patterns are drawn anew in each pass.
    PixelSamples c = b;
    HaltonFrame first = whole;
    c.halton = &first;
    const uint32_t other = VertexDim(0, DimLight) + 0x10000u;
    EXPECT_NE(b.Get2D(other).x, c.Get2D(other).x);
}

}  // namespace
}  // namespace prism
