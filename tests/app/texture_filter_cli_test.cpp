// `prism info` says how textures filter; `prism render --texture-filter` overrides it (none:
// the images Prism rendered before filtering, point-sampled checkerboards), and refuses
// unknown filters.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "image/image_compare.h"
#include "image/image_io.h"
#include "support/process.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

TEST(TextureFilterCli, InfoSaysHowTexturesFilter) {
    fs::path dir = TempDir("info");
    RunResult r = RunPrism("info '" + Source + "/scenes/whitted.pbrt'", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("filtering:  checkerboard closedform 1; ray differentials on"),
              std::string::npos)
        << r.out;
}

TEST(TextureFilterCli, OverrideChangesTheFarCheckerboardAndRefusesUnknownFilters) {
    fs::path dir = TempDir("render");
    const std::string scene = "'" + Source + "/scenes/whitted.pbrt' --res 64x48 --quiet";
    ASSERT_EQ(RunPrism("render " + scene + " -o f.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render " + scene + " --texture-filter none -o n.exr", dir).exitCode, 0);
    ASSERT_EQ(RunPrism("render " + scene + " --texture-filter ewa -o e.exr", dir).exitCode, 0);
    Image f = ReadImage((dir / "f.exr").string()), n = ReadImage((dir / "n.exr").string());
    Image e = ReadImage((dir / "e.exr").string());
    // The scene's images have no imagemap: ewa changes nothing; none point-samples the board.
    EXPECT_EQ(CompareImages(f, e, 0.f).maxAbs, 0.0);
    EXPECT_GT(CompareImages(f, n, 1e-3f).badPixels, 10);
    RunResult bad = RunPrism("render " + scene + " --texture-filter mitchell -o b.exr", dir);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("texture-filter"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace prism
