// Everything Prism accepts and does not simulate is named once, at its location: the sampler
// and accelerator types, and parameters that have no effect (WarnIgnored). An ordinary scene
// warns about nothing. Also: glass with a textured roughness is accepted (pbrt-v3 input).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/shared.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

fs::path ScratchDir() {
    fs::path dir = fs::path(::testing::TempDir()) / "prism_ignored_params";
    fs::create_directories(dir);
    return dir;
}

// Loads and builds `text` (written to <scratch>/<name>.pbrt) and returns its warnings.
std::vector<Warning> BuildWarnings(const std::string &name, const std::string &text,
                                   fs::path *file = nullptr) {
    fs::path path = ScratchDir() / (name + ".pbrt");
    std::ofstream(path) << text;
    if (file) *file = path;
    Diagnostics diag;
    SceneDescription desc = LoadScene(path.string(), diag);
    BuildSettings settings;
    settings.resolution = {8, 8};
    settings.defaultIntegrator = "whitted";
    BuildRenderScene(desc, settings, diag);
    return diag.Warnings();
}

// "file:line:col" of the first occurrence of `needle` in `text`.
std::string LocOf(const fs::path &file, const std::string &text, const std::string &needle) {
    size_t at = text.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    int line = 1, col = 1;
    for (size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    return file.string() + ":" + std::to_string(line) + ":" + std::to_string(col);
}

// Exactly one warning mentions `what` (a quoted name), at the first place `needle` is written.
void ExpectOneWarning(const std::vector<Warning> &warnings, const fs::path &file,
                      const std::string &text, const std::string &what, const std::string &needle) {
    SCOPED_TRACE(what);
    int n = 0;
    for (const Warning &w : warnings) {
        if (w.message.find(what) == std::string::npos) continue;
        ++n;
        EXPECT_EQ(w.loc.ToString(), LocOf(file, text, needle)) << w.ToString();
    }
    EXPECT_EQ(n, 1);
}

const char *World = R"(WorldBegin
LightSource "point" "point3 from" [0 5 0]
)";

TEST(IgnoredParams, SamplerTypeAndParameters) {
    std::string text = std::string(
                           "Sampler \"sobol\" \"integer pixelsamples\" 4\n"
                           "    \"integer dimensions\" 7 \"bool samplepixelcenter\" \"true\"\n") +
                       World + "Shape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("sampler", text, &file);
    ExpectOneWarning(w, file, text, "sampler \"sobol\" is replaced by Prism's stratified sampler",
                     "Sampler");
    ExpectOneWarning(w, file, text, "\"dimensions\"", "\"integer dimensions\"");
    ExpectOneWarning(w, file, text, "\"samplepixelcenter\"", "\"bool samplepixelcenter\"");
    EXPECT_EQ(w.size(), 3u);
    // The stratified sampler's own parameters have an effect (jitter included, by design).
    text = std::string(
               "Sampler \"stratified\" \"integer xsamples\" 2 \"integer ysamples\" 2 "
               "\"bool jitter\" \"false\"\n") +
           World + "Shape \"sphere\"\n";
    EXPECT_TRUE(BuildWarnings("sampler_stratified", text).empty());
}

TEST(IgnoredParams, Accelerator) {
    std::string text = std::string(
                           "Accelerator \"bvh\" \"integer maxnodeprims\" 4\n"
                           "    \"string splitmethod\" \"sah\"\n") +
                       World + "Shape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("accelerator", text, &file);
    ExpectOneWarning(w, file, text, "Accelerator \"bvh\" is replaced by Embree's BVH",
                     "Accelerator");
    ExpectOneWarning(w, file, text, "\"maxnodeprims\"", "\"integer maxnodeprims\"");
    ExpectOneWarning(w, file, text, "\"splitmethod\"", "\"string splitmethod\"");
    EXPECT_EQ(w.size(), 3u);
}

// The shutter is read since motion blur exists (issue 12); only the diagonal is ignored.
TEST(IgnoredParams, CameraShutterAndFilmDiagonal) {
    std::string text = std::string(
                           "Camera \"perspective\" \"float shutteropen\" 0\n"
                           "    \"float shutterclose\" 1\n"
                           "Film \"image\" \"float diagonal\" 35\n") +
                       World + "Shape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("camera", text, &file);
    ExpectOneWarning(w, file, text, "\"diagonal\"", "\"float diagonal\"");
    EXPECT_EQ(w.size(), 1u);
}

