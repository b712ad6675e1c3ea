// Image reading (through the OpenImageIO module, loaded at first use) and the sRGB curves.
// Writing lives in image_write.cpp.
#include "image/image_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "core/file_io.h"
#include "core/memory.h"
#include "image/image_decoder.h"
#include "image/oiio_loader.h"

namespace prism {

namespace fs = std::filesystem;

float SrgbToLinear(float v) {
    // Evaluated in double so the float result is correctly rounded for round trips.
    double d = v;
    if (d <= 0.04045) return float(d / 12.92);
    return float(std::pow((d + 0.055) / 1.055, 2.4));
}

float LinearToSrgb(float v) {
    double d = v;
    if (d <= 0.0031308) return float(d * 12.92);
    return float(1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

namespace {

// The 8-bit encoding by the definition: the sRGB curve in double, rounded.
uint8_t LinearToSrgb8Exact(float v) {
    if (!(v > 0)) return 0;  // also NaN
    if (v >= 1) return 255;
    return uint8_t(std::lround(std::clamp(LinearToSrgb(v), 0.f, 1.f) * 255.f));
}

// thresholds[k - 1] is the smallest float that encodes to k (k = 1..255), found by bisection
// over the ordered bit patterns of positive floats; the encoding is monotonic, so a binary
// search over these gives LinearToSrgb8Exact's result exactly, without a pow per channel.
const std::array<float, 255> &Srgb8Thresholds() {
    static const std::array<float, 255> thresholds = [] {
        std::array<float, 255> t{};
        for (int k = 1; k <= 255; ++k) {
            uint32_t lo = 0, hi = std::bit_cast<uint32_t>(1.0f);  // encodes to 0 / to 255
            while (hi - lo > 1) {
                uint32_t mid = lo + (hi - lo) / 2;
                (LinearToSrgb8Exact(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
            }
            t[size_t(k - 1)] = std::bit_cast<float>(hi);
        }
        return t;
    }();
    return thresholds;
}

}  // namespace

uint8_t LinearToSrgb8(float v) {
    if (!(v > 0)) return 0;  // also NaN
    if (v >= 1) return 255;
    const std::array<float, 255> &t = Srgb8Thresholds();
    return uint8_t(std::upper_bound(t.begin(), t.end(), v) - t.begin());
}

namespace {

const std::array<float, 256> &Srgb8Table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = SrgbToLinear(float(i) / 255.f);
        return t;
    }();
    return table;
}

}  // namespace

namespace {

// Decoder libraries under OpenImageIO (libpng, libjpeg, ...) print errors such as "libpng
// error: ..." to stderr before OIIO reports the same failure, which would give bad input two
// error lines (the direct PNG reader silences libpng itself). Decoding runs with stderr pointed
// at /dev/null; the lock serializes decoders (they are not called from render threads).
class QuietStderr {
  public:
    QuietStderr() : lock_(Mutex()) {
        std::fflush(stderr);
        saved_ = ::dup(2);
        int null = ::open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
        if (null >= 0) ::close(null);
    }
    ~QuietStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, 2);
            ::close(saved_);
        }
    }
    QuietStderr(const QuietStderr &) = delete;
    QuietStderr &operator=(const QuietStderr &) = delete;

  private:
    static std::mutex &Mutex() {
        static std::mutex m;
        return m;
    }
    std::lock_guard<std::mutex> lock_;
    int saved_ = -1;
};

// An image opened by the OpenImageIO module.
class OiioDecoder : public ImageDecoder {
  public:
    OiioDecoder(const PrismOiioModule &module, PrismOiioInput *in) : module_(module), in_(in) {}
    ~OiioDecoder() override { module_.close(in_); }
    OiioDecoder(const OiioDecoder &) = delete;
    OiioDecoder &operator=(const OiioDecoder &) = delete;
    PrismOiioSpec Spec() const override {
        PrismOiioSpec spec{};
        module_.getSpec(in_, &spec);
        return spec;
    }
    void ReadFloat(int nchannels, float *out) override {
        char err[512] = "";
        if (!module_.readFloat(in_, nchannels, out, err, sizeof(err)))
            throw std::runtime_error(err);
    }

