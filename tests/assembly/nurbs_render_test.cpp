// Shape "nurbs" and "heightfield" through whole scenes: a patch that used to be skipped (a black
// image) renders lit; its uv is the parametric (u, v) (a checkerboard over a patch whose u runs
// to 2 repeats twice as often); a rational quarter cylinder's silhouette is the circle's; a
// nurbs area light emits; instances of a patch appear; a moving patch blurs where the static
// one does not; a heightfield's triangles are split and shaded as pbrt-v3 shades them; a
// pbrt-v4 bilinearmesh renders lit, emits from the side pbrt-v4's orientation rule gives, and
// a bad one is an error at its parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

class NurbsRender : public test::FreshDirTest {
  protected:
    struct Result {
        Image image;
        std::vector<Warning> warnings;
    };
    Result RenderText(const std::string &name, const std::string &text, int spp = 4) {
        std::string path = test::WriteTestFile(dir_ / (name + ".pbrt"), text);
        BuildSettings opts;
        opts.spp = spp;
        Diagnostics diag(false);
        SceneDescription desc = LoadScene(path, diag);
        RenderScene scene = BuildRenderScene(desc, opts, diag);
        Result r{Render(scene, nullptr), diag.Warnings()};
        return r;
    }
};

// An orthographic 40 x 40 view straight down at [0, 1]^2 (pbrt's LookAt puts +x at the left of
// the image), lit by a distant light from above: a white matte point facing +z is 1/pi * pi = 1
// times its Kd.
std::string TopView(const std::string &world, int res = 40) {
    return "LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0\n"
           "Camera \"orthographic\" \"float screenwindow\" [-0.5 0.5 -0.5 0.5]\n"
           "Film \"image\" \"integer xresolution\" [" +
           std::to_string(res) + "] \"integer yresolution\" [" + std::to_string(res) +
           "]\n"
           "PixelFilter \"box\"\nIntegrator \"directlighting\"\nWorldBegin\n"
           "LightSource \"distant\" \"point from\" [0 0 5] \"point to\" [0 0 0] "
           "\"rgb L\" [3.14159265 3.14159265 3.14159265]\n" +
           world + "WorldEnd\n";
}

const char *UnitPatch =
    "Shape \"nurbs\" \"integer nu\" [2] \"integer nv\" [2] \"integer uorder\" [2] "
    "\"integer vorder\" [2] \"float uknots\" [0 0 2 2] \"float vknots\" [0 0 1 1] "
    "\"point P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";

TEST_F(NurbsRender, PatchThatWasSkippedRendersLitWithParametricUV) {
    Result r = RenderText(
        "lit", TopView("Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n" + std::string(UnitPatch)));
    for (const Warning &w : r.warnings)
        EXPECT_EQ(w.message.find("not supported"), std::string::npos) << w.message;
    EXPECT_NEAR(MeanChannel(r.image, 0), 0.5,
                0.01);  // every pixel: the patch, Kd 0.5, facing the light
    // The checkerboard of scale 2 over uv: u in [0, 2] gives 4 checks across, v in [0, 1] 2.
    Result c = RenderText(
        "checks", TopView("Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" [2] "
                          "\"float vscale\" [2] \"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\n"
                          "Material \"matte\" \"texture Kd\" \"c\"\n" +
                          std::string(UnitPatch)));
    auto changes = [&](bool alongX) {
        int n = 0;
        for (int i = 1; i < 40; ++i) {
            float a = alongX ? c.image.At(i - 1, 5, 0) : c.image.At(5, i - 1, 0);
            float b = alongX ? c.image.At(i, 5, 0) : c.image.At(5, i, 0);
            n += (a > 0.5f) != (b > 0.5f);
        }
        return n;
    };
    EXPECT_EQ(changes(true), 3);
    EXPECT_EQ(changes(false), 1);
}

TEST_F(NurbsRender, RationalQuarterAnnulusHasTheCirclesArea) {
    // The annulus 0.5 <= r <= 1 in the first quadrant as a rational quadratic in u (Pw is
    // homogeneous: (w x, w y, w z, w)), linear in v; it covers pi (1 - 1/4) / 4 of the view.
    const char *annulus =
        "Material \"matte\" \"rgb Kd\" [1 1 1]\n"
        "Shape \"nurbs\" \"integer nu\" [3] \"integer nv\" [2] \"integer uorder\" [3] "
        "\"integer vorder\" [2] \"float uknots\" [0 0 0 1 1 1] \"float vknots\" [0 0 1 1] "
        "\"float Pw\" [0.5 0 0 1  0.35355339 0.35355339 0 0.70710678  0 0.5 0 1 "
        "1 0 0 1  0.70710678 0.70710678 0 0.70710678  0 1 0 1]\n";
    Result r = RenderText("annulus", TopView(annulus, 200), 16);
    EXPECT_NEAR(MeanChannel(r.image, 0), Pi * 0.75 / 4, 0.002);
}

