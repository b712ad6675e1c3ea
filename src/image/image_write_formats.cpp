// PNG (libpng), OpenEXR and PFM encoders; see image_write_formats.h.
#include "image/image_write_formats.h"

#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <png.h>

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace prism {

namespace {

std::string ErrnoText(const char *what, int err) {
    return std::string(what) + ": " + std::strerror(err);
}

// Owns a FILE*; Close() reports a failed final flush (e.g. a full disk).
class File {
  public:
    explicit File(const std::string &path) : f_(std::fopen(path.c_str(), "wb")) {
        if (!f_) throw std::runtime_error(ErrnoText("could not create the file", errno));
    }
    ~File() {
        if (f_) std::fclose(f_);
    }
    File(const File &) = delete;
    File &operator=(const File &) = delete;
    FILE *get() const { return f_; }
    void Close() {
        bool bad = std::ferror(f_) != 0;
        int err = errno;
        int rc = std::fclose(f_);
        if (rc != 0) err = errno;
        f_ = nullptr;
        if (bad || rc != 0) throw std::runtime_error(ErrnoText("write error", err));
    }

  private:
    FILE *f_;
};

// An OpenEXR output stream over a File that remembers a failed write, so that a failure inside
// OutputFile's destructor (which writes the line offset table and swallows exceptions) is
// still reported. It throws Iex exceptions, the only kind that destructor catches.
class ExrStream : public Imf::OStream {
  public:
    ExrStream(FILE *f, const std::string &name) : Imf::OStream(name.c_str()), f_(f) {}
    void write(const char c[], int n) override {
        if (std::fwrite(c, 1, size_t(n), f_) != size_t(n)) {
            failed_ = true;
            error_ = errno;
            throw IEX_NAMESPACE::IoExc(ErrnoText("write error", error_));
        }
    }
    uint64_t tellp() override { return uint64_t(ftello(f_)); }
    void seekp(uint64_t pos) override {
        if (fseeko(f_, off_t(pos), SEEK_SET) != 0) {
            failed_ = true;
            error_ = errno;
            throw IEX_NAMESPACE::IoExc(ErrnoText("seek error", error_));
        }
    }
    bool failed() const { return failed_; }
    int error() const { return error_; }

  private:
    FILE *f_;
    bool failed_ = false;
    int error_ = 0;
};

}  // namespace

void WritePng(const std::string &path, int width, int height, int channels, bool alpha,
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
    File file(path);
    // The simplified API writes 8-bit values as sRGB-encoded, straight alpha, tagged sRGB.
    if (!png_image_write_to_stdio(&image, file.get(), 0, data, png_int_32(width * channels),
                                  nullptr)) {
        int err = errno;
        std::string msg = std::ferror(file.get()) ? ErrnoText("write error", err)
                          : image.message[0]      ? std::string(image.message)
                                                  : std::string("libpng error");
        png_image_free(&image);
        throw std::runtime_error(msg);
    }
    file.Close();
}

void WriteExr(const std::string &path, int width, int height, int channels, bool alpha,
              const float *data) {
    static const char *const kGray[] = {"Y", "A"};
    static const char *const kColor[] = {"R", "G", "B", "A"};
    bool gray = channels - (alpha ? 1 : 0) == 1;
    const char *const *names = gray ? kGray : kColor;
    File file(path);
    ExrStream stream(file.get(), path);
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // zlib level 1 instead of OpenEXR's default 4: the 1600x1200 RGB float knot image
        // writes in 0.33-0.36 s instead of 0.42-0.49 s, 3% larger (6.2 MB instead of 6.0 MB);
        // the file is the same ZIP EXR for every reader. (PIZ: 0.70 s, 9.7 MB; ZIPS: 0.36-0.40 s,
        // 6.5 MB; none: 0.05 s, 22 MB.)
        header.zipCompressionLevel() = 1;
        Imf::FrameBuffer fb;
        size_t xStride = sizeof(float) * size_t(channels);
        for (int c = 0; c < channels; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            // Insert casts away const: OpenEXR's Slice takes char *, but only reads when writing.
            char *base = reinterpret_cast<char *>(const_cast<float *>(data + c));
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, xStride, xStride * size_t(width)));
        }
        Imf::OutputFile out(stream, header);
        out.setFrameBuffer(fb);
        out.writePixels(height);
    } catch (const std::exception &e) {
        if (stream.failed()) throw std::runtime_error(ErrnoText("write error", stream.error()));
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
    if (stream.failed()) throw std::runtime_error(ErrnoText("write error", stream.error()));
    file.Close();
}

void WriteExrChannels(const std::string &path, int width, int height,
                      const std::vector<ExrChannel> &channels,
                      const std::vector<std::pair<std::string, std::string>> &attributes) {
    File file(path);
    ExrStream stream(file.get(), path);
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.zipCompressionLevel() = 1;  // as in WriteExr
        for (const auto &[name, value] : attributes)
            header.insert(name, Imf::StringAttribute(value));
        Imf::FrameBuffer fb;
        for (const ExrChannel &c : channels) {
            header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
            size_t xStride = sizeof(float) * c.xStride;
            char *base = reinterpret_cast<char *>(const_cast<float *>(c.data));
            fb.insert(c.name, Imf::Slice(Imf::FLOAT, base, xStride, xStride * size_t(width)));
        }
        Imf::OutputFile out(stream, header);
        out.setFrameBuffer(fb);
        out.writePixels(height);
    } catch (const std::exception &e) {
        if (stream.failed()) throw std::runtime_error(ErrnoText("write error", stream.error()));
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
    if (stream.failed()) throw std::runtime_error(ErrnoText("write error", stream.error()));
    file.Close();
}

void WritePfm(const std::string &path, int width, int height, int channels, const float *data) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("could not create the file");
    f << (channels == 1 ? "Pf" : "PF") << "\n" << width << " " << height << "\n-1.0\n";
    size_t rowValues = size_t(width) * size_t(channels);
    std::vector<uint32_t> row(rowValues);
    for (int y = height - 1; y >= 0; --y) {
        std::memcpy(row.data(), data + size_t(y) * rowValues, rowValues * sizeof(float));
        if constexpr (std::endian::native == std::endian::big)
            for (uint32_t &v : row) v = __builtin_bswap32(v);
        f.write(reinterpret_cast<const char *>(row.data()),
                std::streamsize(rowValues * sizeof(float)));
    }
    f.close();
    if (!f) throw std::runtime_error("write error");
}

}  // namespace prism
