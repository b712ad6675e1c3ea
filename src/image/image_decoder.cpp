// Direct PNG and OpenEXR decoding; see image_decoder.h.
#include "image/image_decoder.h"

#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfPartType.h>
#include <ImfVersion.h>
#include <png.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace prism {

namespace {

// ---- PNG ----

// Where libpng's callbacks read from and report to.
struct PngState {
    FILE *file = nullptr;
    const unsigned char *mem = nullptr;
    size_t size = 0, pos = 0;
    bool eof = false;
    char message[256] = "";
};

void PngRead(png_structp png, png_bytep out, size_t n) {
    auto *s = static_cast<PngState *>(png_get_io_ptr(png));
    size_t got;
    if (s->file) {
        got = std::fread(out, 1, n, s->file);
    } else {
        got = std::min(n, s->size - s->pos);
        std::memcpy(out, s->mem + s->pos, got);
        s->pos += got;
    }
    if (got != n) {
        s->eof = true;
        png_error(png, "hit end of file");
    }
}

void PngError(png_structp png, png_const_charp msg) {
    auto *s = static_cast<PngState *>(png_get_error_ptr(png));
    std::snprintf(s->message, sizeof(s->message), "%s", msg);
    png_longjmp(png, 1);
}

void PngWarning(png_structp, png_const_charp) {}

// The setjmp frames hold no C++ objects, so libpng's longjmp skips no destructors.
bool PngReadHeader(png_structp png, png_infop info) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    png_set_expand(png);  // palette -> RGB, gray below 8 bits -> 8, tRNS -> alpha
    if (png_get_bit_depth(png, info) == 16) png_set_swap(png);  // host (little-endian) order
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    return true;
}

bool PngReadRows(png_structp png, png_bytep *rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    return true;
}

class PngDecoder : public ImageDecoder {
  public:
    // `file` (owned) is positioned after the signature, or `data` holds the whole file.
    PngDecoder(FILE *file, const unsigned char *data, size_t size) {
        state_.file = file;
        state_.mem = data;
        state_.size = size;
        state_.pos = 8;
    }
    // Reads the header; throws (the destructor then releases everything).
    void Open() {
        png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state_, PngError, PngWarning);
        if (png_) info_ = png_create_info_struct(png_);
        if (!png_ || !info_) throw std::runtime_error("out of memory");
        png_set_read_fn(png_, &state_, PngRead);
        if (!PngReadHeader(png_, info_)) Fail();
        spec_.width = int(std::min<png_uint_32>(png_get_image_width(png_, info_), 1u << 30));
        spec_.height = int(std::min<png_uint_32>(png_get_image_height(png_, info_), 1u << 30));
        spec_.depth = 1;
        spec_.nchannels = png_get_channels(png_, info_);
        spec_.alphaChannel = spec_.nchannels == 2 ? 1 : spec_.nchannels == 4 ? 3 : -1;
        spec_.isFloat = 0;
        bits_ = png_get_bit_depth(png_, info_);
        spec_.isUint8 = bits_ == 8 ? 1 : 0;
        spec_.deep = 0;
    }
    ~PngDecoder() override {
        if (png_) png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr);
        if (state_.file) std::fclose(state_.file);
    }
    PrismOiioSpec Spec() const override { return spec_; }
    void ReadFloat(int nchannels, float *out) override {
        if (nchannels != spec_.nchannels || (bits_ != 8 && bits_ != 16))
            throw std::runtime_error("unsupported PNG layout");
        size_t rowBytes = png_get_rowbytes(png_, info_);
        size_t w = size_t(spec_.width), h = size_t(spec_.height), n = size_t(nchannels);
        if (rowBytes != w * n * size_t(bits_ / 8)) throw std::runtime_error("unsupported PNG");
        std::vector<unsigned char> bytes(rowBytes * h);
        std::vector<png_bytep> rows(h);
        for (size_t y = 0; y < h; ++y) rows[y] = bytes.data() + y * rowBytes;
        if (!PngReadRows(png_, rows.data())) Fail();
        size_t count = w * h * n;
        if (bits_ == 8) {
            for (size_t i = 0; i < count; ++i) out[i] = float(bytes[i]) * (1.f / 255.f);
        } else {
            for (size_t i = 0; i < count; ++i) {
                uint16_t v;
                std::memcpy(&v, bytes.data() + 2 * i, 2);
                out[i] = float(v) * (1.f / 65535.f);
            }
        }
    }

  private:
    // The wording follows what OpenImageIO reported for the same failures.
    [[noreturn]] void Fail() {
        if (state_.eof) throw std::runtime_error("Read error: hit end of file");
        throw std::runtime_error(std::string("PNG read error: ") + state_.message);
    }

    PngState state_;
    png_structp png_ = nullptr;
    png_infop info_ = nullptr;
    PrismOiioSpec spec_{};
    int bits_ = 8;
};

// ---- OpenEXR ----

// An OpenEXR input stream over a FILE* or memory; a short read is an error.
class ExrIStream : public Imf::IStream {
  public:
    ExrIStream(FILE *file, const unsigned char *data, size_t size, const std::string &name)
        : Imf::IStream(name.c_str()), file_(file), mem_(data), size_(size) {}
    ~ExrIStream() override {
        if (file_) std::fclose(file_);
    }
    bool read(char c[], int n) override {
        if (n < 0) throw IEX_NAMESPACE::InputExc("invalid read");
        if (file_) {
            if (std::fread(c, 1, size_t(n), file_) != size_t(n))
                throw IEX_NAMESPACE::InputExc("hit end of file");
            return true;
        }
        if (size_t(n) > size_ - pos_) throw IEX_NAMESPACE::InputExc("hit end of file");
        std::memcpy(c, mem_ + pos_, size_t(n));
        pos_ += size_t(n);
        return pos_ < size_;
    }
    uint64_t tellg() override { return file_ ? uint64_t(ftello(file_)) : pos_; }
    void seekg(uint64_t pos) override {
        if (file_) {
            if (fseeko(file_, off_t(pos), SEEK_SET) != 0)
                throw IEX_NAMESPACE::InputExc("seek error");
        } else {
            pos_ = size_t(std::min<uint64_t>(pos, size_));
        }
    }
    void clear() override {
        if (file_) std::clearerr(file_);
    }