TEST_F(NurbsRender, AreaLightAndInstances) {
    // A nurbs area light emits on the side of dP/du x dP/dv, as pbrt-v3's does: +z for the
    // patch below, seen by the camera above; flipping v or ReverseOrientation turns it away.
    auto emitter = [](const std::string &pre, const std::string &P) {
        return "LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0\n"
               "Camera \"orthographic\" \"float screenwindow\" [-0.5 0.5 -0.5 0.5]\n"
               "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n"
               "Integrator \"directlighting\"\nWorldBegin\n" +
               pre + "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" +
               "Shape \"nurbs\" \"integer nu\" [2] \"integer nv\" [2] \"integer uorder\" [2] "
               "\"integer vorder\" [2] \"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] "
               "\"point P\" [" +
               P + "]\nWorldEnd\n";
    };
    const std::string up = "-1 -1 0  2 -1 0  -1 2 0  2 2 0",
                      down = "-1 2 0  2 2 0  -1 -1 0  2 -1 0";
    EXPECT_NEAR(MeanChannel(RenderText("light_up", emitter("", up)).image, 0), 1.0, 1e-4);
    EXPECT_LT(MeanChannel(RenderText("light_down", emitter("", down)).image, 0), 1e-6);
    EXPECT_LT(MeanChannel(RenderText("light_rev", emitter("ReverseOrientation\n", up)).image, 0),
              1e-6);
    // The same rule for any mesh with shading normals (pbrt-v3's; Prism used to ignore
    // ReverseOrientation there): reversed, it emits away; mirrored, it keeps its side.
    std::string tri =
        "Shape \"trianglemesh\" \"point P\" [-1 -1 0 2 -1 0 2 2 0 -1 2 0] \"integer indices\" "
        "[0 1 2 0 2 3] \"normal N\" [0 0 1 0 0 1 0 0 1 0 0 1]\n";
    auto meshLight = [&](const std::string &pre) {
        std::string text = emitter(pre, up);
        size_t at = text.find("Shape");
        return text.substr(0, at) + tri + "WorldEnd\n";
    };
    EXPECT_NEAR(MeanChannel(RenderText("mesh_up", meshLight("")).image, 0), 1.0, 1e-4);
    EXPECT_LT(MeanChannel(RenderText("mesh_rev", meshLight("ReverseOrientation\n")).image, 0),
              1e-6);
    EXPECT_NEAR(MeanChannel(RenderText("mesh_mirror", meshLight("Scale -1 1 1\n")).image, 0), 1.0,
                0.1);
    EXPECT_LT(
        MeanChannel(
            RenderText("mesh_mirror_rev", meshLight("Scale -1 1 1\nReverseOrientation\n")).image,
            0),
        1e-6);

    std::string inst = TopView(
        "ObjectBegin \"half\"\nMaterial \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"
        "Shape \"nurbs\" \"integer nu\" [2] \"integer nv\" [2] \"integer uorder\" [2] "
        "\"integer vorder\" [2] \"float uknots\" [0 0 1 1] \"float vknots\" [0 0 1 1] "
        "\"point P\" [0 0 0  0.5 0 0  0 1 0  0.5 1 0]\nObjectEnd\n"
        "ObjectInstance \"half\"\n"
        "AttributeBegin\nTranslate 0.5 0 0\nObjectInstance \"half\"\nAttributeEnd\n");
    Result two = RenderText("instances", inst);
    EXPECT_NEAR(MeanChannel(two.image, 0), 0.5, 0.01);
}

TEST_F(NurbsRender, MovingPatchBlurs) {
    // A biquadratic dome patch over [0.25, 0.75]^2, static and moving 0.4 along x.
    std::string dome =
        "Material \"matte\" \"rgb Kd\" [1 1 1]\n"
        "Shape \"nurbs\" \"integer nu\" [3] \"integer nv\" [3] \"integer uorder\" [3] "
        "\"integer vorder\" [3] \"float uknots\" [0 0 0 1 1 1] \"float vknots\" [0 0 0 1 1 1] "
        "\"point P\" [0.25 0.25 0  0.5 0.25 0  0.75 0.25 0  0.25 0.5 0  0.5 0.5 0.3 "
        "0.75 0.5 0  0.25 0.75 0  0.5 0.75 0  0.75 0.75 0]\n";
    // Jittered film positions: a Halton point (the default) can sit exactly on the patch's
    // edge, which lies on a pixel boundary, and light the pixel beyond it.
    const std::string jitter = "Sampler \"stratified\"\n";
    Result still = RenderText("still", jitter + TopView(dome), 16);
    Result moving = RenderText("moving",
                               jitter + TopView("AttributeBegin\nActiveTransform StartTime\n"
                                                "Translate -0.2 0 0\nActiveTransform EndTime\n"
                                                "Translate 0.2 0 0\nActiveTransform All\n" +
                                                dome + "AttributeEnd\n"),
                               64);
    // The same covered area on average (only moved), but spread over more pixels, each
    // partly covered.
    EXPECT_NEAR(MeanChannel(moving.image, 0), MeanChannel(still.image, 0), 0.02);
    auto lit = [](const Image &img) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) n += img.At(x, y, 0) > 0.01f;
        return n;
    };
    auto partial = [](const Image &img) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                n += img.At(x, y, 0) > 0.05f && img.At(x, y, 0) < 0.5f;
        return n;
    };
    EXPECT_EQ(lit(still.image), 20 * 20);
    EXPECT_GE(lit(moving.image), 36 * 20 - 40);
    EXPECT_GT(partial(moving.image), 200);
    EXPECT_LT(partial(still.image), 5);
}

