// Owen-scrambled Sobol points: the samples of pbrt-v4's "paddedsobol" and "zsobol" samplers
// (render/sampler.h SamplePattern::PaddedSobol, ZSobol). Each 2-D sample is a point of the
// first two dimensions of Sobol's sequence, a (0,2)-sequence in base 2, whose every aligned run
// of 2^m points is a (0,m,2)-net; a nested uniform (Owen) scramble keeps that stratification
// and makes each point uniform on [0,1)^2, so estimates stay unbiased.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/rng.h"
#include "core/vecmath.h"

namespace prism {

inline uint32_t ReverseBits32(uint32_t v) {
    v = (v << 16) | (v >> 16);
    v = ((v & 0x00ff00ffu) << 8) | ((v & 0xff00ff00u) >> 8);
    v = ((v & 0x0f0f0f0fu) << 4) | ((v & 0xf0f0f0f0u) >> 4);
    v = ((v & 0x33333333u) << 2) | ((v & 0xccccccccu) >> 2);
    return ((v & 0x55555555u) << 1) | ((v & 0xaaaaaaaau) >> 1);
}

// How a Sobol point is randomised (pbrt-v4's "randomization" parameter): Owen, a nested
// uniform scramble (pbrt-v4's "fastowen" and "owen"); Xor, a random binary digit permutation
// (pbrt-v4's "permutedigits" in base 2: one XOR); None, the bare sequence.
enum class SobolScramble : uint8_t { Owen, Xor, None };

// A nested uniform scramble of the 32-bit binary fraction v: bit i is flipped by a function of
// the seed and of the bits above it only, so every elementary interval of the point set maps
// onto one of the same shape. Laine and Karras's hash on the reversed bits (there, additions,
// odd multiplications and x ^= x * even carry information from lower to higher bits only),
// with the rounds of N. Vegdahl's "Building a better LK hash" (2021), which also mix the top
// two levels (Burley 2020's constants leave the second bit independent of the first).
inline uint32_t OwenScramble(uint32_t v, uint32_t seed) {
    v = ReverseBits32(v);
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return ReverseBits32(v);
}

inline uint32_t Scramble(uint32_t v, uint32_t seed, SobolScramble s) {
    switch (s) {
        case SobolScramble::Owen:
            return OwenScramble(v, seed);
        case SobolScramble::Xor:
            return v ^ seed;
        default:
            return v;
    }
}

// Sobol's first dimension (van der Corput in base 2) and second (the Pascal matrix mod 2) of
// point n, as 32-bit binary fractions.
inline uint32_t SobolBits0(uint32_t n) { return ReverseBits32(n); }
inline uint32_t SobolBits1(uint32_t n) {
    uint32_t y = 0;
    for (uint32_t v = 1u << 31; n != 0; n >>= 1, v ^= v >> 1)
        if (n & 1) y ^= v;
    return y;
}

inline float BitsToUnit(uint32_t v) { return std::min(float(v) * 0x1p-32f, 0x1.fffffep-1f); }

// Point n of the scrambled 2-D Sobol sequence, each axis with its own seed.
inline Vec2f SobolSample2D(uint32_t n, uint32_t seedX, uint32_t seedY, SobolScramble s) {
    return {BitsToUnit(Scramble(SobolBits0(n), seedX, s)),
            BitsToUnit(Scramble(SobolBits1(n), seedY, s))};
}

// The Morton code of pixel (x, y): x's bits at the even positions, y's at the odd ones.
inline uint64_t MortonCode2(uint32_t x, uint32_t y) {
    auto spread = [](uint64_t v) {
        v &= 0xffffffffull;
        v = (v | (v << 16)) & 0x0000ffff0000ffffull;
        v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
        v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
        v = (v | (v << 2)) & 0x3333333333333333ull;
        v = (v | (v << 1)) & 0x5555555555555555ull;
        return v;
    };
    return spread(x) | (spread(y) << 1);
}

// The index into the global Sobol sequence of sample `sample` (of 2^log2Count) of pixel
// (x, y) in dimension `dim`, for a film whose pixels fit in 2^log2Res x 2^log2Res: the Morton
// order of pixels and samples, each base-4 digit permuted by a hash of the digits above it and
// the dimension (Ahmed and Wonka 2020, "Screen-space blue-noise diffusion of Monte Carlo
// sampling error via hierarchical ordering of pixels"; pbrt-v4's ZSobolSampler). A pixel's
// samples stay one aligned run of the sequence, so they are a (0,m,2)-net as in the padded
// sampler, and neighbouring pixels' runs are spread over the sequence, which turns the error
// between pixels into blue noise.
uint64_t ZSobolIndex(uint32_t x, uint32_t y, uint32_t sample, int log2Count, int log2Res,
                     uint32_t dim);

// ceil(log2(n)) for n >= 1.
inline int CeilLog2(uint64_t n) {
    int k = 0;
    while ((uint64_t(1) << k) < n) ++k;
    return k;
}

}  // namespace prism
