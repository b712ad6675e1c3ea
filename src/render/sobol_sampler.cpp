#include "render/sobol_sampler.h"

#include <algorithm>
#include <boost/random/detail/sobol_table.hpp>
#include <utility>
#include <vector>

#include "core/rng.h"

namespace prism {

namespace {

constexpr int IndexBits = 64;

// Column j of each dimension's generator matrix: the direction number v_j = m_j / 2^(j+1) as
// a 32-bit binary fraction (bits below 2^-32 dropped), for index bits j < 64. Dimension 0 is
// van der Corput's (m_j = 1); dimension d > 0 takes Joe and Kuo's primitive polynomial d - 1
// and initial m's, and the recurrence of Bratley and Fox (1988):
//   m_j = m_{j-s} ^ (m_{j-s} << s) ^ XOR_{k=1}^{s-1} a_k (m_{j-s+k} << (s-k)),
// s the polynomial's degree and a_k its coefficient of z^k.
struct SobolMatrices {
    std::vector<uint32_t> columns;  // dim * IndexBits + j

    SobolMatrices() : columns(size_t(SobolDimensions) * IndexBits) {
        using Table = boost::random::detail::qrng_tables::sobol;
        static_assert(Table::max_dimension >= SobolDimensions);
        for (uint32_t d = 0; d < SobolDimensions; ++d) {
            uint64_t m[IndexBits];
            if (d == 0) {
                std::fill(m, m + IndexBits, uint64_t(1));
            } else {
                const uint32_t poly = Table::polynomial(d - 1);
                int s = 0;
                while ((poly >> (s + 1)) != 0) ++s;
                for (int k = 0; k < s; ++k) m[k] = Table::minit(d - 1, size_t(k));
                for (int j = s; j < IndexBits; ++j) {
                    uint64_t v = m[j - s] ^ (m[j - s] << s);
                    for (int k = 1; k < s; ++k)
                        if ((poly >> k) & 1) v ^= m[j - s + k] << (s - k);
                    m[j] = v;
                }
            }
            for (int j = 0; j < IndexBits; ++j)
                columns[size_t(d) * IndexBits + size_t(j)] =
                    j <= 31 ? uint32_t(m[j] << (31 - j)) : uint32_t(m[j] >> (j - 31));
        }
    }
};

const SobolMatrices &Matrices() {
    static const SobolMatrices matrices;
    return matrices;
}

}  // namespace

uint32_t SobolPoint(uint64_t index, uint32_t dim) {
    const uint32_t *c = &Matrices().columns[size_t(dim % SobolDimensions) * IndexBits];
    uint32_t v = 0;
    for (int j = 0; index != 0; index >>= 1, ++j)
        if (index & 1) v ^= c[j];
    return v;
}

SobolFrame SobolFrame::ForResolution(int width, int height, SobolScramble s) {
    SobolFrame f;
    f.scramble = s;
    const int res = std::max({width, height, 1});
    while ((int64_t(1) << f.log2Scale) < res) ++f.log2Scale;
    f.scale = uint32_t(1) << f.log2Scale;
    const int m = f.log2Scale;
    if (m == 0) return f;
    // A's column t: dimension 1's top m bits from index bit m + t. Gauss-Jordan elimination
    // over GF(2) on [A | I], rows as bit masks: row r holds bit r of every column.
    uint64_t rows[32];
    for (int r = 0; r < m; ++r) {
        uint64_t a = 0;
        for (int t = 0; t < m; ++t) {
            const uint32_t column = SobolPoint(uint64_t(1) << (m + t), 1) >> (32 - m);
            a |= uint64_t((column >> r) & 1) << t;
        }
        rows[r] = a | (uint64_t(1) << (32 + r));  // [A_r | e_r]
    }
    for (int c = 0; c < m; ++c) {
        int pivot = c;
        while (pivot < m && !((rows[pivot] >> c) & 1)) ++pivot;
        // Sobol's first two dimensions are a (0,2)-sequence: A is invertible.
        if (pivot == m) continue;
        std::swap(rows[c], rows[pivot]);
        for (int r = 0; r < m; ++r)
            if (r != c && ((rows[r] >> c) & 1)) rows[r] ^= rows[c];
    }
    // Row t of [I | A^-1] is x_t's dependence on the target bits; store A^-1 by columns.
    for (int b = 0; b < m; ++b) {
        uint32_t column = 0;
        for (int t = 0; t < m; ++t) column |= uint32_t((rows[t] >> (32 + b)) & 1) << t;
        f.inverse[size_t(b)] = column;
    }
    return f;
}

uint64_t SobolFrame::Index(int x, int y, uint64_t sample) const {
    const int m = log2Scale;
    if (m == 0) return sample;
    // Dimension 0 is van der Corput's: its top m bits are the low m index bits reversed.
    const uint32_t low = ReverseBits32(uint32_t(x)) >> (32 - m);
    const uint64_t known = (sample << (2 * m)) | low;
    // Dimension 1's top m bits must be y: the index bits m to 2m - 1 make up the difference.
    const uint32_t target = uint32_t(y) ^ (SobolPoint(known, 1) >> (32 - m));
    uint32_t middle = 0;
    for (int b = 0; b < m; ++b)
        if ((target >> b) & 1) middle ^= inverse[size_t(b)];
    return known | (uint64_t(middle) << m);
}

Vec2f SobolFrame::PixelOffset(uint64_t index, int x, int y) const {
    const double s = double(scale) * 0x1p-32;
    const float u = float(double(SobolPoint(index, 0)) * s - x),
                v = float(double(SobolPoint(index, 1)) * s - y);
    return {std::clamp(u, 0.f, 0x1.fffffep-1f), std::clamp(v, 0.f, 0x1.fffffep-1f)};
}

float SobolFrame::Sample(uint64_t index, uint32_t dim, uint32_t seed) const {
    // pbrt: dimensions past the table start again at 2.
    if (dim >= SobolDimensions) dim = 2 + (dim - 2) % (SobolDimensions - 2);
    const uint32_t h = uint32_t(MixBits64((uint64_t(dim) << 32) ^ seed ^ 0x736f626f6cull));
    return BitsToUnit(Scramble(SobolPoint(index, dim), h, scramble));
}

}  // namespace prism
