// The volumetric path tracer (Integrator "volpath", render/volpath_integrator.h): a furnace of
// scattering media that absorb nothing keeps the environment's radiance, "volpath" without
// media is "path" exactly, and single scattering at maxdepth 1 agrees with the Whitted kernel's
// ray march.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/gltf_scene.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

Rendered RenderText(const std::string &name, const std::string &text, int res, int spp,
                    const std::string &integrator = "") {
    return RenderSceneText("volpath", name, text, SizedSettings(res, res, spp, integrator));
}

// A sphere of scattering medium (albedo 1, forward-scattering) behind an invisible boundary,
// seen from outside and from inside, under a uniform environment of radiance 1: every path
// ends in the environment with its weight intact, so every pixel converges to 1.
TEST(VolPath, FurnaceOfAlbedoOneKeepsTheEnvironment) {
    for (const char *camera : {"LookAt 0 0 -4  0 0 0  0 1 0", "LookAt 0 0 0.2  0 0 1  0 1 0"}) {
        SCOPED_TRACE(camera);
        std::ostringstream s;
        s << "MakeNamedMedium \"cloud\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0 0 0 ] "
             "\"rgb sigma_s\" [ 2 2 2 ] \"float g\" 0.5\n"
          << (std::string(camera).find("-4") == std::string::npos
                  ? "MediumInterface \"\" \"cloud\"\n"
                  : "")
          << camera << "\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
          << "Integrator \"volpath\" \"integer maxdepth\" [ 1000 ]\nWorldBegin\n"
          << "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
          << "AttributeBegin\nMaterial \"none\"\nMediumInterface \"cloud\" \"\"\n"
          << "Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
        Rendered r = RenderText("furnace.pbrt", s.str(), 8, 256);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(MeanChannel(r.image, c), 1.0, 0.02);
        for (float v : r.image.pixels) EXPECT_NEAR(v, 1.f, 0.2f);
        EXPECT_GT(r.stats.rays.reflection, 0u);  // paths scattered in the medium
    }
}

// The same furnace with a heterogeneous medium (delta tracking through a varying density grid
// filling an invisible box).
TEST(VolPath, FurnaceOfHeterogeneousMedium) {
    const std::string scene =
        "MakeNamedMedium \"smoke\" \"string type\" \"heterogeneous\" \"rgb sigma_a\" [ 0 0 0 ] "
        "\"rgb sigma_s\" [ 3 3 3 ] \"float g\" -0.3 \"integer nx\" 2 \"integer ny\" 2 "
        "\"integer nz\" 2 \"float density\" [ 0.1 1 0.5 2 0 1.5 0.7 0.2 ] \"point3 p0\" "
        "[ -1 -1 -1 ] \"point3 p1\" [ 1 1 1 ]\nLookAt 0.3 0.5 -4  0 0 0  0 1 0\n"
        "Camera \"perspective\" \"float fov\" [ 35 ]\n"
        "Integrator \"volpath\" \"integer maxdepth\" [ 1000 ]\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nMaterial \"none\"\n"
        "MediumInterface \"smoke\" \"\"\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 "
        "3 7 6 3 6 2 0 4 7 0 7 3 1 2 6 1 6 5 ]\n  \"point3 P\" [ -1 -1 -1  1 -1 -1  1 1 -1  -1 1 "
        "-1 "
        " -1 -1 1  1 -1 1  1 1 1  -1 1 1 ]\n";
    Rendered r = RenderText("smoke.pbrt", scene, 8, 256);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(MeanChannel(r.image, c), 1.0, 0.02);
    EXPECT_GT(r.stats.rays.reflection, 0u);
}

// Absorption halves nothing it should not: with albedo 1/2 the furnace is darker than 1.
TEST(VolPath, FurnaceWithAbsorptionIsDarker) {
    const std::string scene =
        "MakeNamedMedium \"cloud\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 1 1 1 ] "
        "\"rgb sigma_s\" [ 1 1 1 ]\nLookAt 0 0 -4  0 0 0  0 1 0\n"
        "Camera \"perspective\" \"float fov\" [ 10 ]\n"
        "Integrator \"volpath\" \"integer maxdepth\" [ 1000 ]\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nMaterial \"none\"\n"
        "MediumInterface \"cloud\" \"\"\nShape \"sphere\" \"float radius\" [ 1 ]\n";
    Rendered r = RenderText("absorbing.pbrt", scene, 4, 256);
    const double m = MeanChannel(r.image, 1);
    EXPECT_LT(m, 0.8);
    EXPECT_GT(m, std::exp(-4.0));  // more than the unscattered light alone
}

std::string Room(const std::string &integrator) {
    return integrator + "\n" + std::string(kLitFloorFromLookAt) +
           "Material \"glass\"\nAttributeBegin\nTranslate 0.8 0.4 0\n"
           "Shape \"sphere\" \"float radius\" [0.4]\nAttributeEnd\n"
           "Material \"plastic\" \"rgb Kd\" [0.3 0.6 0.3] \"float roughness\" [0.1]\n"
           "AttributeBegin\nTranslate -0.6 0.6 0\nShape \"sphere\" \"float radius\" [0.6]\n"
           "AttributeEnd\n";
}

