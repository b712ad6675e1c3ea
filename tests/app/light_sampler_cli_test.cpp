// `prism render` says how the path integrators chose the lights of their shadow rays, and
// `--light-sampler` overrides the scene's choice (the same image in expectation, another
// noise), refuses unknown names, and is named as without effect under Whitted.
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

TEST(LightSamplerCli, RenderSaysHowLightsAreChosenAndTheFlagOverridesIt) {
    fs::path dir = TempDir("render");
    const std::string scene = "'" + Source +
                              "/scenes/pbrt4-reference/manylights.pbrt' --res 40x30 --spp 4 "
                              "--no-progress";
    RunResult bvh = RunPrism("render " + scene + " -o b.exr", dir);
    ASSERT_EQ(bvh.exitCode, 0) << bvh.err;
    EXPECT_NE(bvh.err.find("lights: chosen by the light BVH (1024 parts, depth "),
              std::string::npos)
        << bvh.err;
    RunResult power = RunPrism("render " + scene + " --light-sampler power -o p.exr", dir);
    ASSERT_EQ(power.exitCode, 0) << power.err;
    EXPECT_NE(power.err.find("lights: chosen by power\n"), std::string::npos) << power.err;
    const Image b = ReadImage((dir / "b.exr").string()), p = ReadImage((dir / "p.exr").string());
    EXPECT_GT(CompareImages(b, p, 0.f).maxAbs, 0.0);  // another choice, another noise

    RunResult bad = RunPrism("render " + scene + " --light-sampler spatial -o x.exr", dir);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("--light-sampler"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "x.exr"));

    RunResult whitted = RunPrism("render '" + Source +
                                     "/scenes/whitted.pbrt' --res 16x12 --no-progress "
                                     "--light-sampler power -o w.exr",
                                 dir);
    ASSERT_EQ(whitted.exitCode, 0) << whitted.err;
    EXPECT_NE(whitted.err.find("--light-sampler has no effect on the whitted integrator"),
              std::string::npos)
        << whitted.err;
    EXPECT_EQ(whitted.err.find("lights: chosen"), std::string::npos) << whitted.err;
}

}  // namespace
}  // namespace prism