  private:
    const PrismOiioModule &module_;
    PrismOiioInput *in_;
};

// Decodes an opened image into linear float (shared by the file and in-memory readers).
Image DecodeOpened(ImageDecoder &in, const ReadImageOptions &opts,
                   const std::function<std::runtime_error(const std::string &)> &fail) {
    PrismOiioSpec spec = in.Spec();
    if (spec.deep) throw fail("deep images are not supported");
    if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels <= 0)
        throw fail("invalid image dimensions");

    // Channels read from the file and channels of the result.
    int nFile = spec.nchannels;
    int nRead, nOut;
    if (nFile == 1) {
        nRead = nOut = 1;
    } else if (nFile == 2) {
        nRead = 2;  // gray + alpha
        nOut = 4;
    } else if (nFile == 3 || spec.alphaChannel != 3) {
        nRead = nOut = 3;
    } else {
        nRead = nOut = 4;
    }
    int64_t count = int64_t(spec.width) * int64_t(spec.height) * int64_t(std::max(nRead, nOut));
    if (count > opts.maxPixels) {
        // A memory limit: MemoryBudgetError, so that callers can tell it from a bad file.
        uint64_t bytes = uint64_t(count) * sizeof(float);
        uint64_t limit = uint64_t(std::max<int64_t>(opts.maxPixels, 0)) * sizeof(float);
        throw MemoryBudgetError(
            FileLoc{},
            fail("image is too large: " + std::to_string(spec.width) + "x" +
                 std::to_string(spec.height) + "x" + std::to_string(nOut) + " values need " +
                 FormatBytes(bytes) + ", more than the limit of " + FormatBytes(limit))
                .what(),
            bytes, 0, limit);
    }

    PixelVector buf(size_t(spec.width) * size_t(spec.height) * size_t(nRead));
    try {
        in.ReadFloat(nRead, buf.data());
    } catch (const std::runtime_error &e) {
        throw fail(e.what());
    }

    bool integer = !spec.isFloat;
    bool srgb = opts.encoding == ReadImageOptions::Encoding::SRGB ||
                (opts.encoding == ReadImageOptions::Encoding::Auto && integer);
    bool eightBit = spec.isUint8 != 0;
    int nColor = nRead == 2 || nRead == 4 ? nRead - 1 : nRead;
    // The colour channels (not alpha) through a transfer curve; 8-bit values arrive as k/255,
    // and the curve's table at k gives the same result faster.
    auto decode = [&](const std::array<float, 256> &table, auto curve) {
        for (size_t i = 0; i < buf.size(); i += size_t(nRead)) {
            for (int c = 0; c < nColor; ++c) {
                float &v = buf[i + size_t(c)];
                v = eightBit ? table[size_t(std::clamp(std::lround(v * 255.f), 0L, 255L))]
                             : curve(v);
            }
        }
    };
    if (srgb) {
        decode(Srgb8Table(), [](float v) { return SrgbToLinear(v); });
    } else if (opts.encoding == ReadImageOptions::Encoding::Gamma && integer) {
        std::array<float, 256> table;
        for (size_t k = 0; k < 256; ++k)
            table[k] = float(std::pow(double(k) / 255.0, double(opts.gamma)));
        decode(table, [g = opts.gamma](float v) { return std::pow(std::max(v, 0.f), g); });
    }

    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = nOut;
    if (nRead == nOut) {
        img.pixels = std::move(buf);
    } else {
        img.pixels.resize(size_t(spec.width) * size_t(spec.height) * 4);
        for (size_t i = 0, n = size_t(spec.width) * size_t(spec.height); i < n; ++i) {
            float g = buf[2 * i], a = buf[2 * i + 1];
            img.pixels[4 * i + 0] = g;
            img.pixels[4 * i + 1] = g;
            img.pixels[4 * i + 2] = g;
            img.pixels[4 * i + 3] = a;
        }
    }
    return img;
}

