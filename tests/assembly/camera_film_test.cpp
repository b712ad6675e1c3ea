// The Sampler directive: which pattern each pbrt sampler's name draws (assembly/camera_film.cpp
// SamplerRules), its parameters, --sampler, and what a substitution says.
#include <gtest/gtest.h>

#include "support/errors.h"
#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

std::string SamplerScene(const std::string &sampler) {
    return "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\n" + sampler +
           "\nWorldBegin\nLightSource \"point\" \"point3 from\" [0 5 -5]\n" + "Shape \"sphere\"\n";
}

Built BuildSampler(const std::string &sampler, const std::string &integrator = "path",
                   const std::string &override = "") {
    BuildSettings s = SizedSettings(8, 8, 0, integrator);
    s.sampler = override;
    // One file per test (ctest runs them at once) and call.
    static int calls = 0;
    const std::string name =
        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
        std::to_string(calls++);
    return BuildSceneFile(WriteSceneText("camera_film", name, SamplerScene(sampler)), s);
}

int CountWarnings(const Built &b, const std::string &needle) {
    int n = 0;
    for (const Warning &w : b.warnings) n += w.message.find(needle) != std::string::npos;
    return n;
}

TEST(Sampler, EachNameDrawsItsPattern) {
    struct Case {
        const char *line;
        SamplePattern pattern;
        const char *warning;  // "": none
    };
    const Case cases[] = {
        {"Sampler \"zsobol\" \"integer pixelsamples\" 16", SamplePattern::ZSobol, ""},
        {"Sampler \"paddedsobol\" \"integer pixelsamples\" 16", SamplePattern::PaddedSobol, ""},
        {"Sampler \"02sequence\"", SamplePattern::ZeroTwo, ""},
        {"Sampler \"lowdiscrepancy\"", SamplePattern::ZeroTwo, ""},
        {"Sampler \"random\"", SamplePattern::Independent, ""},
        {"Sampler \"independent\"", SamplePattern::Independent, ""},
        {"Sampler \"stratified\"", SamplePattern::Stratified, ""},
        {"Sampler \"pmj02bn\"", SamplePattern::PaddedSobol,
         "sampler \"pmj02bn\" is drawn as \"paddedsobol\""},
        {"Sampler \"halton\"", SamplePattern::Halton, ""},
        {"Sampler \"sobol\"", SamplePattern::Sobol, ""},
        {"Sampler \"maxmindist\"", SamplePattern::Stratified,
         "sampler \"maxmindist\" is replaced by Prism's stratified sampler: Prism has no"},
        {"Sampler \"nosuch\"", SamplePattern::Stratified,
         "sampler \"nosuch\" is replaced by Prism's stratified sampler: Prism does not know"},
        {"", SamplePattern::Halton, ""},  // no Sampler: pbrt-v3's "halton"
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.line);
        const Built b = BuildSampler(c.line);
        EXPECT_EQ(b.scene.sampler.pattern, c.pattern);
        if (*c.warning)
            EXPECT_EQ(CountWarnings(b, c.warning), 1);
        else
            EXPECT_EQ(CountWarnings(b, "sampler"), 0);
    }
}

TEST(Sampler, SobolParameters) {
    Built b = BuildSampler(
        "Sampler \"zsobol\" \"integer pixelsamples\" 8 \"string randomization\" "
        "\"permutedigits\" \"integer seed\" 9");
    EXPECT_EQ(b.scene.sampler.scramble, SobolScramble::Xor);
    EXPECT_EQ(b.scene.sampler.seed, 9u);
    EXPECT_EQ(b.scene.sampler.spp, 8);
    EXPECT_EQ(b.scene.sampler.log2Res, 3);  // 8 x 8
    EXPECT_EQ(CountWarnings(b, "sampler"), 0);
    b = BuildSampler("Sampler \"paddedsobol\" \"string randomization\" \"none\"");
    EXPECT_EQ(b.scene.sampler.scramble, SobolScramble::None);
    b = BuildSampler("Sampler \"paddedsobol\" \"string randomization\" \"owen\"");
    EXPECT_EQ(b.scene.sampler.scramble, SobolScramble::Owen);
    // A bad randomization is an error at the parameter.
    const std::string text =
        SamplerScene("Sampler \"zsobol\"\n   \"string randomization\" \"bogus\"");
    const std::string err = ErrorOf<SceneError>([&] {
        BuildSceneFile(WriteSceneText("camera_film", "bad_randomization", text),
                       SizedSettings(8, 8, 0, "path"));
    });
    EXPECT_NE(err.find("bad_randomization.pbrt:4:4:"), std::string::npos) << err;
    EXPECT_NE(err.find("randomization \"bogus\" is not one of"), std::string::npos) << err;
}

