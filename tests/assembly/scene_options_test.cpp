// pbrt-v4's Option directive (assembly/scene_options.h): seed, disablepixeljitter and
// disabletexturefiltering change the image; the rest are named in a warning.
#include "assembly/scene_options.h"

#include <gtest/gtest.h>

#include "image/image_io.h"
#include "support/errors.h"
#include "support/render_text.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

std::string TexturedScene(const std::string &options, const std::string &sampler) {
    return options + "\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n" +
           sampler +
           "\nIntegrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n"
           "LightSource \"point\" \"point3 from\" [0 0 5] \"rgb I\" [20 20 20]\n"
           "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"stripes.exr\"\n"
           "    \"float uscale\" 40\n"
           "Material \"diffuse\" \"texture reflectance\" \"t\"\n"
           "Shape \"trianglemesh\" \"point3 P\" [-2 -2 0 2 -2 0 2 2 0 -2 2 0] "
           "\"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 1 2 0 2 3]\n";
}

Built BuildOptions(const std::string &name, const std::string &options,
                   const std::string &sampler =
                       "Sampler \"stratified\" \"integer xsamples\" 2 "
                       "\"integer ysamples\" 2",
                   const BuildSettings &s = SizedSettings(16, 16, 0)) {
    Image stripes(8, 1, 3);
    for (int x = 0; x < 8; ++x) stripes.SetRGB(x, 0, RGB(x % 2 ? 0.9f : 0.1f));
    WriteImage((ScratchDir("scene_options") / "stripes.exr").string(), stripes);
    return BuildSceneFile(WriteSceneText("scene_options", name, TexturedScene(options, sampler)),
                          s);
}

TEST(SceneOptions, SeedChangesTheSamples) {
    for (const char *sampler : {"Sampler \"zsobol\" \"integer pixelsamples\" 4",
                                "Sampler \"stratified\" \"integer xsamples\" 2 "
                                "\"integer ysamples\" 2"}) {
        SCOPED_TRACE(sampler);
        const Built plain = BuildOptions("plain", "", sampler);
        const Built seeded = BuildOptions("seeded", "Option \"integer seed\" 7", sampler);
        EXPECT_EQ(seeded.scene.sampler.seed, 7u);
        EXPECT_TRUE(seeded.warnings.empty());
        EXPECT_NE(RenderOnThreads(plain.scene, 1).pixels, RenderOnThreads(seeded.scene, 1).pixels);
    }
    // A Sobol sampler's own seed wins.
    EXPECT_EQ(
        BuildOptions("own", "Option \"integer seed\" 7", "Sampler \"zsobol\" \"integer seed\" 2")
            .scene.sampler.seed,
        2u);
}

TEST(SceneOptions, PixelJitterAndTextureFiltering) {
    const Built centred = BuildOptions("centred", "Option \"bool disablepixeljitter\" true");
    EXPECT_FALSE(centred.scene.sampler.JitterFilm());
    EXPECT_TRUE(BuildOptions("jittered", "").scene.sampler.JitterFilm());
    // disabletexturefiltering renders what --texture-filter point renders.
    const Built unfiltered =
        BuildOptions("unfiltered", "Option \"bool disabletexturefiltering\" true");
    BuildSettings point = SizedSettings(16, 16, 0);
    point.textureFilter = "point";
    const Built pointed = BuildOptions("pointed", "",
                                       "Sampler \"stratified\" \"integer "
                                       "xsamples\" 2 \"integer ysamples\" 2",
                                       point);
    const Built filtered = BuildOptions("filtered", "");
    const Image u = RenderOnThreads(unfiltered.scene, 1);
    EXPECT_EQ(u.pixels, RenderOnThreads(pointed.scene, 1).pixels);
    EXPECT_NE(u.pixels, RenderOnThreads(filtered.scene, 1).pixels);
}

TEST(SceneOptions, OthersWarnAndBadValuesFail) {
    const Built b = BuildOptions("others",
                                 "Option \"bool forcediffuse\" true\n"
                                 "Option \"string rendercoordsys\" \"world\"\n"
                                 "Option \"integer frobnicate\" 1");
    ASSERT_EQ(b.warnings.size(), 3u);
    EXPECT_NE(b.warnings[0].message.find("Option \"forcediffuse\" has no effect"),
              std::string::npos);
    EXPECT_EQ(b.warnings[1].loc.line, 2);
    EXPECT_NE(b.warnings[2].message.find("\"frobnicate\" is not a pbrt-v4 option"),
              std::string::npos);
    const std::string err =
        ErrorOf<SceneError>([&] { BuildOptions("negative", "Option\n  \"integer seed\" -1"); });
    EXPECT_NE(err.find("negative.pbrt:2:3: error: Option \"seed\" must not be negative"),
              std::string::npos)
        << err;
}

}  // namespace
}  // namespace prism
