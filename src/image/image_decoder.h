// Opened image files before their pixels are read: PNG (libpng) and OpenEXR (OpenEXR) are
// decoded directly, everything else through the OpenImageIO module. Internal to src/image.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "image/image_io.h"
#include "image/oiio_module.h"

namespace prism {

class ImageDecoder {
  public:
    virtual ~ImageDecoder() = default;
    virtual PrismOiioSpec Spec() const = 0;
    // Reads channels [0, nchannels) of the whole image as interleaved float, top row first;
    // integer values are normalized to [0, 1], nothing is colour-converted. Throws
    // std::runtime_error with a short reason.
    virtual void ReadFloat(int nchannels, float *out) = 0;
};

// Opens a PNG or OpenEXR file (or, when `data` is not null, the encoded bytes in memory, which
// must outlive the decoder), chosen by magic number. Returns null when the data is neither, or
// is an OpenEXR file whose layout the direct reader leaves to OpenImageIO (channels other than
// Y, YA, RGB, RGBA; multi-part, deep or integer channels). Throws std::runtime_error with a
// short reason when the file is PNG or OpenEXR but malformed.
std::unique_ptr<ImageDecoder> OpenDirectDecoder(const std::string &path, const unsigned char *data,
                                                size_t size);

// ReadImage through OpenImageIO even for PNG and OpenEXR (the tests compare the two readers).
Image ReadImageWithOiio(const std::string &path, ReadImageOptions opts = {});

}  // namespace prism