// pbrt-v4's halton: random digit permutations by default, "owen" and "none"; pbrt-v4 has no
// fastowen for it; the film's tiling is the resolution's (2^3 >= 8 columns, 3^2 >= 8 rows).
TEST(Sampler, HaltonParameters) {
    Built b = BuildSampler("Sampler \"halton\" \"integer pixelsamples\" 8");
    EXPECT_EQ(b.scene.sampler.halton.scramble, HaltonScramble::PermuteDigits);
    EXPECT_EQ(b.scene.sampler.halton.scaleX, 8u);
    EXPECT_EQ(b.scene.sampler.halton.scaleY, 9u);
    EXPECT_EQ(CountWarnings(b, "sampler"), 0);
    b = BuildSampler("Sampler \"halton\" \"string randomization\" \"owen\" \"integer seed\" 4");
    EXPECT_EQ(b.scene.sampler.halton.scramble, HaltonScramble::Owen);
    EXPECT_EQ(b.scene.sampler.seed, 4u);
    b = BuildSampler("Sampler \"halton\" \"string randomization\" \"none\"");
    EXPECT_EQ(b.scene.sampler.halton.scramble, HaltonScramble::None);
    const std::string text =
        SamplerScene("Sampler \"halton\"\n   \"string randomization\" \"fastowen\"");
    const std::string err = ErrorOf<SceneError>([&] {
        BuildSceneFile(WriteSceneText("camera_film", "halton_fastowen", text),
                       SizedSettings(8, 8, 0, "path"));
    });
    EXPECT_NE(err.find("halton_fastowen.pbrt:4:4:"), std::string::npos) << err;
    EXPECT_NE(err.find("has no fastowen"), std::string::npos) << err;
}

// Integrators that draw their own samples keep the stratified pattern and say so.
TEST(Sampler, IntegratorsWithTheirOwnSamples) {
    const Built b = BuildSampler("Sampler \"zsobol\"", "whitted");
    EXPECT_EQ(b.scene.sampler.pattern, SamplePattern::Stratified);
    EXPECT_EQ(CountWarnings(b,
                            "sampler \"zsobol\" is replaced by Prism's stratified sampler: "
                            "the integrator \"whitted\" draws its own"),
              1);
}

// --sampler replaces the type, keeps the count, and reads none of the file's parameters.
TEST(Sampler, OverrideKeepsTheCount) {
    const Built b =
        BuildSampler("Sampler \"halton\" \"integer pixelsamples\" 32 \"integer dimensions\" 4",
                     "path", "zsobol");
    EXPECT_EQ(b.scene.sampler.pattern, SamplePattern::ZSobol);
    EXPECT_EQ(b.scene.sampler.spp, 32);
    EXPECT_EQ(CountWarnings(b, "sampler"), 0);
}

// The Sobol patterns render the same image on any thread count, and camera samples come
// from the pattern (a different image from the stratified one's).
TEST(Sampler, SobolImagesAreDeterministic) {
    for (const char *name : {"zsobol", "paddedsobol", "halton"}) {
        SCOPED_TRACE(name);
        const std::string path = WriteSceneText(
            "camera_film", name,
            SamplerScene(std::string("Sampler \"") + name + "\" \"integer pixelsamples\" 4"));
        const BuildSettings s = SizedSettings(16, 16, 0, "path");
        const Built b = BuildSceneFile(path, s);
        const Image one = RenderOnThreads(b.scene, 1), two = RenderOnThreads(b.scene, 2);
        EXPECT_EQ(one.pixels, two.pixels);
        BuildSettings strat = s;
        strat.sampler = "stratified";
        const Built c = BuildSceneFile(path, strat);
        EXPECT_NE(RenderOnThreads(c.scene, 1).pixels, one.pixels);
    }
}

}  // namespace
}  // namespace prism
