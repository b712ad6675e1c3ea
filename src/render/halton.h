// pbrt-v4's "halton" sampler: one Halton sequence over the whole film. Dimension i of point n
// is the radical inverse of n in the i-th prime; the first two (bases 2 and 3) are scaled so
// the film's pixels tile them (up to 128 x 128 pixels, then repeating), and the points of a
// pixel are found by inverting that scaling (the Chinese remainder theorem over 2^j and 3^k).
// The other dimensions are randomised per dimension: random digit permutations (pbrt-v4's
// default "permutedigits"), a nested Owen scramble in base b ("owen"), or none.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "core/vecmath.h"

namespace prism {

enum class HaltonScramble : uint8_t { PermuteDigits, Owen, None };

// The random digit permutations of one seed, tabulated per dimension when first asked for
// (thread-safe): digit j of the dimension's base goes to Permutation(j)[digit], and Tail(j) is
// what the zero digits from j on contribute, so a point costs a lookup per digit of its index.
// The same permutations HaltonSample draws without them.
class HaltonPermutations {
  public:
    explicit HaltonPermutations(uint32_t seed);
    uint32_t Seed() const { return seed_; }
    struct Dim {
        uint32_t base = 2;
        int digits = 0;              // digits until base^-digits is below float resolution
        std::vector<uint16_t> perm;  // digits x base
        std::vector<double> tail;    // digits + 1
    };
    const Dim &Get(uint32_t dim) const;

  private:
    uint32_t seed_;
    std::unique_ptr<std::once_flag[]> once_;
    std::unique_ptr<std::unique_ptr<Dim>[]> dims_;
};

// The film's tiling of the first two dimensions: 2^expX >= min(width, 128) columns and
// 3^expY >= min(height, 128) rows of pixels per period of the sequence.
struct HaltonFrame {
    uint8_t expX = 0, expY = 0;
    uint32_t scaleX = 1, scaleY = 1;  // 2^expX, 3^expY
    uint64_t stride = 1;              // scaleX * scaleY: points per visit of every pixel
    uint64_t multInvX = 0, multInvY = 0;
    HaltonScramble scramble = HaltonScramble::PermuteDigits;
    // The pass's first sample: a progressive render's passes continue one sequence, so its
    // passes together draw the points one render of their total count draws.
    uint64_t firstSample = 0;
    // PermuteDigits' tables for the render's seed (null: computed per point).
    std::shared_ptr<const HaltonPermutations> permutations;

    static HaltonFrame ForResolution(int width, int height, HaltonScramble s, uint32_t seed = 0);
    // The index of the first point of pixel (x, y): the others are it + i * stride.
    uint64_t PixelIndex(int x, int y) const;
    // Point `index`'s position within its pixel (dimensions 0 and 1, not scrambled; a
    // non-zero passSeed, a later pass of a progressive render, shifts them toroidally).
    Vec2f PixelOffset(uint64_t index, uint32_t passSeed = 0) const;
};

// Dimension `dim` (>= 2) of point `index`, randomised as the frame says. Dimensions past the
// prime table (HaltonDimensions) wrap around to 2, as pbrt-v4's do past its 1000 primes.
// `passSeed` (SamplerSettings::seed: the scene's seed, and a progressive render's later
// passes) changes the randomisation.
float HaltonSample(const HaltonFrame &frame, uint64_t index, uint32_t dim, uint32_t passSeed = 0);
inline constexpr uint32_t HaltonDimensions = 2048;

// The Halton dimension of PixelSamples' dimension `dim` (render/light_sampling.h) drawn as a
// 2-D sample (it takes h and h + 1) or a 1-D one, in the order pbrt's paths draw them (the
// global Sobol pattern numbers its dimensions the same way): the
// film position 0 and 1 (the pixel's own dimensions), the time 2, the lens 3 and 4, then per
// bounce ten: the light choice, the point on the light (2), the direct-lighting BSDF sample
// (2) and its lobe, the path's BSDF sample (2) and its lobe, the roulette. So the first
// bounces get the small primes. NoHaltonDim for any other dimension (the all-lights
// strategy's per-light dimensions, bounces past the prime table, a 1-D slot drawn as 2-D):
// the caller draws those from a per-pixel stratified pattern, never from a shared prime.
inline constexpr uint32_t NoHaltonDim = ~0u;
uint32_t HaltonDim(uint32_t dim, bool twoD);

}  // namespace prism
