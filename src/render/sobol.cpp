#include "render/sobol.h"

#include <array>

namespace prism {

namespace {

// The 24 permutations of {0, 1, 2, 3}, in lexicographic order.
constexpr std::array<std::array<uint8_t, 4>, 24> MakePermutations4() {
    std::array<std::array<uint8_t, 4>, 24> p{};
    int k = 0;
    for (uint8_t a = 0; a < 4; ++a)
        for (uint8_t b = 0; b < 4; ++b)
            for (uint8_t c = 0; c < 4; ++c) {
                if (a == b || a == c || b == c) continue;
                const uint8_t d = uint8_t(6 - a - b - c);
                p[size_t(k++)] = {a, b, c, d};
            }
    return p;
}

constexpr auto Permutations4 = MakePermutations4();

}  // namespace

uint64_t ZSobolIndex(uint32_t x, uint32_t y, uint32_t sample, int log2Count, int log2Res,
                     uint32_t dim) {
    const uint64_t code = (MortonCode2(x, y) << log2Count) | sample;
    // An odd log2Count leaves one base-2 digit at the bottom, permuted on its own.
    const int odd = log2Count & 1;
    const int digits = log2Res + (log2Count + 1) / 2;
    const uint64_t dimKey = 0x9e3779b97f4a7c15ull * (uint64_t(dim) + 1);
    uint64_t index = 0;
    for (int i = digits - 1; i >= odd; --i) {
        const int shift = 2 * i - odd;
        const uint32_t digit = uint32_t(code >> shift) & 3u;
        const uint64_t above = shift + 2 < 64 ? code >> (shift + 2) : 0;
        const uint32_t p = uint32_t(MixBits64(above ^ dimKey) >> 40) % 24u;
        index |= uint64_t(Permutations4[p][digit]) << shift;
    }
    if (odd) index |= (code & 1) ^ (MixBits64((code >> 1) ^ dimKey) & 1);
    return index;
}

}  // namespace prism
