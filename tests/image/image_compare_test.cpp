// Tests for image comparison, downsampling and heat maps.
#include "image/image_compare.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

TEST(CompareImages, Basics) {
    Image a(4, 2, 3), b(4, 2, 3);
    for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = b.pixels[i] = float(i) * 0.1f;
    ImageDiff same = CompareImages(a, b, 0.f);
    EXPECT_EQ(same.rmse, 0);
    EXPECT_EQ(same.meanAbs, 0);
    EXPECT_EQ(same.maxAbs, 0);
    EXPECT_EQ(same.badPixels, 0);

    b.At(1, 1, 2) += 0.5f;
    b.At(3, 0, 0) -= 0.05f;
    ImageDiff d = CompareImages(a, b, 0.1f);
    EXPECT_NEAR(d.maxAbs, 0.5, 1e-6);
    EXPECT_EQ(d.badPixels, 1);
    EXPECT_NEAR(d.meanAbs, 0.55 / 24, 1e-6);
    EXPECT_NEAR(d.rmse, std::sqrt((0.25 + 0.0025) / 24), 1e-6);
    EXPECT_EQ(CompareImages(a, b, 0.01f).badPixels, 2);

    // Gray compares against RGB by replication; alpha is ignored.
    Image gray(1, 1, 1), rgba(1, 1, 4);
    gray.At(0, 0, 0) = 0.3f;
    rgba.SetRGB(0, 0, RGB(0.3f));
    rgba.At(0, 0, 3) = 0.f;
    EXPECT_EQ(CompareImages(gray, rgba, 0.f).maxAbs, 0);

    EXPECT_THROW(CompareImages(Image(2, 2, 3), Image(2, 3, 3), 0.f), std::invalid_argument);
}

TEST(CompareImages, NonFiniteValuesAreInfiniteDifferences) {
    Image a(2, 1, 3), b(2, 1, 3);
    a.At(0, 0, 0) = NAN;
    EXPECT_TRUE(std::isinf(CompareImages(a, b, 1.f).maxAbs));
    EXPECT_EQ(CompareImages(a, b, 1.f).badPixels, 1);
    b.At(0, 0, 0) = NAN;
    a.At(1, 0, 1) = b.At(1, 0, 1) = INFINITY;
    EXPECT_EQ(CompareImages(a, b, 0.f).maxAbs, 0);
}

TEST(BoxDownsample, AveragesBlocks) {
    Image img(5, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) img.At(x, y, 0) = float(x + 10 * y);
    Image d = BoxDownsample(img, 2);
    ASSERT_EQ(d.width, 3);
    ASSERT_EQ(d.height, 2);
    ASSERT_EQ(d.channels, 1);
    EXPECT_FLOAT_EQ(d.At(0, 0, 0), (0 + 1 + 10 + 11) / 4.f);
    EXPECT_FLOAT_EQ(d.At(2, 0, 0), (4 + 14) / 2.f);  // partial block at the right edge
    EXPECT_FLOAT_EQ(d.At(2, 1, 0), 24.f);
    EXPECT_EQ(BoxDownsample(img, 1).pixels, img.pixels);
    EXPECT_THROW(BoxDownsample(img, 0), std::invalid_argument);
}

TEST(DiffHeatmap, ScalesDifferences) {
    Image a(3, 1, 3), b(3, 1, 3);
    b.SetRGB(1, 0, RGB(0.1f));
    b.SetRGB(2, 0, RGB(0.3f));
    Image h = DiffHeatmap(a, b);
    ASSERT_EQ(h.channels, 3);
    EXPECT_EQ(h.GetRGB(0, 0), RGB(0.f));
    EXPECT_EQ(h.GetRGB(2, 0), RGB(1.f));  // the largest difference is white
    RGB mid = h.GetRGB(1, 0);
    EXPECT_NEAR(mid.r, 1.f, 1e-6f);
    EXPECT_EQ(mid.b, 0.f);
    // With an explicit scale, small differences stay dark.
    EXPECT_NEAR(DiffHeatmap(a, b, 3.f).GetRGB(2, 0).r, 0.3f, 1e-6f);
    EXPECT_THROW(DiffHeatmap(a, Image(2, 1, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace prism
