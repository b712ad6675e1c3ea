#include "core/color_space.h"

namespace prism {

namespace {

constexpr std::array<double, 2> kD65 = {0.3127, 0.3290};
constexpr std::array<double, 2> kAcesWhite = {0.32168, 0.33767};  // SMPTE ST 2065-1

constexpr ColorMatrix kBradford = {0.8951, 0.2664, -0.1614, -0.7502, 1.7135,
                                   0.0367, 0.0389, -0.0685, 1.0296};

std::array<double, 3> XYZOf(std::array<double, 2> xy) {
    return {xy[0] / xy[1], 1, (1 - xy[0] - xy[1]) / xy[1]};
}

}  // namespace

std::optional<ColorSpaceId> ColorSpaceByName(std::string_view name) {
    if (name == "srgb") return ColorSpaceId::SRGB;
    if (name == "rec2020") return ColorSpaceId::Rec2020;
    if (name == "dci-p3") return ColorSpaceId::DCIP3;
    if (name == "aces2065-1") return ColorSpaceId::ACES2065_1;
    return std::nullopt;
}

const char *ColorSpaceName(ColorSpaceId cs) {
    switch (cs) {
        case ColorSpaceId::SRGB:
            return "srgb";
        case ColorSpaceId::Rec2020:
            return "rec2020";
        case ColorSpaceId::DCIP3:
            return "dci-p3";
        case ColorSpaceId::ACES2065_1:
            return "aces2065-1";
    }
    return "srgb";
}

ColorSpaceChromaticities Chromaticities(ColorSpaceId cs) {
    switch (cs) {
        case ColorSpaceId::SRGB:
            return {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, kD65};
        case ColorSpaceId::Rec2020:
            return {{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}, kD65};
        case ColorSpaceId::DCIP3:
            return {{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}, kD65};
        case ColorSpaceId::ACES2065_1:
            return {{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770}, kAcesWhite};
    }
    return Chromaticities(ColorSpaceId::SRGB);
}

ColorMatrix Mul(const ColorMatrix &a, const ColorMatrix &b) {
    ColorMatrix c{};
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
            for (size_t k = 0; k < 3; ++k) c[3 * i + j] += a[3 * i + k] * b[3 * k + j];
    return c;
}

ColorMatrix Inverse(const ColorMatrix &m) {
    const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7],
                 i = m[8];
    const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    const double det = a * A + b * B + c * C;
    return {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
            B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
            C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
}

std::array<double, 3> Apply(const ColorMatrix &m, const std::array<double, 3> &v) {
    return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
            m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

std::array<float, 9> ToFloat(const ColorMatrix &m) {
    std::array<float, 9> out{};
    for (size_t k = 0; k < 9; ++k) out[k] = float(m[k]);
    return out;
}

ColorMatrix XYZFromRGB(ColorSpaceId cs) {
    // Columns: the primaries' XYZ at Y = 1, each scaled so that they sum to the white's.
    const ColorSpaceChromaticities c = Chromaticities(cs);
    const std::array<double, 3> r = XYZOf(c.r), g = XYZOf(c.g), b = XYZOf(c.b);
    const ColorMatrix P = {r[0], g[0], b[0], r[1], g[1], b[1], r[2], g[2], b[2]};
    const std::array<double, 3> s = Apply(Inverse(P), XYZOf(c.w));
    ColorMatrix m = P;
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j) m[3 * i + j] *= s[j];
    return m;
}

ColorMatrix BradfordAdaptation(std::array<double, 2> from, std::array<double, 2> to) {
    const std::array<double, 3> src = Apply(kBradford, XYZOf(from)),
                                dst = Apply(kBradford, XYZOf(to));
    const ColorMatrix scale = {dst[0] / src[0], 0, 0, 0, dst[1] / src[1], 0, 0, 0, dst[2] / src[2]};
    return Mul(Inverse(kBradford), Mul(scale, kBradford));
}

ColorMatrix SRGBFromReflectance(ColorSpaceId cs) {
    if (cs == ColorSpaceId::SRGB) return {1, 0, 0, 0, 1, 0, 0, 0, 1};
    return Mul(Inverse(XYZFromRGB(ColorSpaceId::SRGB)),
               Mul(BradfordAdaptation(Chromaticities(cs).w, kD65), XYZFromRGB(cs)));
}

ColorMatrix SRGBFromIlluminant(ColorSpaceId cs) {
    if (cs == ColorSpaceId::SRGB) return {1, 0, 0, 0, 1, 0, 0, 0, 1};
    return Mul(Inverse(XYZFromRGB(ColorSpaceId::SRGB)), XYZFromRGB(cs));
}

ColorMatrix OutputFromSRGB(ColorSpaceId cs, std::optional<std::array<double, 2>> balanceFrom) {
    // Every space's matrix is derived from its chromaticities the same way (sRGB's agrees with
    // IEC 61966-2-1's published one to 3e-4), so a white maps onto a white exactly.
    ColorMatrix xyz = XYZFromRGB(ColorSpaceId::SRGB);
    if (balanceFrom) xyz = Mul(BradfordAdaptation(*balanceFrom, Chromaticities(cs).w), xyz);
    return Mul(Inverse(XYZFromRGB(cs)), xyz);
}

RGB MapClipped(const ColorMatrix &m, const RGB &c) {
    const std::array<double, 3> v = Apply(m, {c.r, c.g, c.b});
    return RGB(float(v[0]), float(v[1]), float(v[2])).Clamped(0);
}

}  // namespace prism
