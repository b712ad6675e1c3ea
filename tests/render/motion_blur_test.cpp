// Motion blur (issue 12): a sphere moving across the shutter leaves a streak of the predicted
// length and profile; a moving mesh, a moving analytic shape and a moving instance agree; a
// scene where nothing moves renders bit-identical whatever its shutter, and whatever moves
// out of sight; bad motion input fails at its directive.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/render_text.h"
#include "support/shared.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// An orthographic 64 x 16 view of the window [-4, 4] x [-1, 1] (8 pixels a unit) against a
// white environment (radiance 1); black matte objects darken it by the fraction of the
// shutter they cover each point.
std::string Header(const std::string &camera = "", int spp = 256) {
    return "LookAt 0 0 -5  0 0 0  0 1 0\n"
           "Camera \"orthographic\" \"float screenwindow\" [ -4 4 -1 1 ] " +
           camera +
           "\n"
           "Film \"image\" \"integer xresolution\" [ 64 ] \"integer yresolution\" [ 16 ]\n"
           "Sampler \"stratified\" \"integer xsamples\" [ " +
           std::to_string(int(std::sqrt(spp))) + " ] \"integer ysamples\" [ " +
           std::to_string(int(std::sqrt(spp))) +
           " ]\n"
           "PixelFilter \"box\"\nIntegrator \"whitted\"\nWorldBegin\n"
           "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
           "Material \"matte\" \"rgb Kd\" [ 0 0 0 ]\n";
}

Rendered RenderText(const std::string &text, const std::string &name) {
    return RenderSceneText("prism_motion", name, text);
}

// Darkness (1 - red) of pixel (x, y).
double Dark(const Image &img, int x, int y) { return 1 - img.pixels[img.PixelOffset(x, y)]; }

// The expected darkness of pixel (px, py): the fraction of the pixel's area and of the
// shutter during which a disk of radius r centred at (c(t), 0), c moving linearly from x0 to
// x1, covers the point (numerically, on a fine grid).
double ExpectedDark(int px, int py, double r, double x0, double x1) {
    const int n = 24, nt = 200;
    double covered = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            // Raster (px, py) to the window: x = -4 + px / 8, y = 1 - py / 8.
            double x = -4 + (px + (i + 0.5) / n) / 8, y = 1 - (py + (j + 0.5) / n) / 8;
            for (int k = 0; k < nt; ++k) {
                double c = Lerp((k + 0.5) / nt, x0, x1);
                covered += (x - c) * (x - c) + y * y <= r * r;
            }
        }
    return covered / (double(n) * n * nt);
}

const char *MovingSphere =
    "AttributeBegin\n"
    "ActiveTransform StartTime\nTranslate -2 0 0\n"
    "ActiveTransform EndTime\nTranslate 2 0 0\n"
    "ActiveTransform All\n"
    "Shape \"sphere\" \"float radius\" [ 0.5 ]\n"
    "AttributeEnd\n";

TEST(MotionBlur, MovingSphereLeavesTheStreakPredicted) {
    Rendered r = RenderText(Header() + MovingSphere, "streak");
    EXPECT_TRUE(r.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_NE(
        r.scene.features.effects.reasons[size_t(Effect::MotionBlur)].find("ActiveTransform at "),
        std::string::npos);
    const Image &img = r.image;
    // The centre rows: the streak runs from x = -2.5 to 2.5 (5 units, 40 pixels), with a
    // plateau of 2r / 4 = 1/4 and linear ramps r wide... over the ends where the sphere enters
    // and leaves.
    int first = -1, last = -1;
    double worst = 0;
    for (int y = 6; y < 10; ++y)
        for (int x = 0; x < 64; ++x) {
            double d = Dark(img, x, y), want = ExpectedDark(x, y, 0.5, -2, 2);
            worst = std::max(worst, std::abs(d - want));
            if (y == 7 && d > 0.005) {
                if (first < 0) first = x;
                last = x;
            }
        }
    EXPECT_LT(worst, 0.02);
    EXPECT_EQ(first, 12);  // x = -2.5 is pixel 12's left edge
    EXPECT_EQ(last, 51);   // x = 2.5 is pixel 51's right edge: 40 pixels
    // The plateau and the linear fade: darkness along the centre row's ends rises by about
    // the same step per pixel.
    EXPECT_NEAR(ExpectedDark(32, 7, 0.5, -2, 2), 0.247, 0.001);  // 2 x half-chord / 4
    EXPECT_NEAR(Dark(img, 32, 7), ExpectedDark(32, 7, 0.5, -2, 2), 0.015);
    // Entering, the sphere covers each point of the row for a time that grows linearly with
    // the point's distance from the streak's end: 1/4 over the sphere's 8-pixel width.
    for (int x = 13; x < 20; ++x)
        EXPECT_NEAR(Dark(img, x, 7) - Dark(img, x - 1, 7), 0.247 / 8, 0.012) << x;
}

// A UV sphere of radius 0.5 as a triangle mesh (fine enough to cover within 0.1% of the
// sphere's silhouette area).
std::string MeshSphere() {
    const int nu = 96, nv = 48;
    std::string P, idx;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i < nu; ++i) {
            double th = Pi * j / nv, ph = 2 * Pi * i / nu;
            P += std::to_string(0.5 * std::sin(th) * std::cos(ph)) + " " +
                 std::to_string(0.5 * std::sin(th) * std::sin(ph)) + " " +
                 std::to_string(0.5 * std::cos(th)) + " ";
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            int a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu;
            idx += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " +
                   std::to_string(b) + " " + std::to_string(d) + " " + std::to_string(c) + " ";
        }
    return "Shape \"trianglemesh\" \"point P\" [ " + P + "] \"integer indices\" [ " + idx + "]\n";
}

