// OpenImageIO is a shared module loaded at first use: processes that read no image through it
// never map it, a missing module is a clear error, and the direct PNG/EXR writers are atomic
// even when the write itself fails.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "image/image_decoder.h"
#include "image/image_io.h"
#include "image/oiio_loader.h"
#include "support/image_stats.h"
#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

namespace fs = std::filesystem;

class ImageModuleTest : public test::FreshDirTest {};

const std::string Prism = PRISM_BINARY;
const std::string Whitted = test::Source + "/scenes/whitted.pbrt";

// A scene whose only image is a texture t.EXT (TGA is a format only OpenImageIO reads).
std::string WriteTexturedScene(const fs::path &dir, const std::string &ext = "tga") {
    Image tex = RandomImage(4, 4, 3, 0.f, 1.f, 5);
    WriteImage((dir / ("t." + ext)).string(), tex);
    std::ofstream f(dir / ("textured_" + ext + ".pbrt"));
    f << "Film \"image\" \"integer xresolution\" [8] \"integer yresolution\" [6]\n"
         "Camera \"perspective\"\n"
         "WorldBegin\n"
         "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"t."
      << ext
      << "\"\n"
         "Material \"matte\" \"texture Kd\" \"t\"\n"
         "Shape \"sphere\"\n"
         "WorldEnd\n";
    return (dir / ("textured_" + ext + ".pbrt")).string();
}

TEST_F(ImageModuleTest, PrismDoesNotLinkOpenImageIO) {
    RunResult r = RunShell("readelf -d '" + Prism + "'", dir_);
    if (r.exitCode != 0) GTEST_SKIP() << "readelf not available";
    EXPECT_NE(r.Both().find("NEEDED"), std::string::npos) << r.Both();
    EXPECT_EQ(r.Both().find("OpenImageIO"), std::string::npos) << r.Both();
}

