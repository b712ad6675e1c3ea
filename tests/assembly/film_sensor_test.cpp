// pbrt-v4's film sensor: ISO and shutter time scale the image, white balance maps daylight of
// the given temperature to white (assembly/film_sensor.h).
#include "assembly/film_sensor.h"

#include <gtest/gtest.h>

#include "scene/spectrum.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

TEST(FilmSensor, DaylightChromaticities) {
    // D65 and D50 (pbrt-v4 evaluates the locus at the CCT of 6500 K and 5000 K).
    auto d65 = DaylightChromaticity(6500), d50 = DaylightChromaticity(5000);
    EXPECT_NEAR(d65[0], 0.3127, 3e-4);
    EXPECT_NEAR(d65[1], 0.3290, 3e-4);
    EXPECT_NEAR(d50[0], 0.3457, 3e-4);
    EXPECT_NEAR(d50[1], 0.3585, 3e-4);
    EXPECT_GT(DaylightChromaticity(3000)[0], DaylightChromaticity(10000)[0]);  // warmer: redder
}

TEST(FilmSensor, WhiteBalanceMapsTheIlluminantToWhite) {
    for (double T : {3000.0, 5000.0, 6500.0, 10000.0}) {
        SCOPED_TRACE(T);
        const auto xy = DaylightChromaticity(T);
        const RGB white = XYZToRGB(xy[0] / xy[1], 1, (1 - xy[0] - xy[1]) / xy[1]);
        const RGB out = ApplyColorMatrix(WhiteBalanceMatrix(xy), white);
        EXPECT_NEAR(out.g / out.r, 1, 2e-3);
        EXPECT_NEAR(out.b / out.r, 1, 2e-3);
        EXPECT_NEAR(out.Luminance(), 1, 2e-3);  // Bradford keeps Y of the white
    }
    const auto id = WhiteBalanceMatrix({0.3127, 0.3290});
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(id[size_t(i)], i % 4 == 0 ? 1 : 0, 2e-4) << i;
}

std::string PlaneScene(const std::string &film, const std::string &camera = "") {
    return "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" "
           "[-0.1 0.1 -0.1 0.1] " +
           camera + "\nFilm " + film +
           "\nSampler \"independent\" \"integer pixelsamples\" 4\n"
           "Integrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n"
           "LightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0]\n"
           "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
           "Shape \"trianglemesh\" \"point3 P\" [-10 -10 0 10 -10 0 10 10 0 -10 10 0] "
           "\"integer indices\" [0 1 2 0 2 3]\n";
}

Built BuildFilm(const std::string &name, const std::string &film, const std::string &camera = "") {
    return BuildSceneFile(WriteSceneText("film_sensor", name, PlaneScene(film, camera)),
                          SizedSettings(4, 4, 0));
}

TEST(FilmSensor, IsoAndShutterTimeScaleTheImage) {
    EXPECT_FLOAT_EQ(BuildFilm("iso", "\"rgb\" \"float iso\" 400").scene.filmScale, 4);
    EXPECT_FLOAT_EQ(BuildFilm("shutter", "\"rgb\" \"float iso\" 200 \"float scale\" 3",
                              "\"float shutteropen\" 0 \"float shutterclose\" 0.25")
                        .scene.filmScale,
                    1.5f);
    // pbrt-v3's Film "image" has no sensor: its shutter does not darken it, iso is unread.
    const Built v3 = BuildFilm("v3", "\"image\" \"float iso\" 400",
                               "\"float shutteropen\" 0 \"float shutterclose\" 0.25");
    EXPECT_FLOAT_EQ(v3.scene.filmScale, 1);
    EXPECT_FALSE(v3.scene.filmColor);
    ASSERT_EQ(v3.warnings.size(), 1u);
    EXPECT_NE(v3.warnings[0].message.find("\"iso\""), std::string::npos);
}