double MeanAbsDiff(const Image &a, const Image &b) {
    double s = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) s += std::abs(a.pixels[i] - b.pixels[i]);
    return s / double(a.pixels.size());
}

double TotalDark(const Image &img) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) s += Dark(img, x, y);
    return s;
}

// The same motions applied to an analytic sphere, to a mesh sphere (Embree time steps) and to
// an instance of the sphere: a translation, and a rotation (many time steps).
TEST(MotionBlur, MeshAnalyticShapeAndInstanceAgree) {
    for (const std::string &motion :
         {std::string("ActiveTransform StartTime\nTranslate -2 0 0\nActiveTransform EndTime\n"
                      "Translate 2 0.3 0\nActiveTransform All\n"),
          std::string("ActiveTransform EndTime\nRotate 150 0 0 1\nActiveTransform All\n"
                      "Translate 2.5 0 0\n")}) {
        std::string sphere = "Shape \"sphere\" \"float radius\" [ 0.5 ]\n";
        Rendered analytic = RenderText(Header("", 64) + motion + sphere, "analytic");
        Rendered mesh = RenderText(Header("", 64) + motion + MeshSphere(), "mesh");
        Rendered inst = RenderText(Header("", 64) + "ObjectBegin \"ball\"\n" + sphere +
                                       "ObjectEnd\n" + motion + "ObjectInstance \"ball\"\n",
                                   "instance");
        double total = TotalDark(analytic.image);
        EXPECT_GT(total, 20);  // (a disk of radius 0.5 is 12.6 pixels: the streak is more)
        EXPECT_NEAR(TotalDark(mesh.image), total, 0.01 * total) << motion;
        EXPECT_NEAR(TotalDark(inst.image), total, 0.01 * total) << motion;
        EXPECT_LT(MeanAbsDiff(mesh.image, analytic.image), 0.005) << motion;
        EXPECT_LT(MeanAbsDiff(inst.image, analytic.image), 0.005) << motion;
    }
}

