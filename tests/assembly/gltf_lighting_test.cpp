// glTF and OBJ features through whole scenes (issue 13): texture coordinate set 1 for every
// texture slot, occlusion scaling only the environment's light, emissive textures as textured
// area lights (the irradiance they give a floor against the analytic form factor), BLEND as
// stochastic transparency for camera and shadow rays, and OBJ's dissolve as transparency.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "render/area_light.h"
#include "render/gltf_material.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/gltf_scene.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

class GltfLighting : public test::FreshDirTest {
  protected:
    std::string Write(const std::string &name, const std::string &text) {
        return test::WriteTestFile(dir_ / name, text);
    }
    Built Build(const std::string &path, int spp = 1) {
        BuildSettings opts;
        opts.spp = spp;
        return BuildSceneFile(path, opts);
    }
    Image RenderFile(const std::string &path, int spp = 1) {
        Built b = Build(path, spp);
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        RenderStats stats;
        return Render(b.scene, &stats);
    }
};

// A ray given in world space, in the scene's render space.
Ray WorldRay(const RenderScene &s, const Vec3f &o, const Vec3f &d, float tMax = Infinity) {
    return {s.renderFromWorld.Point(o), s.renderFromWorld.Vector(d), tMax};
}

TEST_F(GltfLighting, TexCoord1SelectsTheSecondUvSetInEverySlot) {
    WriteHalfImage(Path("tex.png"));
    // At x = 0.1: set 0 reads u = 0.1 (white), set 1 reads u = 0.9 (black).
    auto material = [](const std::string &tc) {
        return R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0)" + tc +
               R"(}, "metallicFactor": 0}, "occlusionTexture": {"index": 0)" + tc +
               R"(}, "emissiveTexture": {"index": 0)" + tc +
               R"(}, "emissiveFactor": [1, 1, 1], "normalTexture": {"index": 0)" + tc + "}}";
    };
    const std::string viaTransform =
        R"(, "extensions": {"KHR_texture_transform": {"texCoord": 1}})";
    for (const auto &[tc, white] :
         std::vector<std::pair<std::string, bool>>{{"", true},
                                                   {R"(, "texCoord": 0)", true},
                                                   {R"(, "texCoord": 1)", false},
                                                   {viaTransform, false}}) {
        SCOPED_TRACE(tc);
        Built b = Build(Write("q.gltf", GltfTwoUvQuad(material(tc))));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        const float want = white ? 1.f : 0.f;
        SurfaceInteraction si;
        ASSERT_TRUE(b.scene.accel->Intersect(
            WorldRay(b.scene, Vec3f(0.1f, 0.5f, 1), Vec3f(0, 0, -1)), &si));
        const ShapeInfo &info = b.scene.Info(si);
        const Material &m = b.scene.materials[size_t(info.material)];
        const TextureContext ctx{si.uv, si.p, si.uv1};
        ASSERT_TRUE(m.ModelAs<GltfMaterial>());
        EXPECT_NEAR(m.ModelAs<GltfMaterial>()->Gltf().baseColor->Evaluate(ctx).g, want, 1e-3);
        EXPECT_NEAR(m.AmbientOcclusion(ctx), want, 1e-3);
        ASSERT_TRUE(m.normalMap);
        EXPECT_NEAR(m.normalMap->Evaluate(ctx).g, want, 1e-3);
        ASSERT_GE(info.areaLight, 0);
        const auto &light =
            static_cast<const DiffuseAreaLight &>(*b.scene.lights[size_t(info.areaLight)]);
        EXPECT_NEAR(light.L(si, si.wo).g, want, 1e-3);
    }
}

// Irradiance below the corner of an a x b rectangle at distance c, radiance 1 (pi times the
// form factor of a parallel differential area).
double CornerIrradiance(double a, double b, double c) {
    const double A = a / c, B = b / c, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
    return 0.5 * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}

// A white matte floor at z = 0 under the unit square [0,1]^2 at z = 1 emitting down, seen from
// between them at the point below the square's centre.
std::string EmitterOverFloor(const std::string &light) {
    return R"(LookAt 0.5 0.5 0.25  0.5 0.5 0  0 1 0
Camera "perspective" "float fov" [2]
Film "image" "integer xresolution" [2] "integer yresolution" [2]
PixelFilter "box"
Integrator "whitted"
WorldBegin
Material "matte" "rgb Kd" [1 1 1]
Shape "trianglemesh" "point P" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] "integer indices" [0 1 2 0 2 3]
AttributeBegin
)" + light +
           R"(
