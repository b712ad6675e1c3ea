#include "render/halton.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "render/sampler.h"

namespace prism {

namespace {

// The first HaltonDimensions primes, by a sieve.
const std::vector<uint32_t> &Primes() {
    static const std::vector<uint32_t> primes = [] {
        std::vector<uint32_t> p;
        std::vector<bool> composite(20000, false);
        for (uint32_t i = 2; p.size() < HaltonDimensions; ++i) {
            if (composite[i]) continue;
            p.push_back(i);
            for (uint32_t j = i * i; j < composite.size(); j += i) composite[j] = true;
        }
        return p;
    }();
    return primes;
}

// The nDigits lowest base-`base` digits of `inverse` reversed: the i whose radical inverse,
// times base^nDigits, has integer part `inverse`.
uint64_t InverseRadicalInverse(uint64_t inverse, uint32_t base, int nDigits) {
    uint64_t index = 0;
    for (int i = 0; i < nDigits; ++i) {
        index = index * base + inverse % base;
        inverse /= base;
    }
    return index;
}

// x with a x = 1 mod n (extended Euclid; a and n coprime).
uint64_t MultiplicativeInverse(int64_t a, int64_t n) {
    int64_t t = 0, newT = 1, r = n, newR = a % n;
    while (newR != 0) {
        const int64_t q = r / newR;
        t -= q * newT;
        std::swap(t, newT);
        r -= q * newR;
        std::swap(r, newR);
    }
    return uint64_t(t < 0 ? t + n : t);
}

double RadicalInverse(uint32_t base, uint64_t a) {
    const double inv = 1.0 / base;
    double scale = inv, v = 0;
    while (a > 0) {
        v += double(a % base) * scale;
        a /= base;
        scale *= inv;
    }
    return v;
}

// The key of dimension `dim`'s digit permutations under `seed`, and that of its digit j.
uint64_t DimKey(uint32_t dim, uint32_t seed) {
    return MixBits64((uint64_t(dim) << 32) ^ 0x68616c746f6eull ^
                     (uint64_t(seed) * 0xc2b2ae3d27d4eb4full));
}
uint64_t DigitKey(uint64_t dimKey, int j) {
    return dimKey + 0x9e3779b97f4a7c15ull * uint64_t(j + 1);
}

}  // namespace

HaltonPermutations::HaltonPermutations(uint32_t seed)
    : seed_(seed),
      once_(new std::once_flag[HaltonDimensions]),
      dims_(new std::unique_ptr<Dim>[HaltonDimensions]) {}

const HaltonPermutations::Dim &HaltonPermutations::Get(uint32_t dim) const {
    std::call_once(once_[dim], [&] {
        auto d = std::make_unique<Dim>();
        d->base = Primes()[dim];
        const double inv = 1.0 / d->base;
        std::vector<double> scales;
        for (double s = inv; s > 0x1p-26; s *= inv) scales.push_back(s);
        d->digits = int(scales.size());
        d->perm.resize(size_t(d->digits) * d->base);
        const PermutationLength pl(d->base);
        const uint64_t key = DimKey(dim, seed_);
        for (int j = 0; j < d->digits; ++j) {
            const uint32_t p = uint32_t(MixBits64(DigitKey(key, j)));
            for (uint32_t k = 0; k < d->base; ++k)
                d->perm[size_t(j) * d->base + k] = uint16_t(PermuteIndex(k, pl, p));
        }
        d->tail.assign(size_t(d->digits) + 1, 0.0);
        for (int j = d->digits - 1; j >= 0; --j)
            d->tail[size_t(j)] =
                d->tail[size_t(j) + 1] + double(d->perm[size_t(j) * d->base]) * scales[size_t(j)];
        dims_[dim] = std::move(d);
    });
    return *dims_[dim];
}

HaltonFrame HaltonFrame::ForResolution(int width, int height, HaltonScramble s, uint32_t seed) {
    HaltonFrame f;
    f.scramble = s;
    if (s == HaltonScramble::PermuteDigits)
        f.permutations = std::make_shared<const HaltonPermutations>(seed);
    const int w = std::clamp(width, 1, 128), h = std::clamp(height, 1, 128);
    while (f.scaleX < uint32_t(w)) {
        f.scaleX *= 2;
        ++f.expX;
    }
    while (f.scaleY < uint32_t(h)) {
        f.scaleY *= 3;
        ++f.expY;
    }
    f.stride = uint64_t(f.scaleX) * f.scaleY;
    f.multInvX = f.scaleX > 1 && f.scaleY > 1 ? MultiplicativeInverse(f.scaleY, f.scaleX) : 0;
    f.multInvY = f.scaleX > 1 && f.scaleY > 1 ? MultiplicativeInverse(f.scaleX, f.scaleY) : 0;
    if (f.scaleY == 1) f.multInvX = 1;  // one row: the x digits alone
    if (f.scaleX == 1) f.multInvY = 1;
    return f;
}

uint64_t HaltonFrame::PixelIndex(int x, int y) const {
    if (stride == 1) return 0;
    const uint64_t px = uint64_t(((x % 128) + 128) % 128) % scaleX;
    const uint64_t py = uint64_t(((y % 128) + 128) % 128) % scaleY;
    // The index i has i mod 2^expX = the x digits reversed, i mod 3^expY the y digits reversed;
    // combined modulo the stride.
    const uint64_t ix = InverseRadicalInverse(px, 2, expX);
    const uint64_t iy = InverseRadicalInverse(py, 3, expY);
    const unsigned __int128 a = (unsigned __int128)ix * (stride / scaleX) * multInvX;
    const unsigned __int128 b = (unsigned __int128)iy * (stride / scaleY) * multInvY;
    return uint64_t((a + b) % stride);
}

Vec2f HaltonFrame::PixelOffset(uint64_t index, uint32_t passSeed) const {
    double x = RadicalInverse(2, index >> expX);
    double y = RadicalInverse(3, index / scaleY);
    if (passSeed != 0) {
        const uint64_t h = MixBits64(uint64_t(passSeed) * 0x9e3779b97f4a7c15ull);
        x += double(h >> 40) * 0x1p-24;
        y += double(h & 0xffffff) * 0x1p-24;
        x -= std::floor(x);
        y -= std::floor(y);
    }
    return {std::min(float(x), 0x1.fffffep-1f), std::min(float(y), 0x1.fffffep-1f)};
}

float HaltonSample(const HaltonFrame &f, uint64_t index, uint32_t dim, uint32_t passSeed) {
    if (dim >= HaltonDimensions) dim = 2 + (dim - 2) % (HaltonDimensions - 2);
    const uint32_t base = Primes()[dim];
    if (f.scramble == HaltonScramble::None)
        return std::min(float(RadicalInverse(base, index)), 0x1.fffffep-1f);
    if (f.scramble == HaltonScramble::PermuteDigits && f.permutations &&
        f.permutations->Seed() == passSeed) {
        // The index's own digits through their tables, then the zero digits' tail at once.
        const HaltonPermutations::Dim &d = f.permutations->Get(dim);
        const double inv = 1.0 / base;
        double scale = inv, v = 0;
        int j = 0;
        for (; index != 0 && j < d.digits; ++j) {
            v += double(d.perm[size_t(j) * base + index % base]) * scale;
            index /= base;
            scale *= inv;
        }
        v += d.tail[size_t(j)];
        return std::min(float(v), 0x1.fffffep-1f);
    }
    // Digit j of the index (0 past its length) goes through a permutation of [0, base): one
    // per dimension and digit (permutedigits), or one per digit prefix too (owen), so the
    // infinite run of zero digits past the index's length is permuted as well. Digits stop
    // counting below float resolution.
    const double inv = 1.0 / base;
    double scale = inv, v = 0;
    uint64_t prefix = 0;
    const PermutationLength pl(base);
    const uint64_t dimKey = DimKey(dim, passSeed);
    for (int j = 0; scale > 0x1p-26; ++j) {
        const uint32_t digit = uint32_t(index % base);
        index /= base;
        uint64_t key = DigitKey(dimKey, j);
        if (f.scramble == HaltonScramble::Owen) key = MixBits64(key ^ prefix);
        const uint32_t p = PermuteIndex(digit, pl, uint32_t(MixBits64(key)));
        v += double(p) * scale;
        scale *= inv;
        prefix = prefix * base + digit + 1;
    }
    return std::min(float(v), 0x1.fffffep-1f);
}

uint32_t HaltonDim(uint32_t dim, bool twoD) {
    // PathDimBase 16, 16 dimensions per bounce, of which 0 to 6 are drawn (PathDim): each
    // slot's offset among a bounce's ten Halton dimensions, and whether it is 2-D.
    struct Slot {
        uint8_t offset;
        bool twoD;
    };
    static constexpr Slot kSlots[7] = {{0, false}, {1, true},  {3, true}, {5, false},
                                       {6, true},  {8, false}, {9, false}};
    if (dim == 0) return twoD ? 0 : NoHaltonDim;
    if (dim == 1) return twoD ? NoHaltonDim : 2;
    if (dim == 2) return twoD ? 3 : NoHaltonDim;
    if (dim < 16 || dim >= 0x10000u || (dim - 16) % 16 >= 7) return NoHaltonDim;
    const Slot s = kSlots[(dim - 16) % 16];
    if (s.twoD != twoD) return NoHaltonDim;
    const uint64_t h = 5 + 10 * uint64_t((dim - 16) / 16) + s.offset;
    return h + (twoD ? 1 : 0) < HaltonDimensions ? uint32_t(h) : NoHaltonDim;
}

}  // namespace prism
