// pbrt's "sobol" sampler (pbrt-v3's SobolSampler and pbrt-v4's): one Sobol sequence over the
// whole film. Dimensions 0 and 1 of a point, scaled by the film's size rounded up to a power
// of two, fall in one pixel; a pixel's samples are the sequence's points that fall in it, in
// order, found by solving for the index bits that pick the pixel (pbrt's
// SobolIntervalToIndex). The other dimensions are Sobol's with Joe and Kuo's direction numbers
// ("new-joe-kuo-6.21201", as Boost.Random tabulates them), randomised per dimension: a nested
// uniform (Owen) scramble, pbrt-v4's default; a random XOR; or none, as pbrt-v3 draws them.
#pragma once

#include <array>
#include <cstdint>

#include "core/vecmath.h"
#include "render/sobol.h"

namespace prism {

// The dimensions of the sequence; pbrt's sampler dimensions past them start again at 2.
inline constexpr uint32_t SobolDimensions = 1024;

// Dimension `dim` (< SobolDimensions) of point `index` of Sobol's sequence, a 32-bit binary
// fraction.
uint32_t SobolPoint(uint64_t index, uint32_t dim);

// The film's Sobol sequence: pixels within scale x scale, scale = 2^log2Scale the film's
// larger side rounded up to a power of two.
struct SobolFrame {
    int log2Scale = 0;
    uint32_t scale = 1;
    SobolScramble scramble = SobolScramble::Owen;
    // The pass's first sample: a progressive render's passes continue the pixels' points.
    uint64_t firstSample = 0;
    // The inverse over GF(2) of the matrix taking index bits log2Scale to 2 log2Scale - 1 to
    // dimension 1's top log2Scale bits, as its columns.
    std::array<uint32_t, 32> inverse{};

    static SobolFrame ForResolution(int width, int height, SobolScramble s);
    // The index of point `sample` of pixel (x, y) (0 <= x, y < scale).
    uint64_t Index(int x, int y, uint64_t sample) const;
    // Point `index`'s position in pixel (x, y), dimensions 0 and 1, not randomised.
    Vec2f PixelOffset(uint64_t index, int x, int y) const;
    // Dimension `dim` >= 2 of point `index`, randomised by the frame's scramble and `seed`.
    float Sample(uint64_t index, uint32_t dim, uint32_t seed) const;
};

}  // namespace prism