// The image of a white light on a grey plane, against pbrt-v4's own (8x8, 64 spp; pbrt-v4 is
// spectral, so its blue is 2% below Prism's at 6500 K already).
TEST(FilmSensor, WhiteBalanceMatchesPbrtV4) {
    struct Case {
        float kelvin;
        RGB pbrt4;
    };
    for (const Case &c : {Case{5000, RGB(0.132027f, 0.162861f, 0.214231f)},
                          Case{10000, RGB(0.188204f, 0.157024f, 0.109692f)},
                          Case{6500, RGB(0.159470f, 0.159281f, 0.156340f)}}) {
        SCOPED_TRACE(c.kelvin);
        const Built b = BuildFilm("wb" + std::to_string(int(c.kelvin)),
                                  "\"rgb\" \"float whitebalance\" " + std::to_string(c.kelvin));
        ASSERT_TRUE(b.scene.filmColor);
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        const RGB m = MeanRGB(RenderOnThreads(b.scene, 1));
        EXPECT_NEAR(m.r / c.pbrt4.r, 1, 0.01);
        EXPECT_NEAR(m.g / c.pbrt4.g, 1, 0.01);
        EXPECT_NEAR(m.b / c.pbrt4.b, 1, 0.025);
    }
}

// pbrt-v4's ColorSpace: RGB values written in a space (before the Film: the film's too) on the
// grey-plane scene, against pbrt-v4's own images (8x8, 64 spp, /tmp files of the same text).
TEST(FilmSensor, ColorSpacesMatchPbrtV4) {
    struct Case {
        const char *name, *beforeFilm, *inWorld, *light, *reflectance;
        RGB pbrt4;
    };
    const Case cases[] = {
        // An ACES film under the default light (ACES's white): grey.
        {"aces", "ColorSpace \"aces2065-1\"", "", "", "[0.5 0.5 0.5]",
         RGB(0.158873f, 0.158995f, 0.156782f)},
        // A Rec. 2020 reflectance on a Rec. 2020 film.
        {"rec", "ColorSpace \"rec2020\"", "", "", "[0.6 0.3 0.2]",
         RGB(0.191898f, 0.095342f, 0.062600f)},
        // An ACES light (D60, warm) on an sRGB film.
        {"acelight", "", "ColorSpace \"aces2065-1\"", "\"rgb L\" [1 1 1]", "[0.5 0.5 0.5]",
         RGB(0.167009f, 0.158388f, 0.143182f)},
        // An ACES reflectance under the default light (ACES's white) on an sRGB film.
        {"acesrefl", "", "ColorSpace \"aces2065-1\"", "", "[0.3 0.2 0.1]",
         RGB(0.161308f, 0.057221f, 0.022799f)},
        // An sRGB reflectance on a DCI-P3 film.
        {"p3", "ColorSpace \"dci-p3\"", "ColorSpace \"srgb\"", "", "[0.8 0.2 0.2]",
         RGB(0.222206f, 0.069789f, 0.065676f)},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        std::string text = std::string(c.beforeFilm) + "\n" +
                           "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"orthographic\" "
                           "\"float screenwindow\" [-0.1 0.1 -0.1 0.1]\n"
                           "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
                           "Sampler \"independent\" \"integer pixelsamples\" 64\n"
                           "Integrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n";
        text += std::string(c.inWorld) +
                "\nLightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0] " +
                c.light + "\n";
        text += "Material \"diffuse\" \"rgb reflectance\" " + std::string(c.reflectance) +
                "\nShape \"trianglemesh\" \"point3 P\" [-10 -10 0 10 -10 0 10 10 0 -10 10 0] "
                "\"integer indices\" [0 1 2 0 2 3]\n";
        const Built b =
            BuildSceneFile(WriteSceneText("film_sensor", c.name, text), SizedSettings(8, 8, 64));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        // A film in another space than sRGB names it in its EXR header.
        const bool srgbFilm = *c.beforeFilm == 0;
        ASSERT_EQ(b.scene.filmChromaticities.has_value(), !srgbFilm);
        if (std::string(c.name) == "rec") EXPECT_FLOAT_EQ((*b.scene.filmChromaticities)[0], 0.708f);
        const RGB m = MeanRGB(RenderOnThreads(b.scene, 1));
        EXPECT_NEAR(m.r / c.pbrt4.r, 1, 0.02);
        EXPECT_NEAR(m.g / c.pbrt4.g, 1, 0.02);
        EXPECT_NEAR(m.b / c.pbrt4.b, 1, 0.05);
    }
}