Material "matte" "rgb Kd" [0 0 0]
Shape "trianglemesh" "point P" [0 0 1 1 0 1 1 1 1 0 1 1] "integer indices" [0 2 1 0 3 2]
  "float uv" [0 0 1 0 1 1 0 1]
AttributeEnd
WorldEnd
)";
}

TEST_F(GltfLighting, MaskAlphaOnTexCoord1CutsOutBySecondUvSet) {
    // An RGBA image whose alpha is 1 where x < 4, else 0; MASK reads the base colour's alpha.
    Image rgba(8, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            for (int c = 0; c < 3; ++c) rgba.At(x, y, c) = 1;
            rgba.At(x, y, 3) = x < 4 ? 1.f : 0.f;
        }
    WriteImage(Path("tex.png"), rgba);
    for (const auto &[tc, hit] : std::vector<std::pair<std::string, bool>>{
             {R"(, "texCoord": 0)", true}, {R"(, "texCoord": 1)", false}}) {
        SCOPED_TRACE(tc);
        Built b = Build(Write("m.gltf", GltfTwoUvQuad(R"({"pbrMetallicRoughness":
          {"baseColorTexture": {"index": 0)" + tc + R"(}}, "alphaMode": "MASK"})")));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        // At x = 0.1: set 0 reads alpha 1 (kept), set 1 reads u = 0.9, alpha 0 (cut out).
        RawHit h;
        const bool got = b.scene.accel->IntersectRaw(
                             WorldRay(b.scene, Vec3f(0.1f, 0.5f, 1), Vec3f(0, 0, -1)), &h) &&
                         h.shape == 0;
        EXPECT_EQ(got, hit);
        EXPECT_EQ(
            b.scene.accel->Occluded(WorldRay(b.scene, Vec3f(0.1f, 0.5f, 1), Vec3f(0, 0, -1), 2.f)),
            hit);
    }
}

TEST_F(GltfLighting, EmissiveTextureLightsAFloorAsTheFormFactorSays) {
    Image white(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) white.SetRGB(x, y, RGB(1));
    WriteImage(Path("white.exr"), white);
    WriteHalfImage(Path("half.exr"), false);  // left half black
    auto light = [](const char *file) {
        return std::string(R"(Texture "em" "spectrum" "imagemap" "string filename" ")") + file +
               R"("
AreaLightSource "diffuse" "rgb L" [2 2 2] "texture emissionmap" "em" "integer nsamples" [64])";
    };
    // Floor radiance = Kd/pi × E, E = L × 4 corner irradiances.
    const double expected = 2 * 4 * CornerIrradiance(0.5, 0.5, 1) / Pi;
    const double uniform =
        MeanChannel(RenderFile(Write("u.pbrt", EmitterOverFloor(light("white.exr"))), 4), 1);
    const double half =
        MeanChannel(RenderFile(Write("h.pbrt", EmitterOverFloor(light("half.exr"))), 4), 1);
    const double constant = MeanChannel(
        RenderFile(Write("c.pbrt", EmitterOverFloor(R"(AreaLightSource "diffuse" "rgb L" [2 2 2]
  "integer nsamples" [64])")),
                   4),
        1);
    EXPECT_NEAR(constant, expected, 0.01 * expected);
    EXPECT_NEAR(uniform, expected, 0.01 * expected);
    EXPECT_NEAR(half, 0.5 * expected, 0.01 * expected);
}

TEST_F(GltfLighting, GltfEmissiveTextureIsANamedAreaLight) {
    WriteHalfImage(Path("tex.png"));
    Built b = Build(Write("e.gltf", GltfTwoUvQuad(R"({"name": "panel",
      "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0.25]})")));
    for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
    ASSERT_GE(b.scene.shapes[0].areaLight, 0);
    const auto &light =
        static_cast<const DiffuseAreaLight &>(*b.scene.lights[size_t(b.scene.shapes[0].areaLight)]);
    EXPECT_TRUE(light.Textured());
    bool named = false;
    for (const LightShadows &l : b.scene.features.effects.lights)
        named =
            named || (l.light.find("emissive texture of material \"panel\"") != std::string::npos &&
                      l.light.find("2 of 2 triangles") != std::string::npos);
    EXPECT_TRUE(named);
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::SoftShadows));
    // Only an emissive texture: the studio rig still lights the model (key, fill, environment).
    EXPECT_EQ(b.scene.lights.size(), 4u);
}

