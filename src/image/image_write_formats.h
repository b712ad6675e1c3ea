// The encoders behind WriteImage that need no OpenImageIO. Each writes `path` (a temporary
// file; WriteImage renames it) from interleaved pixels, top row first, and throws
// std::runtime_error with a short reason on any failure, including a failed final flush.
#pragma once

#include <cstdint>
#include <string>

namespace prism {

// 8-bit PNG through libpng: 1 (gray), 2 (gray + alpha), 3 (RGB) or 4 (RGBA) channels of
// already sRGB-encoded values with straight alpha; tagged sRGB.
void WritePng(const std::string &path, int width, int height, int channels, bool alpha,
              const uint8_t *data);

// OpenEXR through the OpenEXR library: 32-bit float channels Y, YA, RGB or RGBA, ZIP
// compression, scanlines, increasing y.
void WriteExr(const std::string &path, int width, int height, int channels, bool alpha,
              const float *data);

// PFM: "PF" (RGB) or "Pf" (gray), size, scale (negative = little-endian), then float rows from
// the bottom of the image to the top.
void WritePfm(const std::string &path, int width, int height, int channels, const float *data);

}  // namespace prism
