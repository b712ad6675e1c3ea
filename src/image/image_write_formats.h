// The encoders behind WriteImage that need no OpenImageIO. Each writes into `out` (the
// temporary file WriteImage commits; core/output_file.h) from interleaved pixels, top row
// first, and throws std::runtime_error with a short reason on any failure (a failed write is
// AtomicOutputFile's "write error: REASON").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace prism {

class AtomicOutputFile;

// 8-bit PNG through libpng: 1 (gray), 2 (gray + alpha), 3 (RGB) or 4 (RGBA) channels of
// already sRGB-encoded values with straight alpha; tagged sRGB.
void WritePng(AtomicOutputFile &out, int width, int height, int channels, bool alpha,
              const uint8_t *data);

// OpenEXR through the OpenEXR library: 32-bit float channels Y, YA, RGB or RGBA, ZIP
// compression, scanlines, increasing y.
// `chromaticities` (Image::chromaticities) go into the header when given.
void WriteExr(AtomicOutputFile &out, int width, int height, int channels, bool alpha,
              const float *data, const std::array<float, 8> *chromaticities = nullptr);

// One float channel of a multi-channel EXR: `name` ("R", "P.X", "Z", ...), its first value and
// the distance between a pixel's values and the next pixel's, in floats.
struct ExrChannel {
    std::string name;
    const float *data = nullptr;
    size_t xStride = 1;
};
// OpenEXR with any named float channels (ZIP, scanlines) and string attributes in the header.
void WriteExrChannels(AtomicOutputFile &out, int width, int height,
                      const std::vector<ExrChannel> &channels,
                      const std::vector<std::pair<std::string, std::string>> &attributes,
                      const std::array<float, 8> *chromaticities = nullptr);

// PFM: "PF" (RGB) or "Pf" (gray), size, scale (negative = little-endian), then float rows from
// the bottom of the image to the top.
void WritePfm(AtomicOutputFile &out, int width, int height, int channels, const float *data);

}  // namespace prism
