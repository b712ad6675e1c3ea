// Deterministic hashing and random numbers: every sample is a pure function of
// (pixel, sample index, dimension, seed), so images do not depend on thread scheduling.
#pragma once

#include <cstdint>

namespace prism {

// 64-bit finalizer (MurmurHash3 fmix64 constants).
inline uint64_t MixBits(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
    v ^= v >> 33;
    return v;
}

inline uint64_t Hash(uint64_t a, uint64_t b = 0, uint64_t c = 0, uint64_t d = 0) {
    uint64_t h = MixBits(a + 0x9e3779b97f4a7c15ULL);
    h = MixBits(h ^ (b + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2)));
    h = MixBits(h ^ (c + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2)));
    h = MixBits(h ^ (d + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2)));
    return h;
}

// A uniform float in [0, 1) from the top 24 bits.
inline float UniformFloat(uint64_t h) { return float(h >> 40) * 0x1p-24f; }

// PCG32 (O'Neill 2014): small, fast, statistically good stream generator.
class PCG32 {
public:
    explicit PCG32(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL) {
        Seed(seed, stream);
    }
    void Seed(uint64_t seed, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        Next();
        state_ += seed;
        Next();
    }
    uint32_t Next() {
        uint64_t old = state_;
        state_ = old * 0x5851f42d4c957f2dULL + inc_;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }
    float Uniform() { return float(Next() >> 8) * 0x1p-24f; }
    double UniformDouble() {
        uint64_t v = (uint64_t(Next()) << 32) | Next();
        return double(v >> 11) * 0x1p-53;
    }

private:
    uint64_t state_, inc_;
};

}  // namespace prism