TEST(IgnoredParams, IntegratorParametersOtherThanMaxdepth) {
    std::string text = std::string(
                           "Integrator \"whitted\" \"integer maxdepth\" 3\n"
                           "    \"integer pixelbounds\" [0 4 0 4]\n") +
                       World + "Shape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("integrator_whitted", text, &file);
    ExpectOneWarning(w, file, text, "\"pixelbounds\"", "\"integer pixelbounds\"");
    EXPECT_EQ(w.size(), 1u);

    // An integrator Prism does not have renders with Whitted; its parameters are named.
    text = std::string(
               "Integrator \"nosuchintegrator\" \"integer maxdepth\" 3 \"bool "
               "visualizestrategies\" true\n"
               "    \"string lightsamplestrategy\" \"spatial\"\n") +
           World + "Shape \"sphere\"\n";
    w = BuildWarnings("integrator_unknown", text, &file);
    ExpectOneWarning(w, file, text, "is rendered with Whitted", "Integrator");
    ExpectOneWarning(w, file, text, "\"visualizestrategies\"", "\"bool visualizestrategies\"");
    ExpectOneWarning(w, file, text, "\"lightsamplestrategy\"", "\"string lightsamplestrategy\"");
    EXPECT_EQ(w.size(), 3u);

    // The path integrator reads rrthreshold and lightsamplestrategy ("spatial": the light
    // BVH, silently), pixelbounds is named as ignored.
    text =
        std::string(
            "Integrator \"path\" \"integer maxdepth\" 3 \"float rrthreshold\" 0.5\n"
            "    \"string lightsamplestrategy\" \"spatial\" \"integer pixelbounds\" [0 4 0 4]\n") +
        World + "Shape \"sphere\"\n";
    w = BuildWarnings("integrator_path", text, &file);
    ExpectOneWarning(w, file, text, "\"pixelbounds\"", "\"integer pixelbounds\"");
    EXPECT_EQ(w.size(), 1u);

    // pbrt-v4's lightsampler: "exhaustive" is named for its stand-in, an unknown one too.
    for (const char *sampler : {"exhaustive", "nosuchsampler"}) {
        text = std::string("Integrator \"volpath\" \"string lightsampler\" \"") + sampler + "\"\n" +
               World + "Shape \"sphere\"\n";
        w = BuildWarnings(std::string("integrator_lightsampler_") + sampler, text, &file);
        ExpectOneWarning(w, file, text, "light BVH", "\"string lightsampler\"");
        EXPECT_EQ(w.size(), 1u) << sampler;
    }
}

TEST(IgnoredParams, TriangleMeshTangentsAndFaceIndices) {
    const std::string mesh =
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2] "
        "\"point3 P\" [0 0 0 1 0 0 0 1 0]\n"
        "    \"vector3 S\" [1 0 0 1 0 0 1 0 0] \"integer faceIndices\" [0]\n";
    std::string text = World + mesh + mesh;  // twice: still one warning each
    fs::path file;
    auto w = BuildWarnings("trianglemesh", text, &file);
    ExpectOneWarning(w, file, text, "\"S\"", "\"vector3 S\"");
    ExpectOneWarning(w, file, text, "\"faceIndices\"", "\"integer faceIndices\"");
    EXPECT_EQ(w.size(), 2u);
}

// pbrt-v3's checkerboard "aamode" is honoured ("closedform", "none"); an unknown one warns.
TEST(IgnoredParams, CheckerboardClosedForm) {
    const std::string tex =
        "Texture \"c%\" \"spectrum\" \"checkerboard\" \"string aamode\" "
        "\"closedform\"\n";
    std::string text = World;
    for (char c : {'1', '2'}) {
        std::string t = tex;
        t[t.find('%')] = c;
        text += t;
    }
    text +=
        "Texture \"n\" \"spectrum\" \"checkerboard\" \"string aamode\" \"none\"\n"
        "Texture \"x\" \"spectrum\" \"checkerboard\" \"string aamode\" \"supersample\"\n"
        "Material \"matte\" \"texture Kd\" \"c1\"\nShape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("checkerboard", text, &file);
    ExpectOneWarning(w, file, text, "\"supersample\"", "\"string aamode\" \"supersample\"");
    EXPECT_EQ(w.size(), 1u);
}