// pbrt-v4's Film "maxcomponentvalue" scales a sample down to it by its largest component,
// after the film's scale (the plane's pixels are 0.159 each, 0.637 at ISO 400).
TEST(FilmSensor, MaxComponentValueClampsSamplesAfterTheScale) {
    struct Case {
        const char *film;
        float mean;
    };
    for (const Case &c :
         {Case{"\"rgb\" \"float maxcomponentvalue\" 0.1", 0.1f},
          Case{"\"rgb\" \"float maxcomponentvalue\" 1", 0.159155f},
          Case{"\"rgb\" \"float iso\" 400 \"float maxcomponentvalue\" 0.5", 0.5f}}) {
        SCOPED_TRACE(c.film);
        const Built b = BuildFilm("maxcomp", c.film);
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        const RGB m = MeanRGB(RenderOnThreads(b.scene, 1));
        EXPECT_NEAR(m.r, c.mean, 2e-3f);
        EXPECT_NEAR(m.b, c.mean, 2e-3f);
    }
    const std::string err = ErrorOf<SceneError>(
        [&] { BuildFilm("badmaxcomp", "\"rgb\"\n  \"float maxcomponentvalue\" 0"); });
    EXPECT_NE(err.find("badmaxcomp.pbrt:4:3: error: film \"maxcomponentvalue\" must be positive"),
              std::string::npos)
        << err;
}

TEST(FilmSensor, BadAndUnsimulatedValues) {
    const std::string text = PlaneScene("\"rgb\"\n  \"float iso\" -5");
    const std::string err = ErrorOf<SceneError>([&] {
        BuildSceneFile(WriteSceneText("film_sensor", "badiso", text), SizedSettings(4, 4, 0));
    });
    EXPECT_NE(err.find("badiso.pbrt:4:3: error: film \"iso\" must be positive"), std::string::npos)
        << err;
    const std::string wbErr =
        ErrorOf<SceneError>([&] { BuildFilm("badwb", "\"rgb\" \"float whitebalance\" 100"); });
    EXPECT_NE(wbErr.find("\"whitebalance\" must be 0 or a temperature"), std::string::npos);
    // A named sensor is warned and balanced to 6500 K; savefp16 and gbuffer say what they get.
    const Built named = BuildFilm("named",
                                  "\"gbuffer\" \"string sensor\" \"canon_eos_100d\" "
                                  "\"bool savefp16\" false");
    EXPECT_TRUE(named.scene.filmColor);
    std::string all;
    for (const Warning &w : named.warnings) all += w.message + "\n";
    EXPECT_NE(all.find("sensor \"canon_eos_100d\" is not simulated"), std::string::npos) << all;
    EXPECT_NE(all.find("\"savefp16\""), std::string::npos) << all;
    EXPECT_NE(all.find("film \"gbuffer\" writes its channels as Prism's AOVs"), std::string::npos)
        << all;
    EXPECT_NE(all.find("not pbrt-v4's default camera space"), std::string::npos) << all;
    EXPECT_EQ(named.scene.filmAovs, "albedo,P,depth,Ng,N,uv,variance");
    // The film's own "aovs" win; "world" is what Prism writes; another space is an error.
    const Built own = BuildFilm("own",
                                "\"gbuffer\" \"string aovs\" \"N,depth\" "
                                "\"string coordinatesystem\" \"world\"");
    EXPECT_EQ(own.scene.filmAovs, "N,depth");
    all.clear();
    for (const Warning &w : own.warnings) all += w.message + "\n";
    EXPECT_NE(all.find("as Prism's AOVs (N,depth"), std::string::npos) << all;
    EXPECT_EQ(all.find("camera space"), std::string::npos) << all;
    EXPECT_EQ(all.find("unused"), std::string::npos) << all;
    const std::string csErr = ErrorOf<SceneError>(
        [&] { BuildFilm("badcs", "\"gbuffer\" \"string coordinatesystem\" \"screen\""); });
    EXPECT_NE(csErr.find("\"coordinatesystem\" must be \"camera\" or \"world\""), std::string::npos)
        << csErr;
    // "rgb" writes no AOVs of its own.
    EXPECT_EQ(BuildFilm("rgbfilm", "\"rgb\"").scene.filmAovs, "");
}

}  // namespace
}  // namespace prism
