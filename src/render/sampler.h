// Deterministic stratified sample patterns: correlated multi-jittered sampling
// (Kensler 2013, "Correlated Multi-Jittered Sampling"), which stratifies any sample count N in
// 1-D and 2-D. Every pattern is a pure function of (index, count, pattern seed).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/vecmath.h"
#include "render/sobol.h"

namespace prism {

// How far a render follows its paths: the longest path (Integrator "maxdepth", --maxdepth) and
// the ray-weight cutoff (0: every ray; BuildSettings::rayCutoff). The scene holds the file's
// (RenderScene::trace); a render may use others (RenderOptions::trace: the studies' references).
struct TraceSettings {
    int maxDepth = 5;
    float rayCutoff = 0;
};

// A permutation length's parts that depend on it alone: the length, its bit mask w, and
// whether it is a power of two (then the final modulo is a mask).
struct PermutationLength {
    uint32_t l = 0, w = 0;
    bool pow2 = false;
    PermutationLength() = default;
    explicit PermutationLength(uint32_t len) : l(len) {
        w = len > 0 ? len - 1 : 0;
        w |= w >> 1;
        w |= w >> 2;
        w |= w >> 4;
        w |= w >> 8;
        w |= w >> 16;
        pow2 = len > 0 && (len & (len - 1)) == 0;
    }
};

// Element i of the permutation of [0, pm.l) chosen by p (Kensler, "Correlated Multi-Jittered
// Sampling", 2013: cycle-walking a hash over the next power of two).
inline uint32_t PermuteIndex(uint32_t i, const PermutationLength &pm, uint32_t p) {
    if (pm.l <= 1) return 0;
    const uint32_t w = pm.w, l = pm.l;
    do {
        i ^= p;
        i *= 0xe170893d;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3f;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | p >> 27;
        i *= 0x6935fa69;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3;
        i ^= (i & w) >> 2;
        i *= 0xc860a3df;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return pm.pow2 ? (i + p) & (l - 1) : (i + p) % l;
}

inline uint32_t PermuteIndex(uint32_t i, uint32_t l, uint32_t p) {
    return PermuteIndex(i, PermutationLength(l), p);
}

inline float HashFloat(uint32_t i, uint32_t p) {
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i *= 0xb36534e5;
    i ^= i >> 12;
    i ^= i >> 21;
    i *= 0x93fc4795;
    i ^= 0xdf6e307f;
    i ^= i >> 17;
    i *= 1 | p >> 18;
    return std::min(float(i) * (1.0f / 4294967808.0f), 0x1.fffffep-1f);
}

// The strata of an N-sample pattern: m columns by n rows with m n = N exactly, as square as
// N's divisors allow (n the largest divisor of N not above sqrt N; a prime N gives N x 1, a
// Latin hypercube that still has N strata along each axis). Kensler's m = ceil(sqrt N),
// n = ceil(N / m) leaves part of the last row of strata empty when m n > N, and that band of
// every pixel then gets too little weight, an error that no spp averages out (whitted at
// 21 spp had 5x the error of 64 spp and more than 8 spp had; docs/ACCURACY.md). Square and
// m (m - 1) counts keep the grid they had.
struct CMJGrid {
    uint32_t m = 1, n = 1;
    explicit CMJGrid(uint32_t N) {
        if (N == 0) return;
        uint32_t d = uint32_t(std::sqrt(double(N)));
        while (d > 1 && N % d != 0) --d;
        n = d;
        m = N / d;
    }
};

// CMJGrid(N) for CMJSample's calls, which repeat the same N (the light samples of a render):
// the divisor search runs once per thread per count.
inline CMJGrid CachedCMJGrid(uint32_t N) {
    thread_local uint32_t lastN = 1;
    thread_local CMJGrid last(1);
    if (N != lastN) {
        last = CMJGrid(N);
        lastN = N;
    }
    return last;
}

// Sample s of an N-sample correlated multi-jittered pattern in [0,1)^2.
inline Vec2f CMJSample(uint32_t s, uint32_t N, uint32_t p) {
    const CMJGrid grid = CachedCMJGrid(N);
    const uint32_t m = grid.m, n = grid.n;
    s = PermuteIndex(s, N, p * 0x51633e2d);
    uint32_t sx = PermuteIndex(s % m, m, p * 0x68bc21eb);
    uint32_t sy = PermuteIndex(s / m, n, p * 0x02e5be93);
    float jx = HashFloat(s, p * 0x967a889b);
    float jy = HashFloat(s, p * 0x368cc8b7);
    float x = (float(s % m) + (float(sy) + jx) / float(n)) / float(m);
    float y = (float(s / m) + (float(sx) + jy) / float(m)) / float(n);
    return {std::min(x, 0x1.fffffep-1f), std::min(y, 0x1.fffffep-1f)};
}

// CMJSample for one sample count N, with what depends only on N computed once (m, n, the
// permutation masks): a loop over a pixel's samples pays for no sqrt, and power-of-two counts
// and strata (1, 4, 16, 64 spp) use masks and shifts where CMJSample divides. Sample(s, p) ==
// CMJSample(s, N, p) bit for bit (tests/render/sampler_test.cpp).
class CMJPattern {
  public:
    explicit CMJPattern(uint32_t N) : N_(N) {
        CMJGrid grid(N);
        m_ = grid.m;
        n_ = grid.n;
        pN_ = PermutationLength(N_);
        pm_ = PermutationLength(m_);
        pn_ = PermutationLength(n_);
        mPow2_ = (m_ & (m_ - 1)) == 0;
        mShift_ = 0;
        while ((1u << mShift_) < m_) ++mShift_;
        invN_ = 1.0f / float(n_);
        invM_ = 1.0f / float(m_);
        nPow2_ = (n_ & (n_ - 1)) == 0;
    }

    Vec2f Sample(uint32_t s, uint32_t p) const {
        s = PermuteIndex(s, pN_, p * 0x51633e2d);
        uint32_t sm = mPow2_ ? s & (m_ - 1) : s % m_;
        uint32_t sd = mPow2_ ? s >> mShift_ : s / m_;
        uint32_t sx = PermuteIndex(sm, pm_, p * 0x68bc21eb);
        uint32_t sy = PermuteIndex(sd, pn_, p * 0x02e5be93);
        float jx = HashFloat(s, p * 0x967a889b);
        float jy = HashFloat(s, p * 0x368cc8b7);
        // x / 2^k == x * 2^-k exactly; other counts divide as CMJSample does.
        float x = (float(sm) + (nPow2_ ? (float(sy) + jx) * invN_ : (float(sy) + jx) / float(n_)));
        x = mPow2_ ? x * invM_ : x / float(m_);
        float y = (float(sd) + (mPow2_ ? (float(sx) + jy) * invM_ : (float(sx) + jy) / float(m_)));
        y = nPow2_ ? y * invN_ : y / float(n_);
        return {std::min(x, 0x1.fffffep-1f), std::min(y, 0x1.fffffep-1f)};
    }

  private:
    uint32_t N_, m_, n_, mShift_;
    PermutationLength pN_, pm_, pn_;
    bool mPow2_, nPow2_;
    float invN_, invM_;
};

// The samples the path and directlighting integrators draw per dimension
// (render/light_sampling.h PixelSamples): Stratified, a correlated multi-jittered pattern per
// dimension (pbrt's "stratified"); ZeroTwo, pbrt-v3's ZeroTwoSequenceSampler ("02sequence",
// "lowdiscrepancy": a scrambled (0,2)-sequence per dimension, its samples shuffled across the
// pixel); Independent, pbrt's RandomSampler; PaddedSobol, pbrt-v4's "paddedsobol" (an
// Owen-scrambled (0,2)-sequence per dimension, shuffled like ZeroTwo); ZSobol, pbrt-v4's
// "zsobol" (one Owen-scrambled Sobol sequence over the film, its pixels in permuted Morton
// order: render/sobol.h ZSobolIndex); Halton, pbrt's "halton" (one randomised Halton sequence
// over the film: render/halton.h); Sobol, pbrt's "sobol" (one Sobol sequence over the film:
// render/sobol_sampler.h).
enum class SamplePattern : uint8_t {
    Stratified,
    ZeroTwo,
    Independent,
    PaddedSobol,
    ZSobol,
    Halton,
    Sobol
};
inline bool IsSobolPattern(SamplePattern p) {
    return p == SamplePattern::PaddedSobol || p == SamplePattern::ZSobol;
}
// The patterns that draw the camera's film, time and lens samples as dimensions 0 to 2 of
// PixelSamples (pbrt-v4 draws them from its sampler first), not from the camera's own
// correlated multi-jittered patterns.
inline bool DrawsCameraDims(SamplePattern p) {
    return IsSobolPattern(p) || p == SamplePattern::Halton || p == SamplePattern::Sobol;
}

// pbrt-v3's scrambled (0,2)-sequence point n: van der Corput in x, Sobol's second dimension in
// y, each XORed with a scramble (lowdiscrepancy.h Sample02).
inline Vec2f Sample02(uint32_t n, uint32_t scrambleX, uint32_t scrambleY) {
    uint32_t r = n;
    r = (r << 16) | (r >> 16);
    r = ((r & 0x00ff00ffu) << 8) | ((r & 0xff00ff00u) >> 8);
    r = ((r & 0x0f0f0f0fu) << 4) | ((r & 0xf0f0f0f0u) >> 4);
    r = ((r & 0x33333333u) << 2) | ((r & 0xccccccccu) >> 2);
    r = ((r & 0x55555555u) << 1) | ((r & 0xaaaaaaaau) >> 1);
    uint32_t y = scrambleY;
    for (uint32_t v = 1u << 31; n != 0; n >>= 1, v ^= v >> 1)
        if (n & 1) y ^= v;
    return {std::min(float(r ^ scrambleX) * 0x1p-32f, 0x1.fffffep-1f),
            std::min(float(y) * 0x1p-32f, 0x1.fffffep-1f)};
}

// The purposes of the camera samples' patterns: every tile loop (the kernel's, the path
// integrators', the AOV pass, bench's ceiling) draws the same film positions, lens samples and
// ray times from them. TimePurpose is a pattern of its own, so the time dimension shifts no
// other.
enum SamplePurpose : uint32_t { FilmPurpose = 0, LensPurpose = 1, TimePurpose = 0x74696d65 };

// The film position of sample u in [0, 1)^2 of pixel (x, y). float(x) + u rounds up to x + 1
// when u is within half an ulp of 1 (about 1 sample in 30,000 at x ~ 1000); such a sample is
// kept on the pixel's last float, so every sample lies in the pixel it was drawn for (the
// film resolves box-filtered tiles in place on this: image/film.h TiledFilm::ResolvesTiles).
inline Vec2f FilmPosition(int x, int y, Vec2f u) {
    const float px = float(x) + u.x, py = float(y) + u.y;
    const float ex = float(x + 1), ey = float(y + 1);
    return Vec2f(px < ex ? px : NextFloatDown(ex), py < ey ? py : NextFloatDown(ey));
}

// Pattern seed for a pixel and a purpose (film position, light k, ...).
inline uint32_t PatternSeed(int x, int y, uint32_t purpose, uint32_t seed = 0) {
    uint64_t h = (uint64_t(uint32_t(x)) * 0x9E3779B1u) ^ (uint64_t(uint32_t(y)) << 32);
    h ^= uint64_t(purpose) * 0xC2B2AE3D27D4EB4FULL + seed;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    return uint32_t(h);
}

// PaddedSobol's sample i of n: point PermuteIndex(i) of the scrambled (0,2)-sequence's first
// n, so every dimension's n points are a prefix of the sequence (a (0,m,2)-net when n = 2^m)
// and the shuffle pairs them with the other dimensions' at random.
inline Vec2f PaddedSobolSample2D(uint32_t i, uint32_t n, uint32_t seed, SobolScramble s) {
    const uint64_t h = MixBits64(uint64_t(seed) * 0x9e3779b97f4a7c15ull + 1);
    return SobolSample2D(PermuteIndex(i, n, seed), uint32_t(h), uint32_t(h >> 32), s);
}
inline float PaddedSobolSample1D(uint32_t i, uint32_t n, uint32_t seed, SobolScramble s) {
    const uint32_t h = uint32_t(MixBits64(uint64_t(seed) * 0x9e3779b97f4a7c15ull + 2) >> 32);
    return BitsToUnit(Scramble(SobolBits0(PermuteIndex(i, n, seed)), h, s));
}

// ZSobol's sample i of n of pixel (x, y) in dimension dim: one scramble per dimension for the
// whole film (the index tells pixels apart). Index bits above the 32 the points resolve (films
// and counts past 2^32 samples) pick the scramble, so no two pixels share their samples.
inline Vec2f ZSobolSample2D(int x, int y, uint32_t i, uint32_t n, int log2Res, uint32_t dim,
                            uint32_t passSeed, SobolScramble s) {
    const uint64_t index = ZSobolIndex(uint32_t(x), uint32_t(y), i, CeilLog2(n), log2Res, dim);
    const uint64_t h =
        MixBits64((uint64_t(dim) << 32 | passSeed) ^ MixBits64((index >> 32) + 0x2d));
    return SobolSample2D(uint32_t(index), uint32_t(h), uint32_t(h >> 32), s);
}
inline float ZSobolSample1D(int x, int y, uint32_t i, uint32_t n, int log2Res, uint32_t dim,
                            uint32_t passSeed, SobolScramble s) {
    // 1-D dimensions are their own family, as PixelSamples' seeds are.
    const uint32_t d = dim | 0x80000000u;
    const uint64_t index = ZSobolIndex(uint32_t(x), uint32_t(y), i, CeilLog2(n), log2Res, d);
    const uint64_t h = MixBits64((uint64_t(d) << 32 | passSeed) ^ MixBits64((index >> 32) + 0x2d));
    return BitsToUnit(Scramble(SobolBits0(uint32_t(index)), uint32_t(h), s));
}

}  // namespace prism
