// Deterministic random numbers: every sample is a pure function of
// (pixel, sample index, dimension, seed), so images do not depend on thread scheduling.
#pragma once

#include <cstdint>

namespace prism {

// SplitMix64's finaliser (Stafford's mix 13): a 64-bit hash whose every output bit depends on
// every input bit, for seeds that must not correlate with their neighbours'.
inline uint64_t MixBits64(uint64_t v) {
    v ^= v >> 30;
    v *= 0xbf58476d1ce4e5b9ull;
    v ^= v >> 27;
    v *= 0x94d049bb133111ebull;
    return v ^ (v >> 31);
}

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