TEST_F(ImageModuleTest, RenderWithoutImagesNeverMapsOpenImageIO) {
    // LD_DEBUG=files makes the dynamic loader report every library it maps, dlopen() included.
    RunResult r = RunPrism("render '" + Whitted + "' --res 8x6 --quiet -o '" + Path("w.png") + "'",
                           dir_, "LD_DEBUG=files");
    ASSERT_EQ(r.exitCode, 0) << r.Both();
    EXPECT_NE(r.Both().find("libpng16"), std::string::npos) << "LD_DEBUG output missing";
    EXPECT_EQ(r.Both().find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(r.Both().find("libprism_oiio"), std::string::npos);
    r = RunPrism("render '" + Whitted + "' --res 8x6 --quiet -o '" + Path("w.exr") + "'", dir_,
                 "LD_DEBUG=files");
    ASSERT_EQ(r.exitCode, 0) << r.Both();
    EXPECT_EQ(r.Both().find("libOpenImageIO"), std::string::npos);
    EXPECT_TRUE(fs::is_regular_file(Path("w.exr")));
}

TEST_F(ImageModuleTest, OnlyOtherFormatsLoadTheModule) {
    // PNG and EXR textures are read directly.
    for (const char *ext : {"png", "exr"}) {
        std::string scene = WriteTexturedScene(dir_, ext);
        RunResult r = RunPrism("render '" + scene + "' --quiet -o '" + Path("out.png") + "'", dir_,
                               "LD_DEBUG=files");
        ASSERT_EQ(r.exitCode, 0) << r.Both();
        EXPECT_EQ(r.Both().find("libOpenImageIO"), std::string::npos) << ext;
    }
    // A TGA texture loads the module.
    std::string scene = WriteTexturedScene(dir_);
    RunResult r = RunPrism("render '" + scene + "' --quiet -o '" + Path("out.png") + "'", dir_,
                           "LD_DEBUG=files");
    ASSERT_EQ(r.exitCode, 0) << r.Both();
    EXPECT_NE(r.Both().find("libprism_oiio"), std::string::npos);
    EXPECT_NE(r.Both().find("libOpenImageIO"), std::string::npos);
}

TEST_F(ImageModuleTest, MissingModuleIsAClearError) {
    std::string scene = WriteTexturedScene(dir_);
    RunResult r = RunPrism("render '" + scene + "' --quiet -o '" + Path("t.png") + "'", dir_,
                           "PRISM_OIIO_MODULE='" + Path("no-such-module.so") + "'");
    EXPECT_EQ(r.exitCode, 2) << r.Both();
    EXPECT_NE(r.Both().find("cannot read image"), std::string::npos) << r.Both();
    EXPECT_NE(r.Both().find("libprism_oiio.so could not be loaded"), std::string::npos) << r.Both();
    EXPECT_NE(r.Both().find("no-such-module.so: not found"), std::string::npos) << r.Both();
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one error line";
    EXPECT_FALSE(fs::exists(Path("t.png")));
    // A file that is not a shared library is reported with dlopen's reason.
    { std::ofstream(Path("fake.so")) << "not a library\n"; }
    r = RunPrism("render '" + scene + "' --quiet -o '" + Path("t.png") + "'", dir_,
                 "PRISM_OIIO_MODULE='" + Path("fake.so") + "'");
    EXPECT_EQ(r.exitCode, 2) << r.Both();
    EXPECT_NE(r.Both().find("fake.so: "), std::string::npos) << r.Both();
    // PNG and EXR output need no module.
    r = RunPrism("render '" + Whitted + "' --res 8x6 --quiet -o '" + Path("w.exr") + "'", dir_,
                 "PRISM_OIIO_MODULE='" + Path("no-such-module.so") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.Both();
}

TEST_F(ImageModuleTest, ModuleReadsAndWritesOtherFormats) {
    // JPEG and TGA go through the module, in this process.
    Image img = RandomImage(8, 8, 3, 0.f, 1.f, 11);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) img.SetRGB(x, y, RGB(0.2f, 0.5f, 0.8f));
    WriteImage(Path("a.jpg"), img);
    EXPECT_TRUE(OiioModuleLoaded());
    Image jpg = ReadImage(Path("a.jpg"));
    ASSERT_EQ(jpg.channels, 3);
    EXPECT_NEAR(jpg.GetRGB(4, 4).g, 0.5f, 0.02f);
    std::ifstream f(Path("a.jpg"), std::ios::binary);
    std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(f), {}};
    Image mem = ReadImageFromMemory(bytes, "embedded.jpg");
    EXPECT_EQ(mem.pixels, jpg.pixels);
}

TEST_F(ImageModuleTest, ExrAndPngRoundTripsAllLayouts) {
    for (int c : {1, 2, 3, 4}) {
        Image img = RandomImage(9, 7, c, -2.f, 70000.f, 20 + c);  // beyond half's range
        std::string exr = Path("r" + std::to_string(c) + ".exr");
        WriteImage(exr, img);
        Image back = ReadImage(exr);
        // Gray + alpha reads back as RGBA with the gray replicated.
        ASSERT_EQ(back.channels, c == 2 ? 4 : c);
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 9; ++x)
                for (int k = 0; k < back.channels; ++k) {
                    int src = c == 2 ? (k == 3 ? 1 : 0) : k;
                    ASSERT_EQ(back.At(x, y, k), img.At(x, y, src)) << c << " " << k;
                }

        Image ldr = RandomImage(9, 7, c, 0.f, 1.f, 30 + c);
        std::string png = Path("r" + std::to_string(c) + ".png");
        WriteImage(png, ldr);
        back = ReadImage(png);
        ASSERT_EQ(back.channels, c == 2 ? 4 : c);
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 9; ++x)
                for (int k = 0; k < back.channels; ++k) {
                    int src = c == 2 ? (k == 3 ? 1 : 0) : k;
                    bool isAlpha = (c == 2 || c == 4) && k == back.channels - 1;
                    float v = ldr.At(x, y, src), r = back.At(x, y, k);
                    float enc = isAlpha ? v : LinearToSrgb(v);
                    float encBack = isAlpha ? r : LinearToSrgb(r);
                    EXPECT_NEAR(encBack, enc, 1.f / 255.f) << c << " " << k;
                }
    }
}

