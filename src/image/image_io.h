// Reading and writing image files, plus the sRGB transfer curves. Files are converted to and
// from linear float Images; writes are atomic (temp file + rename). PNG and EXR are read and
// written with libpng and OpenEXR, PFM is written by hand; every other format goes through
// OpenImageIO, which lives in a shared module (libprism_oiio.so) loaded only when a file in
// such a format is first read or written.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"

namespace prism {

struct ReadImageOptions {
    // Auto: 8/16-bit integer files (PNG, JPEG, TGA, ...) are sRGB-encoded, float files (EXR,
    // HDR, PFM) are linear. Linear/SRGB force the interpretation of integer files; float files
    // are always linear unless SRGB is forced. Gamma: integer files' values v in [0, 1] are
    // v^gamma (pbrt-v4's "gamma G" encoding), float files linear.
    enum class Encoding { Auto, Linear, SRGB, Gamma };
    Encoding encoding = Encoding::Auto;
    float gamma = 1;
    // Upper bound on width * height * channels, checked before any pixel memory is allocated;
    // more is a MemoryBudgetError (core/memory.h) "image is too large: ...".
    int64_t maxPixels = int64_t(1) << 28;
    // Silence what decoder libraries print to stderr themselves (libpng's "libpng error: ..."):
    // the failure is reported once, through the exception. Off under the fuzzer, whose crash
    // reports go to stderr.
    bool quietDecoders = true;
    // When the reader the extension names fails, let OpenImageIO try its other readers. Off
    // under the fuzzer, so that each run exercises one decoder.
    bool tryAllFormats = true;
};

// Returns linear float pixels with 1 (gray), 3 (RGB) or 4 (RGBA) channels; gray + alpha becomes
// RGBA with the gray replicated. Alpha is never sRGB-decoded and is not premultiplied.
// Throws std::runtime_error with a short reason (no scene location; callers add it).
Image ReadImage(const std::string &path, ReadImageOptions opts = {});
// Decodes an encoded image held in memory (glTF embedded images). `name` must end in the
// format's extension (".png", ".jpg", ...); it also names the image in error messages.
Image ReadImageFromMemory(const std::vector<unsigned char> &bytes, const std::string &name,
                          ReadImageOptions opts = {});

// The format follows the extension: .exr (32-bit float, ZIP), .pfm/.hdr (float), .png/.jpg/
// .jpeg/.tga/.bmp (8-bit sRGB, rounded, clamped to [0,1]). The file is first written to a temporary
// file in the same directory and renamed over `path` only after a successful close, so `path`
// is never left partially written. Throws std::runtime_error on any failure.
void WriteImage(const std::string &path, const Image &img);
// An EXR of img's channels (R G B [A]) and further named float channels (`extra`: name and the
// channel's values, one per pixel, top row first), with string header attributes; written
// atomically like WriteImage. `path` must end in .exr.
struct NamedChannel {
    std::string name;
    const float *data = nullptr;
    size_t xStride = 1;  // floats from one pixel's value to the next
};
void WriteMultiChannelExr(const std::string &path, const Image &img,
                          const std::vector<NamedChannel> &extra,
                          const std::vector<std::pair<std::string, std::string>> &attributes);
// Whether WriteImage writes the format of `ext` (the extension with its dot, in lower case as
// LowerExtension returns it): the one list of output formats.
bool IsWritableImageExtension(const std::string &ext);
// Whether WriteImage stores linear float values for `ext` (.exr, .pfm, .hdr): such outputs get
// the exposure but no tone mapping (image/tonemap.h).
bool IsLinearImageExtension(const std::string &ext);

// The exact piecewise sRGB curves (IEC 61966-2-1).
float SrgbToLinear(float v);
float LinearToSrgb(float v);

// Linear float -> 8-bit sRGB code value with rounding; NaN maps to 0.
uint8_t LinearToSrgb8(float v);

}  // namespace prism