TEST_F(NurbsRender, HeightfieldSplitAndFlatShading) {
    // 2 x 2 heights with corner (1, 1) raised: the triangles (0,0),(1,0),(1,1) (the plane
    // z = y) and (0,0),(1,1),(0,1) (z = x), each flat. Light from (1, 0.3, 1): the first is
    // lit with cos = 0.7 / (sqrt 2 |(1, 0.3, 1)|), the second (normal (-1, 0, 1)) not at all.
    std::string hf =
        "LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0\n"
        "Camera \"orthographic\" \"float screenwindow\" [-0.5 0.5 -0.5 0.5]\n"
        "Film \"image\" \"integer xresolution\" [40] \"integer yresolution\" [40]\n"
        "PixelFilter \"box\"\nIntegrator \"directlighting\"\nWorldBegin\n"
        "LightSource \"distant\" \"point from\" [1 0.3 1] \"point to\" [0 0 0] "
        "\"rgb L\" [3.14159265 3.14159265 3.14159265]\n"
        "Material \"matte\" \"rgb Kd\" [1 1 1]\n"
        "Shape \"heightfield\" \"integer nu\" [2] \"integer nv\" [2] \"float Pz\" [0 0 0 1]\n"
        "WorldEnd\n";
    Result r = RenderText("hf", hf);
    double lit = 0.7 / (std::sqrt(2.0) * std::sqrt(2.09));
    // Pixel (x, y) sees world (1 - (x + 0.5) / 40, 1 - (y + 0.5) / 40): below the diagonal
    // y < x of the world is the lit triangle.
    EXPECT_NEAR(r.image.At(30, 5, 0), 0.0, 1e-4);   // world (0.24, 0.86): z = x side
    EXPECT_NEAR(r.image.At(5, 30, 0), lit, 1e-3);   // world (0.86, 0.24): z = y side
    EXPECT_NEAR(r.image.At(12, 28, 0), lit, 1e-3);  // flat: the same value all over
}

TEST_F(NurbsRender, BilinearMeshRendersAndEmitsFromItsFront) {
    // The unit square as one patch: dp/du = +x, dp/dv = +y, so it faces +z, the light and the
    // camera.
    const std::string patch = "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";
    Result r = RenderText("blp", TopView("Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n" + patch));
    for (const Warning &w : r.warnings) ADD_FAILURE() << w.ToString();
    EXPECT_NEAR(MeanChannel(r.image, 0), 0.5, 0.01);
    // A one-sided emitter (black, so the distant light adds nothing): L toward the camera;
    // reversed, it faces away and the camera sees nothing.
    const std::string light =
        "Material \"matte\" \"rgb Kd\" [0 0 0]\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n";
    Result front = RenderText("blp_front", TopView(light + patch));
    EXPECT_NEAR(MeanChannel(front.image, 0), 2.0, 0.01);
    Result back = RenderText("blp_back", TopView("ReverseOrientation\n" + light + patch));
    EXPECT_NEAR(MeanChannel(back.image, 0), 0.0, 1e-6);
    // A saddle is tessellated finely and shaded smoothly: no two neighbouring pixels of its
    // centre row differ by a facet's step.
    Result saddle = RenderText(
        "saddle", TopView("Material \"matte\" \"rgb Kd\" [1 1 1]\nShape \"bilinearmesh\" "
                          "\"point3 P\" [0 0 -0.3  1 0 0.3  0 1 0.3  1 1 -0.3]\n"));
    for (int x = 1; x < 40; ++x)
        EXPECT_LT(std::abs(saddle.image.At(x, 20, 0) - saddle.image.At(x - 1, 20, 0)), 0.03f) << x;
}

TEST_F(NurbsRender, BadBilinearMeshIsAnErrorAtItsParameter) {
    const std::string text = TopView(
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n"
        "  \"integer indices\" [0 1 2 4]\n");
    const std::string what = test::ErrorOf<SceneError>([&] { RenderText("blp_bad", text); });
    EXPECT_NE(what.find("blp_bad.pbrt:9:3: "), std::string::npos) << what;
    EXPECT_NE(what.find("vertex index 4 out of range"), std::string::npos) << what;
}

}  // namespace
}  // namespace prism
