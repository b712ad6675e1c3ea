// PNG (libpng), OpenEXR and PFM encoders; see image_write_formats.h.
#include "image/image_write_formats.h"

#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <png.h>

#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/output_file.h"

namespace prism {

namespace {

// An OpenEXR output stream over the temporary file. AtomicOutputFile throws
// std::runtime_error; OpenEXR's OutputFile destructor (which writes the line offset table)
// catches only Iex exceptions, so failures are rethrown as IoExc and remembered, and still
// reported after the destructor swallowed them.
class ExrStream : public Imf::OStream {
  public:
    ExrStream(AtomicOutputFile &out, const std::string &name)
        : Imf::OStream(name.c_str()), out_(out) {}
    void write(const char c[], int n) override {
        Guard([&] { out_.Write(c, size_t(n)); });
    }
    uint64_t tellp() override {
        uint64_t pos = 0;
        Guard([&] { pos = out_.Tell(); });
        return pos;
    }
    void seekp(uint64_t pos) override {
        Guard([&] { out_.Seek(pos); });
    }
    // The first failure, or "" when none.
    const std::string &error() const { return error_; }

  private:
    template <typename F>
    void Guard(F &&f) {
        try {
            f();
        } catch (const std::runtime_error &e) {
            if (error_.empty()) error_ = e.what();
            throw IEX_NAMESPACE::IoExc(e.what());
        }
    }
    AtomicOutputFile &out_;
    std::string error_;
};

}  // namespace

void WritePng(AtomicOutputFile &out, int width, int height, int channels, bool alpha,
              const uint8_t *data) {
    png_image image;
    std::memset(&image, 0, sizeof(image));
    image.version = PNG_IMAGE_VERSION;
    // Speed over file size (zlib's fast level): PNG encoding was 9% of a whole 800x600
    // Whitted render at the default level.
    image.flags = PNG_IMAGE_FLAG_FAST;
    image.width = png_uint_32(width);
    image.height = png_uint_32(height);
    bool gray = channels - (alpha ? 1 : 0) == 1;
    image.format = gray ? (alpha ? PNG_FORMAT_GA : PNG_FORMAT_GRAY)
                        : (alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB);
    // Encoded in memory (at most the pixels' size plus zlib's overhead: the film's budget
    // counts an encoded copy), then written through the checked temporary file. The buffer
    // is left uninitialized so the pages the encoder does not reach are never touched.
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(image);
    std::unique_ptr<unsigned char[]> buffer(new unsigned char[size]);
    // The simplified API writes 8-bit values as sRGB-encoded, straight alpha, tagged sRGB.
    if (!png_image_write_to_memory(&image, buffer.get(), &size, 0, data,
                                   png_int_32(width * channels), nullptr)) {
        std::string msg = image.message[0] ? std::string(image.message) : "libpng error";
        png_image_free(&image);
        throw std::runtime_error(msg);
    }
    out.Write(buffer.get(), size);
}

namespace {

void SetChromaticities(Imf::Header &header, const std::array<float, 8> *c) {
    if (!c) return;
    const std::array<float, 8> &v = *c;
    Imf::addChromaticities(header,
                           Imf::Chromaticities(Imath::V2f(v[0], v[1]), Imath::V2f(v[2], v[3]),
                                               Imath::V2f(v[4], v[5]), Imath::V2f(v[6], v[7])));
}

}  // namespace

void WriteExr(AtomicOutputFile &out, int width, int height, int channels, bool alpha,
              const float *data, const std::array<float, 8> *chromaticities) {
    static const char *const kGray[] = {"Y", "A"};
    static const char *const kColor[] = {"R", "G", "B", "A"};
    bool gray = channels - (alpha ? 1 : 0) == 1;
    const char *const *names = gray ? kGray : kColor;
    ExrStream stream(out, out.TemporaryPath());
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // zlib level 1 instead of OpenEXR's default 4: the 1600x1200 RGB float knot image
        // writes in 0.33-0.36 s instead of 0.42-0.49 s, 3% larger (6.2 MB instead of 6.0 MB);
        // the file is the same ZIP EXR for every reader. (PIZ: 0.70 s, 9.7 MB; ZIPS: 0.36-0.40 s,
        // 6.5 MB; none: 0.05 s, 22 MB.)
        header.zipCompressionLevel() = 1;
        SetChromaticities(header, chromaticities);
        Imf::FrameBuffer fb;
        size_t xStride = sizeof(float) * size_t(channels);
        for (int c = 0; c < channels; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            // Insert casts away const: OpenEXR's Slice takes char *, but only reads when writing.
            char *base = reinterpret_cast<char *>(const_cast<float *>(data + c));
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, xStride, xStride * size_t(width)));
        }
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(fb);
        file.writePixels(height);
    } catch (const std::exception &e) {
        if (!stream.error().empty()) throw std::runtime_error(stream.error());
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
    if (!stream.error().empty()) throw std::runtime_error(stream.error());
}

void WriteExrChannels(AtomicOutputFile &out, int width, int height,
                      const std::vector<ExrChannel> &channels,
                      const std::vector<std::pair<std::string, std::string>> &attributes,
                      const std::array<float, 8> *chromaticities) {
    ExrStream stream(out, out.TemporaryPath());
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.zipCompressionLevel() = 1;  // as in WriteExr
        SetChromaticities(header, chromaticities);
        for (const auto &[name, value] : attributes)
            header.insert(name, Imf::StringAttribute(value));
        Imf::FrameBuffer fb;
        for (const ExrChannel &c : channels) {
            header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
            size_t xStride = sizeof(float) * c.xStride;
            char *base = reinterpret_cast<char *>(const_cast<float *>(c.data));
            fb.insert(c.name, Imf::Slice(Imf::FLOAT, base, xStride, xStride * size_t(width)));
        }
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(fb);
        file.writePixels(height);
    } catch (const std::exception &e) {
        if (!stream.error().empty()) throw std::runtime_error(stream.error());
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
    if (!stream.error().empty()) throw std::runtime_error(stream.error());
}

void WritePfm(AtomicOutputFile &out, int width, int height, int channels, const float *data) {
    out.Write(std::string(channels == 1 ? "Pf" : "PF") + "\n" + std::to_string(width) + " " +
              std::to_string(height) + "\n-1.0\n");
    size_t rowValues = size_t(width) * size_t(channels);
    std::vector<uint32_t> row(rowValues);
    for (int y = height - 1; y >= 0; --y) {
        std::memcpy(row.data(), data + size_t(y) * rowValues, rowValues * sizeof(float));
        if constexpr (std::endian::native == std::endian::big)
            for (uint32_t &v : row) v = __builtin_bswap32(v);
        out.Write(row.data(), rowValues * sizeof(float));
    }
}

}  // namespace prism