// OpenEXR 3.1 allocates whatever an attribute's size field claims before reading the value,
// so a 100-byte hostile file can cost gigabytes. Walk the header attributes (name\0 type\0
// int32 size, value) of every part first and reject sizes that exceed the file. Its line and
// tile buffers are sized from dataWindow x channels before any pixel is read, so those are
// checked against `maxPixels` here too. `data` holds the first `avail` bytes of a file of
// `fileSize` bytes; checking stops where `data` ends.
void CheckExrHeader(const unsigned char *data, size_t avail, uint64_t fileSize, int64_t maxPixels,
                    const std::function<std::runtime_error(const std::string &)> &fail) {
    if (avail < 8 || data[0] != 0x76 || data[1] != 0x2f || data[2] != 0x31 || data[3] != 0x01)
        return;
    bool multipart = (data[5] & 0x10) != 0;  // version flag bit 12
    size_t pos = 8;
    auto i32 = [&](size_t at) {
        return int32_t(uint32_t(data[at]) | uint32_t(data[at + 1]) << 8 |
                       uint32_t(data[at + 2]) << 16 | uint32_t(data[at + 3]) << 24);
    };
    auto skipString = [&]() {
        while (pos < avail && data[pos] != 0) ++pos;
        if (pos >= avail) return false;
        ++pos;
        return true;
    };
    for (int part = 0; part < (1 << 16); ++part) {
        if (pos >= avail) return;
        if (data[pos] == 0) {  // empty header: end of the part list (or of a single part)
            return;
        }
        int64_t width = 0, height = 0, channels = 0, tileW = 0, tileH = 0;
        while (pos < avail && data[pos] != 0) {
            size_t nameAt = pos;
            if (!skipString()) return;
            size_t typeAt = pos;
            if (!skipString() || pos + 4 > avail) return;
            int32_t size = i32(pos);
            pos += 4;
            if (size < 0 || uint64_t(size) > fileSize - pos)
                throw fail("corrupt OpenEXR header (an attribute claims " + std::to_string(size) +
                           " bytes)");
            if (pos + size_t(size) > avail) return;
            std::string name(reinterpret_cast<const char *>(data + nameAt));
            std::string type(reinterpret_cast<const char *>(data + typeAt));
            if (name == "dataWindow" && type == "box2i" && size == 16) {
                width = int64_t(i32(pos + 8)) - i32(pos) + 1;
                height = int64_t(i32(pos + 12)) - i32(pos + 4) + 1;
            } else if (name == "tiles" && type == "tiledesc" && size >= 8) {
                tileW = uint32_t(i32(pos));
                tileH = uint32_t(i32(pos + 4));
            } else if (name == "channels" && type == "chlist") {
                // name\0 then 16 bytes per channel; a lone null byte ends the list
                for (size_t c = pos, end = pos + size_t(size); c < end && data[c] != 0;) {
                    while (c < end && data[c] != 0) ++c;
                    c += 17;
                    ++channels;
                }
            }
            pos += size_t(size);
        }
        ++pos;  // the header's terminating null byte
        channels = std::max<int64_t>(channels, 1);
        // Up to 256 scanlines (or one tile) are buffered per block, whatever the image height.
        int64_t lines = std::min<int64_t>(std::max<int64_t>(height, 1), 256);
        if (width > 0 && height > 0 &&
            (width > maxPixels / height / channels || width > maxPixels / lines / channels ||
             (tileW > 0 && tileH > 0 && tileW > maxPixels / tileH / channels)))
            throw fail("image is too large (" + std::to_string(width) + "x" +
                       std::to_string(height) + "x" + std::to_string(channels) + " values)");
        if (!multipart) return;
    }
}

// The OpenImageIO module, or the reason it cannot be loaded as a read error.
const PrismOiioModule &LoadModule(
    const std::function<std::runtime_error(const std::string &)> &fail) {
    try {
        return OiioModule();
    } catch (const std::runtime_error &e) {
        throw fail(e.what());
    }
}

}  // namespace