// A gltf sphere under one light block; occlusion "ao" (0.25) at `strength`.
std::string OcclusionScene(const std::string &lights, float strength) {
    return R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [30]
Film "image" "integer xresolution" [16] "integer yresolution" [16]
Integrator "whitted"
WorldBegin
)" + lights +
           R"(
Texture "ao" "spectrum" "imagemap" "string filename" "ao.exr"
Material "gltf" "rgb basecolor" [0.8 0.8 0.8] "float metallic" [0] "float roughness" [0.6]
  "texture occlusionmap" "ao" "float occlusionstrength" [)" +
           std::to_string(strength) + R"(]
Shape "sphere" "float radius" [1]
WorldEnd
)";
}

TEST_F(GltfLighting, OcclusionScalesOnlyTheEnvironmentsLight) {
    Image ao(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) ao.SetRGB(x, y, RGB(0.25f));
    WriteImage(Path("ao.exr"), ao);
    const std::string distant =
        R"(LightSource "distant" "point from" [1 1 2] "point to" [0 0 0] "rgb L" [2 2 2])";
    const std::string env = R"(LightSource "infinite" "rgb L" [1 1 1] "integer nsamples" [4])";
    auto render = [&](const std::string &lights, float strength) {
        return RenderFile(Write("o.pbrt", OcclusionScene(lights, strength)));
    };
    // A punctual light: the strength changes nothing.
    Image d0 = render(distant, 0), d1 = render(distant, 1);
    ASSERT_EQ(d0.pixels.size(), d1.pixels.size());
    for (size_t i = 0; i < d0.pixels.size(); ++i) ASSERT_EQ(d0.pixels[i], d1.pixels[i]) << i;
    EXPECT_GT(d0.GetRGB(8, 8).g, 0.05f);
    // The environment alone: strength 1 scales the sphere by 0.25, strength 0.5 by 0.625; the
    // background (rays that miss) is the same.
    Image e0 = render(env, 0), e1 = render(env, 1), eh = render(env, 0.5f);
    EXPECT_GT(e0.GetRGB(8, 8).g, 0.05f);
    EXPECT_NEAR(e1.GetRGB(8, 8).g, 0.25f * e0.GetRGB(8, 8).g, 1e-5);
    EXPECT_NEAR(eh.GetRGB(8, 8).g, 0.625f * e0.GetRGB(8, 8).g, 1e-5);
    EXPECT_EQ(e1.GetRGB(0, 0).g, e0.GetRGB(0, 0).g);
    // Both: the punctual part stays, the environment's is scaled.
    // (The environment first: its light samples' pattern depends on its index.)
    Image b0 = render(env + "\n" + distant, 0), b1 = render(env + "\n" + distant, 1);
    const float direct = d0.GetRGB(8, 8).g, envPart = e0.GetRGB(8, 8).g;
    EXPECT_NEAR(b0.GetRGB(8, 8).g, direct + envPart, 1e-4);
    EXPECT_NEAR(b1.GetRGB(8, 8).g, direct + 0.25f * envPart, 1e-4);
}

TEST_F(GltfLighting, BlendPassesThreeQuartersOfCameraAndShadowRays) {
    // A glTF quad of alpha 0.25 (BLEND): rays straight through it on a 64 x 64 grid.
    std::string quad = GltfTwoUvQuad(
        R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.25]}, "alphaMode": "BLEND"})");
    WriteHalfImage(Path("tex.png"));  // referenced by the file, unused by the material
    Built b = Build(Write("b.gltf", quad));
    for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::Alpha));
    const int n = 64;
    int hits = 0, blocked = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Vec3f o((float(i) + 0.5f) / n, (float(j) + 0.5f) / n, 1);
            RawHit h;
            hits += b.scene.accel->IntersectRaw(WorldRay(b.scene, o, Vec3f(0, 0, -1)), &h) &&
                    h.shape == 0;
            // Shadow rays of another direction (their own hash).
            blocked += b.scene.accel->Occluded(
                WorldRay(b.scene, o + Vec3f(0.1f, 0, 0), Vec3f(-0.1f, 0, -1), 2.f));
        }
    // Binomial: n² = 4096 rays, sigma of the fraction = sqrt(0.25 × 0.75 / 4096) = 0.0068.
    EXPECT_NEAR(double(hits) / (n * n), 0.25, 0.03);
    EXPECT_NEAR(double(blocked) / (n * n), 0.25, 0.03);
}