// The imagemap's "filter", "trilinear" and "maxanisotropy" are honoured (docs/MATERIALS.md);
// an unknown filter warns, and so does an encoding other than sRGB, linear or "gamma G".
TEST(IgnoredParams, ImageMapFilteringAndEncoding) {
    Image img(2, 2, 3);
    WriteImage((ScratchDir() / "tex.png").string(), img);
    const std::string tex =
        "Texture \"t%\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\"\n"
        "    \"string filter\" \"ewa\" \"bool trilinear\" \"true\" \"float maxanisotropy\" 16\n"
        "    \"string encoding\" \"log\"\n";
    std::string text = World;
    for (char c : {'1', '2'}) {
        std::string t = tex;
        t[t.find('%')] = c;
        text += t;
    }
    // Honoured: pbrt-v4's bilinear filter and sRGB, linear and gamma encodings.
    text +=
        "Texture \"b\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\" "
        "\"string filter\" \"bilinear\" \"string encoding\" \"linear\"\n"
        "Texture \"g\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\" "
        "\"string encoding\" \"gamma 2.2\"\n"
        "Texture \"u\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\" "
        "\"string filter\" \"mitchell\"\n"
        "Material \"matte\" \"texture Kd\" \"t1\"\nShape \"sphere\"\n";
    fs::path file;
    auto w = BuildWarnings("imagemap", text, &file);
    ExpectOneWarning(w, file, text, "\"mitchell\"", "\"string filter\" \"mitchell\"");
    ExpectOneWarning(w, file, text, "\"encoding\"", "\"string encoding\"");
    EXPECT_EQ(w.size(), 2u);
}

// A "gamma G" encoding whose G is not a positive number is an error at the parameter.
TEST(IgnoredParams, ImageMapBadGammaIsAnError) {
    Image img(2, 2, 3);
    WriteImage((ScratchDir() / "tex.png").string(), img);
    for (const char *g : {"gamma", "gamma x", "gamma -1", "gamma 2.2x", "gamma inf"}) {
        SCOPED_TRACE(g);
        const std::string text =
            std::string(World) +
            "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\"\n"
            "    \"string encoding\" \"" +
            g +
            "\"\n"
            "Material \"matte\" \"texture Kd\" \"t\"\nShape \"sphere\"\n";
        fs::path file;
        const std::string what = ErrorOf<SceneError>([&] { BuildWarnings("gamma", text, &file); });
        EXPECT_NE(what.find(LocOf(file, text, "\"string encoding\"")), std::string::npos) << what;
        EXPECT_NE(what.find("the gamma must be a positive number"), std::string::npos) << what;
    }
}

TEST(IgnoredParams, WhittedSceneWarnsAboutNothing) {
    Diagnostics diag;
    SceneDescription desc = LoadScene(Source + "/scenes/whitted.pbrt", diag);
    BuildSettings settings;
    settings.resolution = {8, 6};
    BuildRenderScene(desc, settings, diag);
    for (const Warning &w : diag.Warnings()) ADD_FAILURE() << w.ToString();
}

// pbrt-v3 glass may bind its roughness to a float texture; Whitted renders it smooth, as for a
// constant roughness, with the same warning (it used to be rejected: "must be float").
TEST(IgnoredParams, GlassWithTexturedRoughnessIsAccepted) {
    std::string text =
        std::string(World) +
        "Texture \"r\" \"float\" \"constant\" \"float value\" 0.2\n"
        "Texture \"z\" \"float\" \"constant\" \"float value\" 0\n"
        "Texture \"f\" \"float\" \"fbm\"\n"
        "Material \"glass\" \"texture uroughness\" \"r\" \"texture vroughness\" \"f\"\n"
        "Shape \"sphere\"\n"
        "Material \"glass\" \"texture roughness\" \"z\"\n"
        "Shape \"sphere\"\n";
    fs::path file;
    std::vector<Warning> w;
    ASSERT_NO_THROW(w = BuildWarnings("rough_glass", text, &file));
    // The first glass may be rough; the second is smooth (roughness texture constant 0).
    ExpectOneWarning(w, file, text, "rough glass is rendered as smooth glass",
                     "Material \"glass\"");
    EXPECT_EQ(w.size(), 1u);
}

}  // namespace
}  // namespace prism
