// Atomic image writing: PNG through libpng, EXR through OpenEXR, PFM by hand, and the other
// formats (HDR, TGA, BMP, JPEG) through the OpenImageIO module.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"
#include "core/output_file.h"
#include "image/image_io.h"
#include "image/image_write_formats.h"
#include "image/oiio_loader.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

enum class OutKind { Float, Srgb8 };

struct OutputFormat {
    OutKind kind;
    bool allowGray, allowAlpha;  // channel layouts the format can store
};

bool LookupOutputFormat(const std::string &ext, OutputFormat *f) {
    if (ext == ".exr")
        *f = {OutKind::Float, true, true};
    else if (ext == ".pfm")
        *f = {OutKind::Float, true, false};
    else if (ext == ".hdr")
        *f = {OutKind::Float, false, false};
    else if (ext == ".png" || ext == ".tga" || ext == ".bmp")
        *f = {OutKind::Srgb8, true, true};
    else if (ext == ".jpg" || ext == ".jpeg")
        *f = {OutKind::Srgb8, true, false};
    else
        return false;
    return true;
}

// Writes the image file `path` atomically: write(out) fills the temporary file beside it
// (core/output_file.h), which replaces `path` only once complete and is removed otherwise.
// Every failure (a missing folder, the writer's std::runtime_error, the fsync, close or
// rename) is "cannot write image PATH: why".
template <typename WriteFn>
void WriteImageAtomically(const std::string &path, WriteFn &&write) {
    auto fail = [&](const std::string &why) -> std::runtime_error {
        return std::runtime_error("cannot write image " + Quote(path) + ": " + why);
    };
    fs::path target(path);
    std::error_code dirEc;
    fs::path dir = target.parent_path();
    if (!dir.empty() && !fs::is_directory(dir, dirEc))
        throw fail("directory " + Quote(dir.string()) + " does not exist");
    try {
        AtomicOutputFile out(path);
        write(out);
        out.Commit();
    } catch (const std::runtime_error &e) {
        throw fail(e.what());
    }
}

}  // namespace

bool IsWritableImageExtension(const std::string &ext) {
    OutputFormat format;
    return LookupOutputFormat(ext, &format);
}

bool IsLinearImageExtension(const std::string &ext) {
    OutputFormat format;
    return LookupOutputFormat(ext, &format) && format.kind == OutKind::Float;
}