// A moving camera sees a still sphere move the other way: the same streak, mirrored.
TEST(MotionBlur, MovingCameraMatchesMovingObject) {
    Rendered object = RenderText(Header("", 64) + MovingSphere, "object");
    std::string text = Header("", 64) + "Shape \"sphere\" \"float radius\" [ 0.5 ]\n";
    // The camera moves from x = 2 to x = -2: the sphere goes from -2 to 2 in its view.
    text.replace(0, text.find('\n'),
                 "ActiveTransform StartTime\nLookAt 2 0 -5  2 0 0  0 1 0\n"
                 "ActiveTransform EndTime\nLookAt -2 0 -5  -2 0 0  0 1 0\nActiveTransform All");
    Rendered camera = RenderText(text, "camera");
    EXPECT_TRUE(camera.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_LT(MeanAbsDiff(camera.image, object.image), 0.003);
}

bool SameImage(const Image &a, const Image &b) { return a.pixels == b.pixels; }

// A scene where nothing moves renders bit-identical with any shutter, with ActiveTransform
// directives that change nothing, and with something moving out of sight (which turns the
// time dimension on): the time pattern shifts no other sample dimension.
TEST(MotionBlur, StillSceneIsIdenticalWhateverTheShutter) {
    const std::string scene =
        "Translate 0.3 0.1 0\nShape \"sphere\" \"float radius\" [ 0.7 ]\n"
        "Material \"plastic\" \"rgb Kd\" [ 0.5 0.3 0.2 ]\n"
        "Translate -2 0 0\nShape \"sphere\" \"float radius\" [ 0.6 ]\n";
    auto header = [](const std::string &camera) {
        std::string h = Header(camera, 16);
        return h.substr(0, h.find("LightSource")) +
               "LightSource \"point\" \"point from\" [ 0 3 -4 ] \"rgb I\" [ 20 20 20 ]\n"
               "Material \"matte\" \"rgb Kd\" [ 0.8 0.8 0.8 ]\n";
    };
    Rendered plain = RenderText(header("") + scene, "still");
    EXPECT_FALSE(plain.scene.features.effects.Has(Effect::MotionBlur));
    Rendered shutter =
        RenderText(header("\"float shutteropen\" [ 0.2 ] \"float shutterclose\" [ 0.7 ]") + scene,
                   "still_shutter");
    EXPECT_FALSE(shutter.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_TRUE(SameImage(plain.image, shutter.image));
    Rendered noop =
        RenderText(header("") + "TransformTimes 0 2\nActiveTransform All\n" + scene, "still_noop");
    EXPECT_FALSE(noop.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_TRUE(SameImage(plain.image, noop.image));
    // A sphere moving far behind the camera: motion blur is on, the image the same.
    Rendered hidden = RenderText(header("") + scene +
                                     "AttributeBegin\nActiveTransform EndTime\nTranslate 0 1 0\n"
                                     "ActiveTransform All\nTranslate 0 0 -50\n"
                                     "Shape \"sphere\" \"float radius\" [ 0.5 ]\nAttributeEnd\n",
                                 "still_hidden");
    EXPECT_TRUE(hidden.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_TRUE(SameImage(plain.image, hidden.image));
    // Motion outside the shutter is no motion: the sphere stands where it is at shutteropen.
    Rendered before = RenderText(
        header("\"float shutteropen\" [ 2 ] \"float shutterclose\" [ 3 ]") +
            "AttributeBegin\nActiveTransform StartTime\nTranslate 5 0 0\nActiveTransform All\n" +
            scene + "AttributeEnd\n",
        "still_after");
    EXPECT_FALSE(before.scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_TRUE(SameImage(plain.image, before.image));
}

// scenes/distribution.pbrt (the gallery's showcase) loads without a warning and calls for
// motion blur (its ActiveTransform), depth of field and glossy rays; a small render of it is
// finite everywhere and the moving ball is there.
TEST(MotionBlur, DistributionSceneShowsEveryEffect) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(test::Source + "/scenes/distribution.pbrt", diag);
    BuildSettings opts;
    opts.resolution = {64, 40};
    opts.spp = 4;
    RenderScene scene = BuildRenderScene(desc, opts, diag);
    EXPECT_EQ(diag.Warnings().size(), 0u);
    EXPECT_TRUE(scene.features.effects.Has(Effect::MotionBlur));
    EXPECT_NE(
        scene.features.effects.reasons[size_t(Effect::MotionBlur)].find("ActiveTransform at "),
        std::string::npos);
    EXPECT_TRUE(scene.features.lens);
    RenderStats stats;
    Image img = Render(scene, &stats);
    EXPECT_EQ(stats.nonFiniteSamples, 0u);
    EXPECT_GT(stats.rays.glossy, 0u);
}

std::string ErrorOf(const std::string &text, const std::string &name) {
    return test::ErrorOf<SceneError>([&] { RenderText(text, name); });
}

TEST(MotionBlur, BadMotionInputIsLocated) {
    std::string err = ErrorOf(Header("", 1) + "TransformTimes 1 0.5\n", "times");
    EXPECT_NE(err.find("times.pbrt:10:1: error: TransformTimes end time 0.5 is before the "
                       "start time 1"),
              std::string::npos)
        << err;
    // A reversed shutter is swapped with a warning (pbrt-v3) and renders.
    fs::path dir = fs::path(::testing::TempDir()) / "prism_motion";
    fs::create_directories(dir);
    fs::path file = dir / "shutter.pbrt";
    std::ofstream(file) << Header("\"float shutteropen\" [ 1 ] \"float shutterclose\" [ 0 ]", 1) +
                               MovingSphere;
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(file.string(), diag);
    RenderScene scene = BuildRenderScene(desc, BuildSettings{}, diag);
    ASSERT_EQ(diag.Warnings().size(), 1u);
    EXPECT_NE(diag.Warnings()[0].message.find("swapping"), std::string::npos);
    EXPECT_TRUE(scene.features.effects.Has(Effect::MotionBlur));
    // A singular moving transform cannot be interpolated: an error at the shape.
    err = ErrorOf(Header("", 1) +
                      "ActiveTransform EndTime\nConcatTransform [ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 "
                      "0 ]\nActiveTransform All\nShape \"sphere\"\n",
                  "singular");
    EXPECT_NE(err.find("singular.pbrt"), std::string::npos) << err;
}

}  // namespace
}  // namespace prism
