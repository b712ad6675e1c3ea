// Hostile image files are rejected before the decoder allocates: OpenEXR headers whose
// attribute sizes or data window exceed the file or the pixel limit, and images over maxPixels.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/memory.h"
#include "image/image_io.h"
#include "support/errors.h"
#include "support/shared.h"

namespace prism {
namespace {

using namespace test;

std::vector<unsigned char> Bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::string Bad = test::Source + "/tests/bad/tex/";

TEST(ImageLimits, ExrAttributeLargerThanTheFileIsRejected) {
    std::vector<unsigned char> b = Bytes(Bad + "huge_attribute.exr");
    ASSERT_FALSE(b.empty());
    std::string err = ErrorOf<std::runtime_error>([&] { ReadImageFromMemory(b, "t.exr"); });
    EXPECT_NE(err.find("corrupt OpenEXR header (an attribute claims 2147418112 bytes)"),
              std::string::npos)
        << err;
    // The same through a file, whatever its extension says.
    err = ErrorOf<std::runtime_error>([&] { ReadImage(Bad + "huge_attribute.exr"); });
    EXPECT_NE(err.find("corrupt OpenEXR header"), std::string::npos) << err;
}

TEST(ImageLimits, ExrDataWindowBeyondThePixelLimitIsRejected) {
    std::vector<unsigned char> b = Bytes(Bad + "huge_window.exr");
    std::string err = ErrorOf<std::runtime_error>([&] { ReadImageFromMemory(b, "t.exr"); });
    EXPECT_NE(err.find("image is too large (2000000001x2000000001x1 values)"), std::string::npos)
        << err;
}

TEST(ImageLimits, ValidExrStillReadsAndMaxPixelsIsEnforced) {
    Image img;
    img.width = 8;
    img.height = 4;
    img.channels = 3;
    img.pixels.assign(8 * 4 * 3, 0.5f);
    std::string path = ::testing::TempDir() + "prism_limits_ok.exr";
    WriteImage(path, img);
    std::vector<unsigned char> b = Bytes(path);
    Image back = ReadImageFromMemory(b, "ok.exr");
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(back.pixels[5], 0.5f);
    ReadImageOptions small;
    small.maxPixels = 95;  // 8 x 4 x 3 = 96 values
    std::string err = ErrorOf<std::runtime_error>([&] { ReadImageFromMemory(b, "ok.exr", small); });
    EXPECT_NE(err.find("image is too large"), std::string::npos) << err;
    small.maxPixels = 96;
    EXPECT_NO_THROW(ReadImage(path, small));
    std::string png = ::testing::TempDir() + "prism_limits_ok.png";
    WriteImage(png, img);
    small.maxPixels = 95;
    err = ErrorOf<std::runtime_error>([&] { ReadImage(png, small); });
    EXPECT_NE(err.find("image is too large: 8x4x3 values need 384 bytes, more than the limit of "
                       "380 bytes"),
              std::string::npos)
        << err;
    // A memory limit, not a bad file: MemoryBudgetError, and the library names no flag.
    EXPECT_EQ(err.find("--max-memory"), std::string::npos) << err;
    try {
        ReadImage(png, small);
        ADD_FAILURE() << "no error";
    } catch (const MemoryBudgetError &e) {
        EXPECT_EQ(e.Requested(), 384u);
        EXPECT_EQ(e.Limit(), 380u);
    }
}

}  // namespace
}  // namespace prism