namespace {

Image ReadImageFile(const std::string &path, const ReadImageOptions &opts, bool direct) {
    auto fail = [&](const std::string &why) {
        return std::runtime_error("cannot read image " + Quote(path) + ": " + why);
    };
    // --confine (core/file_io.h): the image must resolve to a regular file inside the folder,
    // and is read through ReadFileContents (checked again on the opened file) and decoded from
    // memory, so that no decoder opens the path again after the check.
    if (std::string why = ReadConfinementRefusal(path); !why.empty()) throw fail(why);
    if (!ReadConfinementFolder().empty()) {
        std::vector<unsigned char> bytes;
        FileReadError err;
        // An encoded file larger than its decoded float pixels may be would be odd.
        uint64_t limit = std::max<uint64_t>(uint64_t(std::max<int64_t>(opts.maxPixels, 0)) * 4,
                                            uint64_t(16) << 20);
        if (!ReadFileContents(path, &bytes, &err, limit))
            throw fail(err.tooLarge ? "the file is larger than " + std::to_string(limit) +
                                          " bytes, more than its pixels may take"
                                    : err.reason);
        return ReadImageFromMemory(bytes, path, opts);
    }
    std::optional<QuietStderr> quiet;
    if (opts.quietDecoders) quiet.emplace();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw fail(fs::exists(path, ec) ? "not a regular file" : "file not found");
    {
        // OpenEXR files (by magic number, whatever the extension) get their header checked.
        std::ifstream f(path, std::ios::binary);
        unsigned char magic[4] = {};
        f.read(reinterpret_cast<char *>(magic), 4);
        uint64_t size = fs::file_size(path, ec);
        if (f.gcount() == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 &&
            magic[3] == 0x01 && !ec) {
            std::vector<unsigned char> head(size_t(std::min<uint64_t>(size, 16u << 20)));
            f.seekg(0);
            f.read(reinterpret_cast<char *>(head.data()), std::streamsize(head.size()));
            head.resize(size_t(f.gcount()));
            CheckExrHeader(head.data(), head.size(), size, opts.maxPixels, fail);
        }
    }
    // PNG and OpenEXR are decoded directly; only other formats load OpenImageIO.
    std::unique_ptr<ImageDecoder> decoder;
    try {
        if (direct) decoder = OpenDirectDecoder(path, nullptr, 0);
    } catch (const std::runtime_error &e) {
        throw fail(e.what());
    }
    if (decoder) return DecodeOpened(*decoder, opts, fail);
    const PrismOiioModule &module = LoadModule(fail);
    char err[512] = "";
    PrismOiioInput *in = module.openFile(path.c_str(), opts.tryAllFormats, err, sizeof(err));
    if (!in) throw fail(err);
    OiioDecoder oiio(module, in);
    return DecodeOpened(oiio, opts, fail);
}

}  // namespace

Image ReadImage(const std::string &path, ReadImageOptions opts) {
    return ReadImageFile(path, opts, true);
}

Image ReadImageWithOiio(const std::string &path, ReadImageOptions opts) {
    return ReadImageFile(path, opts, false);
}

Image ReadImageFromMemory(const std::vector<unsigned char> &bytes, const std::string &name,
                          ReadImageOptions opts) {
    auto fail = [&](const std::string &why) {
        return std::runtime_error("cannot read image " + Quote(name) + ": " + why);
    };
    if (bytes.empty()) throw fail("no data");
    std::optional<QuietStderr> quiet;
    if (opts.quietDecoders) quiet.emplace();
    CheckExrHeader(bytes.data(), bytes.size(), bytes.size(), opts.maxPixels, fail);
    std::unique_ptr<ImageDecoder> direct;
    try {
        direct = OpenDirectDecoder(name, bytes.data(), bytes.size());
    } catch (const std::runtime_error &e) {
        throw fail(e.what());
    }
    if (direct) return DecodeOpened(*direct, opts, fail);
    const PrismOiioModule &module = LoadModule(fail);
    char err[512] = "";
    PrismOiioInput *in = module.openMemory(bytes.data(), bytes.size(), name.c_str(),
                                           opts.tryAllFormats, err, sizeof(err));
    if (in) {
        OiioDecoder decoder(module, in);
        return DecodeOpened(decoder, opts, fail);
    }
    // Some of OIIO's readers (JPEG in 2.4) cannot read from memory: decode through a private
    // temporary file that is removed straight away.
    std::string ext = fs::path(name).extension().string();
    std::string pattern = (fs::temp_directory_path() / ("prism-image-XXXXXX" + ext)).string();
    std::vector<char> tmpl(pattern.begin(), pattern.end());
    tmpl.push_back('\0');
    int fd = mkstemps(tmpl.data(), int(ext.size()));
    if (fd < 0) throw fail("cannot create a temporary file to decode it");
    std::string tmp(tmpl.data());
    bool ok = ::write(fd, bytes.data(), bytes.size()) == ssize_t(bytes.size());
    ::close(fd);
    try {
        if (!ok) throw fail("cannot write a temporary file to decode it");
        PrismOiioInput *fin = module.openFile(tmp.c_str(), opts.tryAllFormats, err, sizeof(err));
        if (!fin) throw fail(err);
        OiioDecoder decoder(module, fin);
        Image img = DecodeOpened(decoder, opts, fail);
        std::error_code ec;
        fs::remove(tmp, ec);
        return img;
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
}

}  // namespace prism
