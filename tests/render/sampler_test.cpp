#include "render/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace prism {

// CMJPattern precomputes CMJSample's per-count constants; it must give the same bits.
TEST(CMJPattern, MatchesCMJSampleBitForBit) {
    for (uint32_t N = 1; N <= 70; ++N) {
        CMJPattern pat(N);
        for (uint32_t p : {0u, 1u, 7u, 0x12345678u, 0xdeadbeefu, 0xffffffffu}) {
            for (uint32_t s = 0; s < N; ++s) {
                Vec2f a = CMJSample(s, N, p), b = pat.Sample(s, p);
                ASSERT_EQ(std::memcmp(&a.x, &b.x, sizeof(float)), 0) << N << " " << p << " " << s;
                ASSERT_EQ(std::memcmp(&a.y, &b.y, sizeof(float)), 0) << N << " " << p << " " << s;
            }
        }
    }
    for (uint32_t N : {256u, 1024u, 1000u}) {
        CMJPattern pat(N);
        for (uint32_t s = 0; s < N; s += 7) {
            uint32_t p = PatternSeed(int(s), 3, 1);
            Vec2f a = CMJSample(s, N, p), b = pat.Sample(s, p);
            ASSERT_EQ(std::memcmp(&a, &b, sizeof(Vec2f)), 0) << N << " " << s;
        }
    }
}

}  // namespace prism

namespace prism {

// Every count fills its grid of strata: each of the m x n cells (m n = N) holds exactly one
// sample, and each of the N columns and N rows of width 1/N holds exactly one (the
// multi-jittered property). Kensler's grid m = ceil(sqrt N), n = ceil(N / m) fails the first for
// N = 3, 5, 7, 8, 21, ...: part of its last row stays empty.
TEST(CMJPattern, EveryCountFillsItsStrata) {
    for (uint32_t N = 1; N <= 300; ++N) {
        CMJGrid grid(N);
        ASSERT_EQ(grid.m * grid.n, N);
        ASSERT_GE(grid.m, grid.n);
        for (uint32_t p : {0u, 5u, 0x9e3779b9u}) {
            std::vector<int> cells(N, 0), cols(N, 0), rows(N, 0);
            CMJPattern pat(N);
            for (uint32_t s = 0; s < N; ++s) {
                Vec2f u = pat.Sample(s, p);
                ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1);
                uint32_t cx = std::min(uint32_t(u.x * float(grid.m)), grid.m - 1);
                uint32_t cy = std::min(uint32_t(u.y * float(grid.n)), grid.n - 1);
                ++cells[cy * grid.m + cx];
                ++cols[std::min(uint32_t(double(u.x) * N), N - 1)];
                ++rows[std::min(uint32_t(double(u.y) * N), N - 1)];
            }
            for (uint32_t i = 0; i < N; ++i) {
                ASSERT_EQ(cells[i], 1) << "N " << N << " cell " << i;
                ASSERT_EQ(cols[i], 1) << "N " << N << " column " << i;
                ASSERT_EQ(rows[i], 1) << "N " << N << " row " << i;
            }
        }
    }
    EXPECT_EQ(CMJGrid(21).m, 7u);
    EXPECT_EQ(CMJGrid(16).m, 4u);
    EXPECT_EQ(CMJGrid(12).m, 4u);  // m (m - 1) counts keep Kensler's grid
    EXPECT_EQ(CMJGrid(23).m, 23u);
}

}  // namespace prism

namespace prism {

// Every film position lies in the pixel it was drawn for, even where float(x) + u rounds up
// to x + 1; elsewhere it is that sum, unchanged.
TEST(FilmPosition, StaysInItsPixel) {
    const float belowOne = std::nextafter(1.f, 0.f);
    for (int x : {0, 1, 7, 600, 1599, 4095, 100000}) {
        for (float u : {0.f, 0.25f, 0.5f, 0.999f, 1 - 1e-6f, belowOne}) {
            const Vec2f p = FilmPosition(x, x + 3, Vec2f(u, u));
            EXPECT_EQ(int(std::floor(p.x)), x) << x << " " << u;
            EXPECT_EQ(int(std::floor(p.y)), x + 3) << x << " " << u;
            if (float(x) + u < float(x + 1)) EXPECT_EQ(p.x, float(x) + u);
        }
    }
    // The case it exists for: at x = 1599, x + (1 - 2^-24) rounds to 1600.
    EXPECT_EQ(1599.f + belowOne, 1600.f);
    EXPECT_LT(FilmPosition(1599, 0, Vec2f(belowOne, 0)).x, 1600.f);
}

}  // namespace prism
