// What changes with the pbrt version a file is read by (scene/pbrt_version.h): the default
// integrator and sampler, a light's non-RGB spectrum, a spot light's falloff, and a spectrum
// where pbrt-v4 takes one and Prism reads a number.
#include <gtest/gtest.h>

#include "render/light.h"
#include "render/sampler.h"
#include "support/render_text.h"

namespace prism {
namespace {

BuildSettings Small() {
    BuildSettings s;
    s.resolution = Vec2i(4, 4);
    s.cameraRelative = false;
    return s;
}

test::Built Build(const std::string &name, const std::string &text) {
    return test::BuildSceneFile(test::WriteSceneText("pbrt_rules", name, text), Small());
}

TEST(PbrtRules, APbrtV4FileWithoutIntegratorOrSamplerGetsPbrtV4sDefaults) {
    const test::Built v4 = Build("v4", "Film \"rgb\"\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_STREQ(v4.scene.IntegratorName(), "volpath");
    EXPECT_EQ(v4.scene.integratorWhy, "pbrt-v4's default: the scene names no Integrator");
    EXPECT_EQ(v4.scene.sampler.pattern, SamplePattern::ZSobol);
    EXPECT_EQ(v4.scene.trace.maxDepth, 5);
    const test::Built v3 = Build("v3", "WorldBegin\nShape \"sphere\"\n");
    EXPECT_STREQ(v3.scene.IntegratorName(), "path");
    EXPECT_EQ(v3.scene.integratorWhy, "pbrt-v3's default: the scene names no Integrator");
    EXPECT_NE(v3.scene.sampler.pattern, SamplePattern::ZSobol);
}

// Without a PixelFilter line pbrt-v4 filters with its gaussian (radius 1.5, sigma 0.5) and
// pbrt-v3 with the box (radius 0.5); pbrt-v4 names the radius "xradius" and the falloff
// "sigma".
TEST(PbrtRules, EachVersionHasItsDefaultPixelFilterAndParameterNames) {
    const test::Built v4 = Build("f4", "Film \"rgb\"\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(v4.scene.filter.kind, Filter::Kind::Gaussian);
    EXPECT_EQ(v4.scene.filter.radiusX, 1.5f);
    EXPECT_EQ(v4.scene.filter.alpha, 2.f);
    const test::Built v3 = Build("f3", "WorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(v3.scene.filter.kind, Filter::Kind::Box);
    EXPECT_EQ(v3.scene.filter.radiusX, 0.5f);
    const test::Built named =
        Build("fn",
              "Film \"rgb\"\nPixelFilter \"gaussian\" \"float xradius\" 1 "
              "\"float yradius\" 3 \"float sigma\" 0.25\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(named.scene.filter.radiusX, 1.f);
    EXPECT_EQ(named.scene.filter.radiusY, 3.f);
    EXPECT_EQ(named.scene.filter.alpha, 8.f);
    for (const Warning &w : named.warnings)  // all three read: none reported unused
        EXPECT_EQ(w.message.find("filter"), std::string::npos) << w.ToString();
    // A named filter keeps pbrt-v3's radius in a pbrt-v3 file.
    const test::Built mitchell =
        Build("fm", "PixelFilter \"gaussian\"\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(mitchell.scene.filter.radiusX, 2.f);
    // pbrt's sinc: radius 4 and tau 3 by default, both read.
    const test::Built sinc =
        Build("fs",
              "Film \"rgb\"\nPixelFilter \"sinc\" \"float tau\" 2\nWorldBegin\n"
              "Shape \"sphere\"\n");
    EXPECT_EQ(sinc.scene.filter.kind, Filter::Kind::LanczosSinc);
    EXPECT_EQ(sinc.scene.filter.radiusX, 4.f);
    EXPECT_EQ(sinc.scene.filter.tau, 2.f);
    for (const Warning &w : sinc.warnings)  // radius and tau read: none reported unused
        EXPECT_EQ(w.message.find("filter"), std::string::npos) << w.ToString();
}

// pbrt-v4 divides a light's spectrum by its luminance: a blackbody of any temperature emits
// as much as white 1; pbrt-v3 keeps the peak-normalised blackbody.
TEST(PbrtRules, APbrtV4BlackbodyLightHasLuminanceOne) {
    for (const char *t : {"2000", "6500"}) {
        SCOPED_TRACE(t);
        const test::Built v4 =
            Build(std::string("bb4-") + t,
                  std::string("WorldBegin\nLightSource \"point\" \"blackbody I\" ") + t +
                      " \"float scale\" 2\n");
        ASSERT_EQ(v4.scene.lights.size(), 1u);
        EXPECT_NEAR(v4.scene.lights[0]->Power(1), 2 * 4 * Pi, 1e-3 * 8 * Pi);
    }
    const test::Built v3 =
        Build("bb3", "WorldBegin\nLightSource \"point\" \"blackbody I\" [2000 1]\n");
    ASSERT_EQ(v3.scene.lights.size(), 1u);
    EXPECT_LT(v3.scene.lights[0]->Power(1), 0.5 * 4 * Pi);  // the visible tail of 2000 K
    // An RGB spectrum keeps its magnitude in both.
    const test::Built rgb =
        Build("rgb4", "Film \"rgb\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [2 2 2]\n");
    EXPECT_NEAR(rgb.scene.lights[0]->Power(1), 2 * 4 * Pi, 1e-4);
    // A named illuminant is its chromaticity at luminance 1.
    const test::Built illuminant =
        Build("illuminant", "WorldBegin\nLightSource \"point\" \"spectrum I\" \"stdillum-A\"\n");
    EXPECT_NEAR(illuminant.scene.lights[0]->Power(1), 4 * Pi, 1e-2);
}

// pbrt-v3's quartic falloff and pbrt-v4's smoothstep, halfway through the falloff band.
TEST(PbrtRules, ASpotLightFallsOffByItsVersionsCurve) {
    const std::string spot =
        "LightSource \"spot\" \"point3 from\" [0 0 0] \"point3 to\" [0 0 1] "
        "\"float coneangle\" 40 \"float conedeltaangle\" 20\n";
    const double cosStart = std::cos(Radians(20.0)), cosEnd = std::cos(Radians(40.0));
    const double cosMid = 0.5 * (cosStart + cosEnd), sinMid = std::sqrt(1 - cosMid * cosMid);
    const Vec3f w(float(sinMid), 0, float(cosMid));
    for (int v : {3, 4}) {
        SCOPED_TRACE(v);
        const test::Built b =
            Build("spot" + std::to_string(v), (v == 4 ? "Film \"rgb\"\n" : "Film \"image\"\n") +
                                                  std::string("WorldBegin\n") + spot);
        ASSERT_EQ(b.scene.lights.size(), 1u);
        const auto &s = static_cast<const SpotLight &>(*b.scene.lights[0]);
        EXPECT_NEAR(s.Falloff(w), v == 4 ? 0.5 : 0.0625, 1e-3);
    }
}

// pbrt-v4's "spectrum eta" on a dielectric: one index, its luminance-weighted mean, and a
// warning at the parameter that the glass does not disperse.
TEST(PbrtRules, ASpectralIndexOfRefractionIsItsMeanWithAWarning) {
    const test::Built b = Build("glass",
                                "WorldBegin\nLightSource \"point\"\nMaterial \"dielectric\"\n"
                                "  \"spectrum eta\" \"glass-BK7\"\nShape \"sphere\"\n");
    ASSERT_EQ(b.warnings.size(), 1u) << b.warnings.back().ToString();
    const std::string w = b.warnings[0].ToString();
    EXPECT_NE(w.find("glass.pbrt:4:3"), std::string::npos) << w;
    EXPECT_NE(w.find("without dispersion"), std::string::npos) << w;
    EXPECT_NE(w.find("1.51"), std::string::npos) << w;
    const test::Built flat = Build("flat",
                                   "WorldBegin\nLightSource \"point\"\nMaterial \"dielectric\"\n"
                                   "  \"rgb eta\" [1.4 1.4 1.4]\nShape \"sphere\"\n");
    EXPECT_TRUE(flat.warnings.empty());
}

}  // namespace
}  // namespace prism
