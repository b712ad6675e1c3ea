// pbrt-v4's RGB colour spaces and their maps to and from linear sRGB (core/color_space.h).
#include "core/color_space.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

void ExpectMatrixNear(const ColorMatrix &m, const ColorMatrix &want, double tol) {
    for (size_t k = 0; k < 9; ++k) EXPECT_NEAR(m[k], want[k], tol) << "entry " << k;
}

constexpr ColorSpaceId kAll[] = {ColorSpaceId::SRGB, ColorSpaceId::Rec2020, ColorSpaceId::DCIP3,
                                 ColorSpaceId::ACES2065_1};

TEST(ColorSpace, NamesRoundTrip) {
    for (ColorSpaceId cs : kAll) EXPECT_EQ(ColorSpaceByName(ColorSpaceName(cs)), cs);
    EXPECT_FALSE(ColorSpaceByName("adobergb"));
    EXPECT_FALSE(ColorSpaceByName("sRGB"));  // pbrt-v4's names are lower case
}

// The published RGB-to-XYZ matrices: IEC 61966-2-1 (sRGB), ITU-R BT.2020, SMPTE EG 432-1 (P3 with a
// D65 white) and SMPTE ST 2065-1 (ACES AP0).
TEST(ColorSpace, XYZMatricesAreThePublishedOnes) {
    ExpectMatrixNear(XYZFromRGB(ColorSpaceId::SRGB),
                     {0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522, 0.0721750, 0.0193339,
                      0.1191920, 0.9503041},
                     3e-4);  // IEC's white is 0.95047 1 1.08883, a little off xy 0.3127 0.3290
    ExpectMatrixNear(
        XYZFromRGB(ColorSpaceId::Rec2020),
        {0.636958, 0.144617, 0.168881, 0.262700, 0.677998, 0.059302, 0.0, 0.028073, 1.060985},
        2e-4);
    ExpectMatrixNear(
        XYZFromRGB(ColorSpaceId::DCIP3),
        {0.486571, 0.265668, 0.198217, 0.228975, 0.691739, 0.079287, 0.0, 0.045113, 1.043944},
        2e-4);
    ExpectMatrixNear(XYZFromRGB(ColorSpaceId::ACES2065_1),
                     {0.952552, 0.0, 0.0000937, 0.343966, 0.728166, -0.072133, 0.0, 0.0, 1.008825},
                     2e-4);
}

TEST(ColorSpace, GreyReflectancesStayGreyAndWhitesKeepLuminanceOne) {
    for (ColorSpaceId cs : kAll) {
        SCOPED_TRACE(ColorSpaceName(cs));
        const RGB grey = MapClipped(SRGBFromReflectance(cs), RGB(0.5f));
        EXPECT_NEAR(grey.r, 0.5, 1e-4);
        EXPECT_NEAR(grey.g, 0.5, 1e-4);
        EXPECT_NEAR(grey.b, 0.5, 1e-4);
        EXPECT_NEAR(MapClipped(SRGBFromIlluminant(cs), RGB(1)).Luminance(), 1, 1e-4);
    }
    // ACES's white (D60) is a warm white in sRGB; the D65 spaces' is sRGB's.
    const RGB aces = MapClipped(SRGBFromIlluminant(ColorSpaceId::ACES2065_1), RGB(1));
    EXPECT_GT(aces.r, 1.02f);
    EXPECT_LT(aces.b, 0.95f);
    const RGB rec = MapClipped(SRGBFromIlluminant(ColorSpaceId::Rec2020), RGB(1));
    EXPECT_NEAR(rec.r, 1, 1e-4);
    EXPECT_NEAR(rec.b, 1, 1e-4);
}

// An emission written in the film's own space comes out of the film as it was written.
TEST(ColorSpace, OutputUndoesTheEmissionMap) {
    for (ColorSpaceId cs : kAll) {
        SCOPED_TRACE(ColorSpaceName(cs));
        const ColorMatrix m = Mul(OutputFromSRGB(cs, {}), SRGBFromIlluminant(cs));
        ExpectMatrixNear(m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, 1e-9);
        // Balanced from the space's own white, nothing changes either.
        const ColorMatrix b = Mul(OutputFromSRGB(cs, Chromaticities(cs).w), SRGBFromIlluminant(cs));
        ExpectMatrixNear(b, {1, 0, 0, 0, 1, 0, 0, 0, 1}, 1e-9);
    }
}

TEST(ColorSpace, ColoursOutsideSRGBAreClippedAtZero) {
    // Rec. 2020's pure green is far outside sRGB: its red and blue would be negative.
    const RGB g = MapClipped(SRGBFromReflectance(ColorSpaceId::Rec2020), RGB(0, 1, 0));
    EXPECT_EQ(g.r, 0);
    EXPECT_EQ(g.b, 0);
    EXPECT_GT(g.g, 1);
}

}  // namespace
}  // namespace prism