// Without media, volpath traces the same paths with the same samples as path: the same image
// bits and the same rays.
TEST(VolPath, WithoutMediaIsPath) {
    Rendered path = RenderText("path.pbrt", Room("Integrator \"path\""), 24, 16);
    Rendered vol = RenderText("vol.pbrt", Room("Integrator \"volpath\""), 24, 16);
    ASSERT_EQ(path.image.pixels.size(), vol.image.pixels.size());
    EXPECT_EQ(path.image.pixels, vol.image.pixels);
    EXPECT_EQ(path.stats.rays.shadow, vol.stats.rays.shadow);
    EXPECT_EQ(path.stats.rays.reflection, vol.stats.rays.reflection);
    EXPECT_EQ(path.stats.rays.refraction, vol.stats.rays.refraction);
}

// The same on what the untextured room cannot show: a glTF quad whose base colour and normal
// map read the second uv set (TEXCOORD_1) and whose metallic-roughness texture is EWA-filtered
// over the camera rays' footprints, under every sampler the path integrators draw: volpath
// shades a surface vertex with path's own code.
TEST(VolPath, WithoutMediaIsPathOnATexturedGltfUnderEverySampler) {
    const auto dir = ScratchDir("volpath-gltf");
    Image tex(16, 16, 3);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            tex.SetRGB(x, y, RGB(float(x) / 15, float((x + y) % 5) / 4, (x ^ y) & 1 ? 0.9f : 0.1f));
    WriteImage((dir / "tex.png").string(), tex);
    const std::string gltf = WriteTestFile(
        dir / "q.gltf",
        test::GltfTwoUvQuad(R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
          "texCoord": 1}, "metallicRoughnessTexture": {"index": 0}, "metallicFactor": 0.5},
          "normalTexture": {"index": 0, "texCoord": 1}})"));
    for (const char *sampler : {"stratified", "random", "02sequence", "lowdiscrepancy", "halton",
                                "sobol", "zsobol", "paddedsobol"}) {
        SCOPED_TRACE(sampler);
        auto render = [&](const std::string &integrator) {
            Diagnostics diag(false);
            SceneDescription desc = LoadScene(gltf, diag);
            desc.sampler.type = sampler;
            BuildSettings s;
            s.resolution = Vec2i(24, 24);
            s.spp = 4;
            s.integrator = integrator;
            RenderScene scene = BuildRenderScene(desc, s, diag);
            EXPECT_TRUE(scene.differentials);  // the texture filters over the footprint
            Rendered r;
            r.image = Render(scene, &r.stats);
            return r;
        };
        const Rendered path = render("path"), vol = render("volpath");
        ASSERT_EQ(path.image.pixels.size(), vol.image.pixels.size());
        EXPECT_EQ(path.image.pixels, vol.image.pixels);
        EXPECT_EQ(path.stats.rays.shadow, vol.stats.rays.shadow);
        EXPECT_EQ(path.stats.rays.reflection, vol.stats.rays.reflection);
    }
}

// At maxdepth 1 volpath's medium paths are single scattering from the lights: against the
// Whitted kernel's ray march of the same homogeneous fog lit by a point light, in the mean.
TEST(VolPath, SingleScatteringAgreesWithTheRayMarch) {
    auto scene = [](const std::string &integrator) {
        return "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.05 "
               "0.05 0.05 ] \"rgb sigma_s\" [ 0.2 0.2 0.2 ] \"float g\" 0.3\n"
               "MediumInterface \"\" \"fog\"\nLookAt 0 1 -4  0 0.5 0  0 1 0\n"
               "Camera \"perspective\" \"float fov\" [ 50 ]\n"
               // One fixed stream: the mean's noise is the point light's 1/r^2 tail, a few
               // percent between seeds at any spp.
               "Sampler \"stratified\"\n" +
               integrator +
               "\nWorldBegin\nLightSource \"point\" \"point from\" [ 0.5 2 0 ] \"rgb I\" "
               "[ 5 5 5 ]\nMaterial \"matte\" \"rgb Kd\" [ 0.5 0.5 0.5 ]\n"
               "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
               "  \"point P\" [-3 0 -3  3 0 -3  3 0 3  -3 0 3]\n"
               "AttributeBegin\nMaterial \"none\"\nMediumInterface \"fog\" \"\"\n"
               "Shape \"sphere\" \"float radius\" [ 6 ]\nAttributeEnd\n";
    };
    Rendered march =
        RenderText("march.pbrt", scene("Integrator \"whitted\" \"integer maxdepth\" [ 1 ]"), 8, 16);
    Rendered vol = RenderText("vol1.pbrt",
                              scene("Integrator \"volpath\" \"integer maxdepth\" [ 1 ]"), 8, 1024);
    EXPECT_NEAR(MeanChannel(vol.image, 1), MeanChannel(march.image, 1),
                0.03 * MeanChannel(march.image, 1));
}

}  // namespace
}  // namespace prism