TEST_F(ImageModuleTest, FailedWritesLeaveNoFile) {
    Image img = RandomImage(4, 4, 3, 0.f, 1.f, 3);
    // A missing directory and a parent that is a regular file (root ignores directory
    // permission bits, so a read-only directory would not fail).
    { std::ofstream(Path("plain")) << "x"; }
    for (const char *ext : {".png", ".exr", ".pfm", ".tga"}) {
        EXPECT_THROW(WriteImage(Path(std::string("missing/out") + ext), img), std::runtime_error)
            << ext;
        EXPECT_THROW(WriteImage(Path(std::string("plain/out") + ext), img), std::runtime_error)
            << ext;
    }
    EXPECT_EQ(ListDir(), std::set<std::string>{"plain"});
}

TEST_F(ImageModuleTest, WriteErrorMidFileRemovesTheTemporary) {
    // A file size limit makes the writes fail part-way (EFBIG), as a full disk would (ENOSPC).
    Image img = RandomImage(256, 256, 4, 0.f, 1.f, 4);  // noise does not compress
    struct rlimit saved;
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
    auto oldHandler = ::signal(SIGXFSZ, SIG_IGN);
    struct rlimit small = saved;
    small.rlim_cur = 20000;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string errors[2];
    int i = 0;
    for (const char *name : {"big.png", "big.exr"}) {
        try {
            WriteImage(Path(name), img);
        } catch (const std::runtime_error &e) {
            errors[i] = e.what();
        }
        ++i;
    }
    ::setrlimit(RLIMIT_FSIZE, &saved);
    ::signal(SIGXFSZ, oldHandler);
    for (const std::string &e : errors) {
        EXPECT_NE(e.find("cannot write image"), std::string::npos) << e;
        EXPECT_NE(e.find("File too large"), std::string::npos) << e;
    }
    EXPECT_TRUE(ListDir().empty());
    // And the same writes succeed without the limit.
    WriteImage(Path("big.exr"), img);
    EXPECT_EQ(ReadImage(Path("big.exr")).pixels, img.pixels);
}

// The direct PNG and OpenEXR readers give exactly what OpenImageIO gives, on every PNG and EXR
// in the repository and the shared scenes (palette, 16-bit, gray + alpha, half, tiled, ...),
// and fail on the same files.
TEST(ImageModule, DirectReadersMatchOpenImageIO) {
    std::vector<fs::path> files;
    for (const std::string &root :
         {test::Source + "/tests", test::Source + "/scenes", std::string(PRISM_SHARED_DIR)}) {
        std::error_code ec;
        if (!fs::is_directory(root, ec)) continue;
        for (auto it = fs::recursive_directory_iterator(root, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            std::string ext = it->path().extension().string();
            if ((ext == ".png" || ext == ".exr") && it->is_regular_file(ec) &&
                it->file_size(ec) < (32u << 20))
                files.push_back(it->path());
        }
    }
    ASSERT_GT(files.size(), 5u);
    int compared = 0;
    for (const fs::path &f : files) {
        for (auto enc : {ReadImageOptions::Encoding::Auto, ReadImageOptions::Encoding::Linear}) {
            ReadImageOptions opts;
            opts.encoding = enc;
            std::string errDirect, errOiio;
            Image direct, oiio;
            try {
                direct = ReadImage(f.string(), opts);
            } catch (const std::runtime_error &e) {
                errDirect = e.what();
            }
            try {
                oiio = ReadImageWithOiio(f.string(), opts);
            } catch (const std::runtime_error &e) {
                errOiio = e.what();
            }
            EXPECT_EQ(errDirect.empty(), errOiio.empty())
                << f << "\n  direct: " << errDirect << "\n  oiio: " << errOiio;
            if (!errDirect.empty() || !errOiio.empty()) continue;
            EXPECT_EQ(direct.width, oiio.width) << f;
            EXPECT_EQ(direct.height, oiio.height) << f;
            EXPECT_EQ(direct.channels, oiio.channels) << f;
            EXPECT_TRUE(direct.pixels == oiio.pixels) << f;
            ++compared;
        }
    }
    EXPECT_GT(compared, 5);
}

}  // namespace
}  // namespace prism
