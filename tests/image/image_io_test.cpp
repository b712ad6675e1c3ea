// Tests for image reading/writing, sRGB curves and atomic writes.
#include "image/image_io.h"

#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>

#include "support/image_stats.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

namespace fs = std::filesystem;

class ImageIOTest : public test::FreshDirTest {};

// The 8-bit encoding (a table of thresholds) equals its definition — the sRGB curve in double,
// rounded — on a dense sweep of floats in (0, 1), around every step, and at the edges.
TEST(Srgb, EightBitEncodingMatchesTheCurveExactly) {
    auto reference = [](float v) -> int {
        if (!(v > 0)) return 0;
        if (v >= 1) return 255;
        double d = v;
        float e = d <= 0.0031308 ? float(d * 12.92) : float(1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
        return int(std::lround(std::clamp(e, 0.f, 1.f) * 255.f));
    };
    const uint32_t one = std::bit_cast<uint32_t>(1.0f);
    int previous = 0;
    for (uint32_t bits = 0; bits <= one; bits += 1013) {
        float v = std::bit_cast<float>(bits);
        int want = reference(v);
        ASSERT_EQ(int(LinearToSrgb8(v)), want) << v;
        if (want != previous) {  // a step lies in the last stride: check every float of it
            for (uint32_t b = bits - 1013; b <= bits; ++b)
                ASSERT_EQ(int(LinearToSrgb8(std::bit_cast<float>(b))),
                          reference(std::bit_cast<float>(b)))
                    << std::bit_cast<float>(b);
            previous = want;
        }
    }
    for (float v : {-1.f, 0.f, 1.f, 2.f, std::numeric_limits<float>::quiet_NaN(),
                    std::numeric_limits<float>::infinity()})
        EXPECT_EQ(int(LinearToSrgb8(v)), reference(v)) << v;
}

TEST(Srgb, KnownValuesAndRoundTrip) {
    EXPECT_EQ(SrgbToLinear(0.f), 0.f);
    EXPECT_FLOAT_EQ(SrgbToLinear(1.f), 1.f);
    EXPECT_FLOAT_EQ(LinearToSrgb(1.f), 1.f);
    EXPECT_NEAR(SrgbToLinear(0.5f), 0.214041140f, 1e-7f);
    EXPECT_NEAR(LinearToSrgb(0.214041140f), 0.5f, 1e-7f);
    // The linear segment below the knee.
    EXPECT_FLOAT_EQ(SrgbToLinear(0.02f), 0.02f / 12.92f);
    EXPECT_FLOAT_EQ(LinearToSrgb(0.001f), 0.001f * 12.92f);
    // Continuity at the knee (the exact curves meet to ~1e-7).
    EXPECT_NEAR(LinearToSrgb(0.0031308f), 0.04045f, 1e-6f);
    for (int i = 0; i <= 1000; ++i) {
        float x = float(i) / 1000.f;
        EXPECT_NEAR(SrgbToLinear(LinearToSrgb(x)), x, 1e-6f * std::max(x, 1e-3f)) << x;
        EXPECT_NEAR(LinearToSrgb(SrgbToLinear(x)), x, 1e-6f) << x;
    }
    // Every 8-bit code survives decode + encode.
    for (int k = 0; k < 256; ++k) EXPECT_EQ(LinearToSrgb8(SrgbToLinear(k / 255.f)), k) << k;
    EXPECT_EQ(LinearToSrgb8(-1.f), 0);
    EXPECT_EQ(LinearToSrgb8(2.f), 255);
    EXPECT_EQ(LinearToSrgb8(NAN), 0);
}

TEST_F(ImageIOTest, ExrPreservesFloatsExactly) {
    for (int c : {1, 3, 4}) {
        Image img = RandomImage(7, 5, c, -10.f, 1000.f, 42 + c);
        img.At(0, 0, 0) = 1e-30f;   // would underflow in half
        img.At(1, 0, 0) = 3.0e38f;  // would overflow in half
        img.At(2, 0, 0) = 0.1f;     // not representable in half
        std::string path = Path("f" + std::to_string(c) + ".exr");
        WriteImage(path, img);
        Image back = ReadImage(path);
        ASSERT_EQ(back.width, 7);
        ASSERT_EQ(back.height, 5);
        ASSERT_EQ(back.channels, c);
        EXPECT_EQ(back.pixels, img.pixels) << "channels " << c;
    }
}

// An image in another RGB space than sRGB (a pbrt-v4 ColorSpace film) names its primaries and
// white in the EXR header, with or without named channels; an sRGB one writes none.
TEST_F(ImageIOTest, ExrRecordsChromaticities) {
    Image img = RandomImage(4, 3, 3, 0.f, 1.f, 7);
    const std::string plain = Path("plain.exr");
    WriteImage(plain, img);
    EXPECT_FALSE(Imf::hasChromaticities(Imf::InputFile(plain.c_str()).header()));
    img.chromaticities = {0.708f, 0.292f, 0.170f, 0.797f, 0.131f, 0.046f, 0.3127f, 0.3290f};
    const std::string tagged = Path("rec2020.exr"), channels = Path("aov.exr");
    WriteImage(tagged, img);
    const std::vector<float> extra(12, 0.5f);
    WriteMultiChannelExr(channels, img, {{"Z", extra.data(), 1}}, {});
    for (const std::string &path : {tagged, channels}) {
        SCOPED_TRACE(path);
        const Imf::InputFile in(path.c_str());
        ASSERT_TRUE(Imf::hasChromaticities(in.header()));
        const Imf::Chromaticities c = Imf::chromaticities(in.header());
        EXPECT_FLOAT_EQ(c.red.x, 0.708f);
        EXPECT_FLOAT_EQ(c.green.y, 0.797f);
        EXPECT_FLOAT_EQ(c.blue.y, 0.046f);
        EXPECT_FLOAT_EQ(c.white.x, 0.3127f);
    }
    EXPECT_EQ(ReadImage(tagged).pixels, img.pixels);
}

TEST_F(ImageIOTest, PfmAndHdrRoundTrip) {
    Image img = RandomImage(6, 4, 3, 0.01f, 50.f, 7);
    WriteImage(Path("a.pfm"), img);
    EXPECT_EQ(ReadImage(Path("a.pfm")).pixels, img.pixels);
    WriteImage(Path("a.hdr"), img);
    Image hdr = ReadImage(Path("a.hdr"));
    ASSERT_EQ(hdr.channels, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        // RGBE has an 8-bit mantissa shared against the largest component.
        int p = int(i / 3) * 3;
        float maxc = std::max({img.pixels[p], img.pixels[p + 1], img.pixels[p + 2]});
        EXPECT_NEAR(hdr.pixels[i], img.pixels[i], maxc / 128.f) << i;
    }
}

TEST_F(ImageIOTest, PngRoundTripWithinOneCode) {
    for (int c : {1, 3, 4}) {
        Image img = RandomImage(16, 9, c, -0.2f, 1.2f, 3 + c);
        std::string path = Path("p" + std::to_string(c) + ".png");
        WriteImage(path, img);
        Image back = ReadImage(path);
        ASSERT_EQ(back.width, 16);
        ASSERT_EQ(back.height, 9);
        ASSERT_EQ(back.channels, c);
        for (int y = 0; y < 9; ++y) {
            for (int x = 0; x < 16; ++x) {
                for (int k = 0; k < c; ++k) {
                    float v = std::clamp(img.At(x, y, k), 0.f, 1.f);
                    float r = back.At(x, y, k);
                    bool isAlpha = c == 4 && k == 3;
                    // Alpha is stored linearly; colour is compared in the encoded domain.
                    float enc = isAlpha ? v : LinearToSrgb(v);
                    float encBack = isAlpha ? r : LinearToSrgb(r);
                    EXPECT_NEAR(encBack, enc, 0.5f / 255.f + 1e-5f) << x << "," << y << "," << k;
                }
            }
        }
    }
}

TEST_F(ImageIOTest, PngWithTransparentPixelKeepsColour) {
    // Straight (unassociated) alpha: a transparent pixel keeps its colour.
    Image img(2, 1, 4);
    img.SetRGB(0, 0, RGB(0.5f, 0.25f, 1.f));
    img.At(0, 0, 3) = 0.f;
    img.SetRGB(1, 0, RGB(0.5f, 0.25f, 1.f));
    img.At(1, 0, 3) = 0.5f;
    WriteImage(Path("t.png"), img);
    Image back = ReadImage(Path("t.png"));
    ASSERT_EQ(back.channels, 4);
    for (int x = 0; x < 2; ++x) {
        EXPECT_NEAR(back.GetRGB(x, 0).r, 0.5f, 0.005f);
        EXPECT_NEAR(back.GetRGB(x, 0).g, 0.25f, 0.005f);
        EXPECT_NEAR(back.GetRGB(x, 0).b, 1.f, 0.005f);
    }
    EXPECT_EQ(back.At(0, 0, 3), 0.f);
    EXPECT_NEAR(back.At(1, 0, 3), 0.5f, 0.5f / 255.f + 1e-6f);
}

TEST_F(ImageIOTest, GrayAlphaBecomesRgba) {
    Image img(3, 2, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            img.At(x, y, 0) = 0.1f * float(x + 3 * y);
            img.At(x, y, 1) = 1.f;
        }
    WriteImage(Path("ga.png"), img);
    Image back = ReadImage(Path("ga.png"));
    ASSERT_EQ(back.channels, 4);
    RGB c = back.GetRGB(2, 1);
    EXPECT_NEAR(c.r, 0.5f, 0.005f);
    EXPECT_EQ(c.r, c.g);
    EXPECT_EQ(c.r, c.b);
    EXPECT_EQ(back.At(2, 1, 3), 1.f);
}

TEST_F(ImageIOTest, EncodingOverride) {
    Image img(1, 1, 1);
    img.At(0, 0, 0) = SrgbToLinear(128 / 255.f);
    WriteImage(Path("g.png"), img);
    EXPECT_NEAR(ReadImage(Path("g.png")).At(0, 0, 0), SrgbToLinear(128 / 255.f), 1e-6f);
    ReadImageOptions linear;
    linear.encoding = ReadImageOptions::Encoding::Linear;
    EXPECT_NEAR(ReadImage(Path("g.png"), linear).At(0, 0, 0), 128 / 255.f, 1e-6f);
    // pbrt-v4's "gamma G": the code's value to the power G.
    ReadImageOptions gamma;
    gamma.encoding = ReadImageOptions::Encoding::Gamma;
    gamma.gamma = 2.2f;
    EXPECT_NEAR(ReadImage(Path("g.png"), gamma).At(0, 0, 0), std::pow(128 / 255.f, 2.2f), 1e-6f);
    // Float files are linear under Auto, and under Gamma.
    img.At(0, 0, 0) = 0.5f;
    WriteImage(Path("g.exr"), img);
    EXPECT_EQ(ReadImage(Path("g.exr")).At(0, 0, 0), 0.5f);
    EXPECT_EQ(ReadImage(Path("g.exr"), gamma).At(0, 0, 0), 0.5f);
}

TEST_F(ImageIOTest, RowOrderIsPreserved) {
    Image img(2, 3, 3);
    for (int y = 0; y < 3; ++y) img.SetRGB(0, y, RGB(float(y)));
    WriteImage(Path("rows.pfm"), img);  // PFM stores rows bottom-up on disk
    Image back = ReadImage(Path("rows.pfm"));
    for (int y = 0; y < 3; ++y) EXPECT_EQ(back.GetRGB(0, y).r, float(y));
    // On disk the first row after the header is the bottom image row (y = 2).
    std::string bytes;
    {
        std::ifstream f(Path("rows.pfm"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(f), {});
    }
    size_t header = bytes.find("-1.0\n");
    ASSERT_NE(header, std::string::npos);
    ASSERT_EQ(bytes.size(), header + 5 + 2 * 3 * 3 * sizeof(float));
    float first;
    std::memcpy(&first, bytes.data() + header + 5, sizeof(float));
    EXPECT_EQ(first, 2.f);
    // PNG agrees with PFM on which row is the top.
    WriteImage(Path("rows.png"), img);
    Image png = ReadImage(Path("rows.png"));
    EXPECT_EQ(png.GetRGB(0, 0).r, 0.f);
    EXPECT_EQ(png.GetRGB(0, 2).r, 1.f);
}

TEST_F(ImageIOTest, FormatsWithoutAlphaOrGrayConvert) {
    Image rgba(4, 4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            rgba.SetRGB(x, y, RGB(0.5f, 0.2f, 0.8f));
            rgba.At(x, y, 3) = 0.5f;
        }
    WriteImage(Path("a.jpg"), rgba);
    Image jpg = ReadImage(Path("a.jpg"));
    EXPECT_EQ(jpg.channels, 3);
    EXPECT_NEAR(jpg.GetRGB(1, 1).g, 0.2f, 0.02f);
    WriteImage(Path("a.hdr"), Image(2, 2, 1));
    EXPECT_EQ(ReadImage(Path("a.hdr")).channels, 3);
    WriteImage(Path("a.pfm"), rgba);
    Image pfm = ReadImage(Path("a.pfm"));
    EXPECT_EQ(pfm.channels, 3);
    EXPECT_EQ(pfm.GetRGB(3, 3), RGB(0.5f, 0.2f, 0.8f));
    WriteImage(Path("a.tga"), rgba);
    EXPECT_EQ(ReadImage(Path("a.tga")).channels, 4);
}

TEST_F(ImageIOTest, MissingDirectoryThrowsAndLeavesNothing) {
    Image img(2, 2, 3);
    std::string path = Path("nope/out.png");
    EXPECT_THROW(WriteImage(path, img), std::runtime_error);
    EXPECT_FALSE(fs::exists(dir_ / "nope"));
    EXPECT_TRUE(ListDir().empty());
}

TEST_F(ImageIOTest, OverwriteReplacesFileAndLeavesNoTempFiles) {
    Image a = RandomImage(4, 4, 3, 0.f, 1.f, 1), b = RandomImage(8, 2, 3, 0.f, 1.f, 2);
    WriteImage(Path("out.exr"), a);
    WriteImage(Path("out.exr"), b);
    Image back = ReadImage(Path("out.exr"));
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(back.pixels, b.pixels);
    WriteImage(Path("out.png"), a);
    WriteImage(Path("out.png"), b);
    EXPECT_EQ(ReadImage(Path("out.png")).width, 8);
    EXPECT_EQ(ListDir(), (std::set<std::string>{"out.exr", "out.png"}));
}

TEST_F(ImageIOTest, FailedRenameRemovesTempFile) {
    // The target is a non-empty directory, so the final rename fails after OIIO wrote the
    // temporary file; the directory must stay and the temporary must be gone.
    fs::create_directories(dir_ / "out.exr" / "keep");
    Image img(2, 2, 3);
    EXPECT_THROW(WriteImage(Path("out.exr"), img), std::runtime_error);
    EXPECT_TRUE(fs::is_directory(dir_ / "out.exr" / "keep"));
    EXPECT_EQ(ListDir(), (std::set<std::string>{"out.exr"}));
}

TEST_F(ImageIOTest, UnsupportedExtensionThrows) {
    Image img(2, 2, 3);
    try {
        WriteImage(Path("out.xyz"), img);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("unsupported output format \".xyz\""),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(WriteImage(Path("noext"), img), std::runtime_error);
    EXPECT_TRUE(ListDir().empty());
}

TEST_F(ImageIOTest, InvalidImageIsRejected) {
    Image img(2, 2, 3);
    img.pixels.resize(5);
    EXPECT_THROW(WriteImage(Path("bad.exr"), img), std::runtime_error);
    EXPECT_THROW(WriteImage(Path("empty.exr"), Image()), std::runtime_error);
    EXPECT_TRUE(ListDir().empty());
}

TEST_F(ImageIOTest, ReadingBadFilesThrows) {
    EXPECT_THROW(ReadImage(Path("missing.png")), std::runtime_error);
    EXPECT_THROW(ReadImage(dir_.string()), std::runtime_error);
    {
        std::ofstream f(Path("text.png"));
        f << "this is not an image\n";
    }
    try {
        ReadImage(Path("text.png"));
        FAIL() << "expected an exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("cannot read image"), std::string::npos);
    }
    { std::ofstream f(Path("empty.exr")); }
    EXPECT_THROW(ReadImage(Path("empty.exr")), std::runtime_error);

    // Truncate a valid PNG at several points; every prefix must fail cleanly.
    WriteImage(Path("ok.png"), RandomImage(64, 64, 3, 0.f, 1.f, 9));
    std::string bytes;
    {
        std::ifstream f(Path("ok.png"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(f), {});
    }
    ASSERT_GT(bytes.size(), 200u);
    for (size_t len : {size_t(8), size_t(40), bytes.size() / 2, bytes.size() - 20}) {
        {
            std::ofstream f(Path("cut.png"), std::ios::binary | std::ios::trunc);
            f.write(bytes.data(), std::streamsize(len));
        }
        EXPECT_THROW(ReadImage(Path("cut.png")), std::runtime_error) << len;
    }
    // Same for EXR.
    WriteImage(Path("ok.exr"), RandomImage(64, 64, 3, 0.f, 1.f, 9));
    {
        std::ifstream f(Path("ok.exr"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(f), {});
    }
    {
        std::ofstream f(Path("cut.exr"), std::ios::binary | std::ios::trunc);
        f.write(bytes.data(), std::streamsize(bytes.size() / 2));
    }
    EXPECT_THROW(ReadImage(Path("cut.exr")), std::runtime_error);
}

TEST_F(ImageIOTest, SizeLimitIsCheckedBeforeReading) {
    WriteImage(Path("big.png"), Image(32, 32, 3));
    ReadImageOptions opts;
    opts.maxPixels = 32 * 32 * 3 - 1;
    try {
        ReadImage(Path("big.png"), opts);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
    }
    opts.maxPixels = 32 * 32 * 3;
    EXPECT_EQ(ReadImage(Path("big.png"), opts).width, 32);
}

}  // namespace
}  // namespace prism
