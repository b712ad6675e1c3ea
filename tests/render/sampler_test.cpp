#include "render/sampler.h"

#include <gtest/gtest.h>

#include <cstring>

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
