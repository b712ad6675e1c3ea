// pbrt-v4's RGB colour spaces (the ColorSpace directive) and the linear maps between each and
// Prism's working space, linear sRGB (Rec. 709 primaries, D65 white). Prism renders in RGB: an
// RGB value written in another space is mapped into sRGB where the scene is read, as
// pbrt-v4's spectral rendering of it looks in sRGB, and the film maps sRGB out into its own
// space at the end.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/color.h"

namespace prism {

enum class ColorSpaceId : uint8_t { SRGB, Rec2020, DCIP3, ACES2065_1 };

// pbrt-v4's names: "srgb", "rec2020", "dci-p3" (P3 with a D65 white, as pbrt-v4 defines it),
// "aces2065-1" (AP0 primaries, the ACES D60 white); nullopt for any other.
std::optional<ColorSpaceId> ColorSpaceByName(std::string_view name);
const char *ColorSpaceName(ColorSpaceId cs);

// CIE 1931 xy chromaticities of the red, green and blue primaries and of the white.
struct ColorSpaceChromaticities {
    std::array<double, 2> r, g, b, w;
};
ColorSpaceChromaticities Chromaticities(ColorSpaceId cs);

// Row-major 3x3 matrices of linear colour maps.
using ColorMatrix = std::array<double, 9>;
ColorMatrix Mul(const ColorMatrix &a, const ColorMatrix &b);
ColorMatrix Inverse(const ColorMatrix &m);
std::array<double, 3> Apply(const ColorMatrix &m, const std::array<double, 3> &v);
std::array<float, 9> ToFloat(const ColorMatrix &m);

// XYZ of an RGB value of `cs` (its white, RGB 1 1 1, has luminance Y = 1).
ColorMatrix XYZFromRGB(ColorSpaceId cs);
// The Bradford chromatic adaptation in XYZ that maps white `from` (xy) onto white `to`.
ColorMatrix BradfordAdaptation(std::array<double, 2> from, std::array<double, 2> to);

// sRGB of a reflectance (or any RGB that is not an emission) written in `cs`: adapted from
// the space's white to D65, so a grey stays the same grey, as pbrt-v4's RGB albedo spectra
// are flat for grey in every space.
ColorMatrix SRGBFromReflectance(ColorSpaceId cs);
// sRGB of an emission written in `cs`: not adapted, so an RGB 1 1 1 light is the space's own
// white (ACES's D60 is slightly warm in sRGB), as pbrt-v4's RGB illuminant spectra are.
ColorMatrix SRGBFromIlluminant(ColorSpaceId cs);
// RGB of `cs` from linear sRGB, the film's output map: pbrt-v4's film converts the sensor's
// XYZ to its colour space without adaptation, unless it white-balances (`balanceFrom`: the
// chromaticity rendered as the space's white).
ColorMatrix OutputFromSRGB(ColorSpaceId cs, std::optional<std::array<double, 2>> balanceFrom);

// `m` applied to `c` with negative components clipped to 0 (a colour outside sRGB's gamut
// is rendered as its nearest in-gamut neighbour along the axes).
RGB MapClipped(const ColorMatrix &m, const RGB &c);

}  // namespace prism
