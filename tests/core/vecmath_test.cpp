#include "core/vecmath.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace prism {

// NextFloatUp/Down step through the bits instead of calling std::nextafter: the same floats,
// bit for bit, for normals, denormals, both zeros, the extremes, infinities and NaN.
TEST(Vecmath, NextFloatMatchesNextafter) {
    const float inf = std::numeric_limits<float>::infinity();
    const float cases[] = {0.f,
                           -0.f,
                           1.f,
                           -1.f,
                           0.5f,
                           3.14159f,
                           -2.5e-3f,
                           1e30f,
                           -1e30f,
                           std::numeric_limits<float>::min(),
                           -std::numeric_limits<float>::min(),
                           std::numeric_limits<float>::denorm_min(),
                           -std::numeric_limits<float>::denorm_min(),
                           std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::max(),
                           inf,
                           -inf};
    for (float v : cases) {
        EXPECT_EQ(std::bit_cast<uint32_t>(NextFloatUp(v)),
                  std::bit_cast<uint32_t>(std::nextafter(v, inf)))
            << v;
        EXPECT_EQ(std::bit_cast<uint32_t>(NextFloatDown(v)),
                  std::bit_cast<uint32_t>(std::nextafter(v, -inf)))
            << v;
    }
    // Every 4099th float of one sign's range, both signs.
    for (uint32_t bits = 0; bits < 0x7f800000u; bits += 4099u)
        for (uint32_t sign : {0u, 0x80000000u}) {
            const float v = std::bit_cast<float>(bits | sign);
            ASSERT_EQ(NextFloatUp(v), std::nextafter(v, inf)) << v;
            ASSERT_EQ(NextFloatDown(v), std::nextafter(v, -inf)) << v;
        }
    EXPECT_TRUE(std::isnan(NextFloatUp(std::nanf(""))));
    EXPECT_TRUE(std::isnan(NextFloatDown(std::nanf(""))));
}

}  // namespace prism