void WriteImage(const std::string &path, const Image &img) {
    auto fail = [&](const std::string &why) -> std::runtime_error {
        return std::runtime_error("cannot write image " + Quote(path) + ": " + why);
    };
    std::string ext = LowerExtension(path);
    OutputFormat format;
    if (!LookupOutputFormat(ext, &format))
        throw std::runtime_error("unsupported output format " + Quote(ext) + " (use .exr or .png)");
    if (img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4 ||
        img.pixels.size() != size_t(img.width) * size_t(img.height) * size_t(img.channels))
        throw fail("invalid image (size " + std::to_string(img.width) + "x" +
                   std::to_string(img.height) + "x" + std::to_string(img.channels) + ")");

    // Map the image's channels onto what the format can store: gray -> RGB if gray is not
    // supported, alpha dropped if alpha is not supported.
    bool gray = img.channels <= 2, alpha = img.HasAlpha();
    if (gray && !format.allowGray) gray = false;
    if (alpha && !format.allowAlpha) alpha = false;
    int nOut = (gray ? 1 : 3) + (alpha ? 1 : 0);
    int srcAlpha = img.channels - 1;
    auto source = [&](size_t pixel, int c) -> float {
        const float *p = &img.pixels[pixel * size_t(img.channels)];
        if (alpha && c == nOut - 1) return p[srcAlpha];
        return img.channels >= 3 ? p[c] : p[0];
    };

    size_t nPixels = size_t(img.width) * size_t(img.height);

    std::vector<float> floats;
    std::vector<uint8_t> bytes;
    const void *data;
    if (format.kind == OutKind::Float) {
        if (nOut == img.channels) {
            data = img.pixels.data();
        } else {
            floats.resize(nPixels * size_t(nOut));
            for (size_t i = 0; i < nPixels; ++i)
                for (int c = 0; c < nOut; ++c) floats[i * size_t(nOut) + size_t(c)] = source(i, c);
            data = floats.data();
        }
    } else {
        bytes.resize(nPixels * size_t(nOut));
        for (size_t i = 0; i < nPixels; ++i) {
            for (int c = 0; c < nOut; ++c) {
                float v = source(i, c);
                uint8_t &b = bytes[i * size_t(nOut) + size_t(c)];
                if (alpha && c == nOut - 1)
                    b = v > 0 ? uint8_t(std::lround(std::min(v, 1.f) * 255.f)) : 0;  // linear
                else
                    b = LinearToSrgb8(v);
            }
        }
        data = bytes.data();
    }

    WriteImageAtomically(path, [&](AtomicOutputFile &out) {
        if (ext == ".pfm") {
            // OIIO 2.4 reads PFM but cannot write it; the format is simple enough to write here.
            WritePfm(out, img.width, img.height, nOut, static_cast<const float *>(data));
        } else if (ext == ".png") {
            WritePng(out, img.width, img.height, nOut, alpha, static_cast<const uint8_t *>(data));
        } else if (ext == ".exr") {
            WriteExr(out, img.width, img.height, nOut, alpha, static_cast<const float *>(data),
                     img.chromaticities ? &*img.chromaticities : nullptr);
        } else {
            const PrismOiioModule &module = OiioModule();
            bool isFloat = format.kind == OutKind::Float;
            const char *compression = ext == ".jpg" || ext == ".jpeg" ? "jpeg:95" : "";
            char err[512] = "";
            // Encoded in memory by OpenImageIO (which never opens a file here; `path` only
            // names the format), then written through the checked temporary file.
            struct Sink {
                AtomicOutputFile *out;
                std::string error;  // the write's failure (exceptions must not cross the module)
            } sink{&out, {}};
            auto write = [](void *ctx, const unsigned char *bytes, size_t size) -> int {
                Sink *s = static_cast<Sink *>(ctx);
                try {
                    s->out->Write(bytes, size);
                    return 1;
                } catch (const std::runtime_error &e) {
                    s->error = e.what();
                    return 0;
                }
            };
            if (!module.write(path.c_str(), img.width, img.height, nOut, alpha ? nOut - 1 : -1,
                              isFloat ? 1 : 0, data, isFloat ? "Linear" : "sRGB", compression,
                              write, &sink, err, sizeof(err)))
                throw std::runtime_error(sink.error.empty() ? std::string(err) : sink.error);
        }
    });
}

void WriteMultiChannelExr(const std::string &path, const Image &img,
                          const std::vector<NamedChannel> &extra,
                          const std::vector<std::pair<std::string, std::string>> &attributes) {
    auto fail = [&](const std::string &why) -> std::runtime_error {
        return std::runtime_error("cannot write image " + Quote(path) + ": " + why);
    };
    if (LowerExtension(path) != ".exr") throw fail("named channels need an .exr output");
    static const char *const kNames[] = {"R", "G", "B", "A"};
    std::vector<ExrChannel> channels;
    for (int c = 0; c < std::min(img.channels, 4); ++c)
        channels.push_back({img.channels >= 3 ? kNames[c] : (c == 0 ? "Y" : "A"),
                            img.pixels.data() + c, size_t(img.channels)});
    for (const NamedChannel &n : extra) channels.push_back({n.name, n.data, n.xStride});
    WriteImageAtomically(path, [&](AtomicOutputFile &out) {
        WriteExrChannels(out, img.width, img.height, channels, attributes,
                         img.chromaticities ? &*img.chromaticities : nullptr);
    });
}

}  // namespace prism