  private:
    FILE *file_;
    const unsigned char *mem_;
    size_t size_, pos_ = 0;
};

class ExrDecoder : public ImageDecoder {
  public:
    ExrDecoder(std::unique_ptr<ExrIStream> stream, std::unique_ptr<Imf::InputFile> file,
               std::vector<std::string> channels)
        : stream_(std::move(stream)), file_(std::move(file)), channels_(std::move(channels)) {
        const Imath::Box2i &dw = file_->header().dataWindow();
        int64_t w = int64_t(dw.max.x) - dw.min.x + 1, h = int64_t(dw.max.y) - dw.min.y + 1;
        spec_.width = int(std::clamp<int64_t>(w, 0, 1 << 30));
        spec_.height = int(std::clamp<int64_t>(h, 0, 1 << 30));
        spec_.depth = 1;
        spec_.nchannels = int(channels_.size());
        spec_.alphaChannel = channels_.back() == "A" ? spec_.nchannels - 1 : -1;
        spec_.isFloat = 1;
        spec_.isUint8 = 0;
        spec_.deep = 0;
    }
    PrismOiioSpec Spec() const override { return spec_; }
    void ReadFloat(int nchannels, float *out) override {
        try {
            const Imath::Box2i &dw = file_->header().dataWindow();
            size_t xStride = sizeof(float) * size_t(nchannels);
            size_t yStride = xStride * size_t(spec_.width);
            // Slices are addressed from pixel (0, 0): offset the base by the data window.
            ptrdiff_t origin = -ptrdiff_t(dw.min.x) * ptrdiff_t(xStride) -
                               ptrdiff_t(dw.min.y) * ptrdiff_t(yStride);
            Imf::FrameBuffer fb;
            for (int c = 0; c < nchannels; ++c) {
                char *base = reinterpret_cast<char *>(out + c) + origin;
                fb.insert(channels_[size_t(c)], Imf::Slice(Imf::FLOAT, base, xStride, yStride));
            }
            file_->setFrameBuffer(fb);
            file_->readPixels(dw.min.y, dw.max.y);
        } catch (const std::exception &e) {
            throw std::runtime_error(std::string("OpenEXR: ") + e.what());
        }
    }

  private:
    std::unique_ptr<ExrIStream> stream_;
    std::unique_ptr<Imf::InputFile> file_;
    std::vector<std::string> channels_;
    PrismOiioSpec spec_{};
};

// The channel layouts the direct reader takes, in the order OpenImageIO gives them.
std::vector<std::string> SimpleExrChannels(const Imf::ChannelList &list) {
    std::vector<std::string> names;
    for (auto it = list.begin(); it != list.end(); ++it) {
        if (it.channel().type == Imf::UINT || it.channel().xSampling != 1 ||
            it.channel().ySampling != 1)
            return {};
        names.push_back(it.name());
    }
    std::sort(names.begin(), names.end());  // ChannelList is sorted too; be explicit
    if (names == std::vector<std::string>{"Y"}) return {"Y"};
    if (names == std::vector<std::string>{"A", "Y"}) return {"Y", "A"};
    if (names == std::vector<std::string>{"B", "G", "R"}) return {"R", "G", "B"};
    if (names == std::vector<std::string>{"A", "B", "G", "R"}) return {"R", "G", "B", "A"};
    return {};
}

std::unique_ptr<ImageDecoder> OpenExr(FILE *file, const unsigned char *data, size_t size,
                                      const std::string &path) {
    auto stream = std::make_unique<ExrIStream>(file, data, size, path);
    std::unique_ptr<Imf::InputFile> in;
    try {
        in = std::make_unique<Imf::InputFile>(*stream);
    } catch (const std::exception &e) {
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
    const Imf::Header &h = in->header();
    if (h.hasType() && h.type() != Imf::SCANLINEIMAGE && h.type() != Imf::TILEDIMAGE)
        return nullptr;
    if (Imf::isMultiPart(in->version())) return nullptr;
    std::vector<std::string> channels = SimpleExrChannels(h.channels());
    if (channels.empty()) return nullptr;
    return std::make_unique<ExrDecoder>(std::move(stream), std::move(in), std::move(channels));
}

}  // namespace

std::unique_ptr<ImageDecoder> OpenDirectDecoder(const std::string &path, const unsigned char *data,
                                                size_t size) {
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
    unsigned char magic[8] = {};
    size_t got = 0;
    FILE *file = nullptr;
    if (data) {
        got = std::min<size_t>(size, 8);
        std::memcpy(magic, data, got);
    } else {
        file = std::fopen(path.c_str(), "rb");
        if (!file) return nullptr;  // OpenImageIO reports it
        got = std::fread(magic, 1, 8, file);
    }
    if (got == 8 && std::memcmp(magic, kPng, 8) == 0) {
        auto png = std::make_unique<PngDecoder>(file, data, size);
        png->Open();
        return png;
    }
    if (got >= 4 && std::memcmp(magic, kExr, 4) == 0) {
        if (file) std::rewind(file);
        return OpenExr(file, data, size, path);
    }
    if (file) std::fclose(file);
    return nullptr;
}

}  // namespace prism
