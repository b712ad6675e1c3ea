// Figures of images the tests compare.
#pragma once

#include <cstdint>

#include "core/color.h"
#include "image/image.h"

namespace prism::test {

// The mean of each of the first three channels over all pixels.
RGB MeanRGB(const Image &img);
// The mean of channel `c` over all pixels.
double MeanChannel(const Image &img, int c);
// The mean of every channel of every pixel.
double MeanValue(const Image &img);
// Mean |a - b| over mean |b| (all channels; a and b of one size).
double RelL1(const Image &a, const Image &b);
// The largest |a - b| of any channel of any pixel.
double MaxAbsDiff(const Image &a, const Image &b);
// A w x h image of c channels, each value uniform in [lo, hi) from seed `seed`.
Image RandomImage(int w, int h, int c, float lo, float hi, uint32_t seed);

}  // namespace prism::test