TEST_F(GltfLighting, BlendShadowDarkensByAlphaOnAverage) {
    // A floor lit by a distant light from (1, 0, 1); a BLEND quad of alpha 0.25 at z = 1 over
    // x in [1, 2] (outside the view) casts its shadow on the whole visible floor.
    auto scene = [](const std::string &blocker) {
        return R"(LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.5 0.5]
Film "image" "integer xresolution" [64] "integer yresolution" [64]
PixelFilter "box"
Integrator "whitted"
WorldBegin
LightSource "distant" "point from" [1 0 1] "point to" [0 0 0] "rgb L" [1 1 1]
Material "matte" "rgb Kd" [1 1 1]
Shape "trianglemesh" "point P" [-1 -1 0 2 -1 0 2 2 0 -1 2 0] "integer indices" [0 1 2 0 2 3]
)" + blocker + R"(
WorldEnd
)";
    };
    const std::string blocker =
        R"(Shape "trianglemesh" "point P" [1 -1 1 2 -1 1 2 2 1 1 2 1] "integer indices" [0 1 2 0 2 3]
  "string alphamode" "blend" "float alpha" [0.25])";
    const Image lit = RenderFile(Write("l.pbrt", scene(""))),
                shadowed = RenderFile(Write("s.pbrt", scene(blocker)));
    const double ratio = MeanChannel(shadowed, 1) / MeanChannel(lit, 1);
    EXPECT_NEAR(ratio, 0.75, 0.03);
    EXPECT_LT(ratio, 0.99);  // it does cast a shadow
}

TEST_F(GltfLighting, ObjDissolveIsTransparencyNotGlass) {
    auto obj = [&](const char *material, const std::string &mtl) {
        Write("q.mtl", "newmtl " + std::string(material) + "\n" + mtl);
        return Write("q.obj", std::string("mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                          "usemtl ") +
                                  material + "\nf 1 2 3\nf 1 3 4\n");
    };
    {
        Built b = Build(obj("faded", "Kd 0.5 0.5 0.5\nd 0.5\nillum 2\n"));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        EXPECT_FALSE(b.scene.features.effects.Has(Effect::Refraction));
        EXPECT_TRUE(b.scene.features.effects.Has(Effect::Alpha));
        EXPECT_FALSE(b.scene.features.transmission);
        int hits = 0, blocked = 0;
        const int n = 64;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                Vec3f o((float(i) + 0.5f) / n, (float(j) + 0.5f) / n, 1);
                RawHit h;
                hits += b.scene.accel->IntersectRaw(WorldRay(b.scene, o, Vec3f(0, 0, -1)), &h) &&
                        h.shape == 0;
                blocked += b.scene.accel->Occluded(
                    WorldRay(b.scene, o + Vec3f(0, 0.1f, 0), Vec3f(0, -0.1f, -1), 2.f));
            }
        EXPECT_NEAR(double(hits) / (n * n), 0.5, 0.035);
        EXPECT_NEAR(double(blocked) / (n * n), 0.5, 0.035);
    }
    {
        // A coloured Tf beside d: still transparency, with a warning that says so.
        Built b = Build(obj("tinted", "Kd 0.5 0.5 0.5\nd 0.5\nTf 0.2 0.8 0.2\nillum 2\n"));
        bool warned = false;
        for (const Warning &w : b.warnings)
            warned = warned || w.message.find("is read as transparency") != std::string::npos;
        EXPECT_TRUE(warned);
        EXPECT_FALSE(b.scene.features.effects.Has(Effect::Refraction));
    }
    {
        // illum 7 asks for refraction: glass, no transparency.
        Built b = Build(obj("glass", "Kd 0 0 0\nd 0.5\nNi 1.5\nillum 7\n"));
        EXPECT_TRUE(b.scene.features.effects.Has(Effect::Refraction));
        EXPECT_FALSE(b.scene.features.effects.Has(Effect::Alpha));
    }
}

}  // namespace
}  // namespace prism
