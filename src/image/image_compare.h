// Image comparison helpers for tests and tools: error statistics, downsampling, heat maps.
#pragma once

#include <cstdint>

#include "image/image.h"

namespace prism {

struct ImageDiff {
    double rmse = 0, meanAbs = 0, maxAbs = 0;  // over all RGB components
    int64_t badPixels = 0;                     // pixels with some |a - b| > badThreshold
};

// Compares the RGB components (gray is replicated, alpha ignored). A component that is
// non-finite in one image and not identical in the other counts as an infinite difference.
// Throws std::invalid_argument if the sizes differ.
ImageDiff CompareImages(const Image &a, const Image &b, float badThreshold);

// Averages factor x factor blocks (partial blocks at the right/bottom edge average the pixels
// they have); keeps the channel count. Throws std::invalid_argument if factor < 1.
Image BoxDownsample(const Image &img, int factor);

// RGB heat map of the mean absolute RGB difference per pixel, scaled by `scale` (0: by the
// largest difference) and mapped black -> red -> yellow -> white. Throws like CompareImages.
Image DiffHeatmap(const Image &a, const Image &b, float scale = 0);

}  // namespace prism
