// Texture values at known points: Perlin noise (against an independent evaluation of the
// published algorithm), fbm/wrinkled/windy/marble, bilerp, uv, dots, directionmix, and the
// 3-D mapping.
#include "render/texture.h"

#include <gtest/gtest.h>

#include <cmath>

#include "assembly/build_scene.h"
#include "render/materials.h"
#include "render/noise.h"
#include "scene/pbrt_parser.h"
#include "support/errors.h"

namespace prism {
namespace {

using test::ErrorOf;

TexturePtr Const(float v) { return std::make_shared<ConstantTexture>(RGB(v)); }

TextureContext AtUV(float u, float v) { return {{u, v}, {0, 0, 0}}; }
TextureContext AtP(Vec3f p) { return {{0, 0}, p}; }

TEST(Noise, MatchesReferenceValuesAndVanishesOnTheLattice) {
    // Values from a separate (Python) evaluation of Perlin's improved noise with his table.
    EXPECT_NEAR(PerlinNoise(0.5f, 0.25f, 0.75f), -0.37507868f, 1e-5f);
    EXPECT_NEAR(PerlinNoise(1.3f, -2.7f, 4.1f), 0.16882148f, 1e-5f);
    EXPECT_NEAR(PerlinNoise(-0.6f, 10.2f, 3.3f), -0.05911824f, 1e-5f);
    EXPECT_NEAR(PerlinNoise(100.5f, 0.5f, 0.5f), 0.125f, 1e-5f);
    for (int i = -3; i < 3; ++i) EXPECT_EQ(PerlinNoise(float(i), float(2 * i), 7.f), 0.f);
    // Periodic with period 256, bounded, and finite for hostile inputs.
    EXPECT_NEAR(PerlinNoise(1.3f + 256, -2.7f, 4.1f), PerlinNoise(1.3f, -2.7f, 4.1f), 1e-4f);
    EXPECT_EQ(PerlinNoise(NAN, 0, 0), 0.f);
    EXPECT_TRUE(std::isfinite(PerlinNoise(3e38f, -3e38f, 1e20f)));
    for (int i = 0; i < 1000; ++i) {
        float n = PerlinNoise(i * 0.137f, i * 0.071f, i * 0.293f);
        EXPECT_LE(std::abs(n), 1.1f);
    }
}

TEST(Noise, OctaveSums) {
    Vec3f p(0.3f, 1.7f, -2.2f);
    EXPECT_EQ(FBm(p, 0.5f, 1), PerlinNoise(p));
    float want =
        PerlinNoise(p) + 0.5f * PerlinNoise(p * 1.99f) + 0.25f * PerlinNoise(p * (1.99f * 1.99f));
    EXPECT_NEAR(FBm(p, 0.5f, 3), want, 1e-6f);
    float turb = std::abs(PerlinNoise(p)) + 0.5f * std::abs(PerlinNoise(p * 1.99f)) + 0.25f * 0.2f;
    EXPECT_NEAR(Turbulence(p, 0.5f, 2), turb, 1e-6f);
}

TEST(Texture, NoiseTexturesEvaluateTheirDefinitions) {
    Vec3f p(0.3f, 1.7f, -2.2f);
    TextureMapping3D id{Transform()};
    EXPECT_EQ(NoiseTexture(NoiseTexture::Kind::FBm, id, 8, 0.5f).Evaluate(AtP(p)),
              RGB(FBm(p, 0.5f, 8)));
    EXPECT_EQ(NoiseTexture(NoiseTexture::Kind::Wrinkled, id, 8, 0.5f).Evaluate(AtP(p)),
              RGB(Turbulence(p, 0.5f, 8)));
    float windy = std::abs(FBm(p * 0.1f, 0.5f, 3)) * FBm(p, 0.5f, 6);
    EXPECT_NEAR(NoiseTexture(NoiseTexture::Kind::Windy, id, 0, 0).Evaluate(AtP(p)).r, windy, 1e-7f);
    // Marble: a spline of greys and a dark vein, scaled by 1.5.
    MarbleTexture marble(id, 8, 0.5f, 1.f, 0.2f);
    float lo = 1e9f, hi = -1e9f;
    for (int i = 0; i < 2000; ++i) {
        RGB c = marble.Evaluate(AtP({0.1f * i, 0.013f * i, 0.3f}));
        lo = std::min(lo, c.r);
        hi = std::max(hi, c.r);
        EXPECT_GE(c.b, 0.2f * 1.5f - 1e-4f);
        EXPECT_LE(c.b, 0.6f * 1.5f + 1e-4f);
    }
    EXPECT_LT(lo, 0.6f);  // veins
    EXPECT_GT(hi, 0.8f);
}

TEST(Texture, BilerpUVAndDots) {
    TextureMapping uv;
    BilerpTexture bl(uv, RGB(1), RGB(2), RGB(3), RGB(5));
    EXPECT_EQ(bl.Evaluate(AtUV(0, 0)), RGB(1));
    EXPECT_EQ(bl.Evaluate(AtUV(0, 1)), RGB(2));
    EXPECT_EQ(bl.Evaluate(AtUV(1, 0)), RGB(3));
    EXPECT_EQ(bl.Evaluate(AtUV(1, 1)), RGB(5));
    EXPECT_NEAR(bl.Evaluate(AtUV(0.5f, 0.5f)).r, 2.75f, 1e-6f);

    UVTexture uvt(uv);
    RGB c = uvt.Evaluate(AtUV(1.25f, -0.25f));
    EXPECT_NEAR(c.r, 0.25f, 1e-6f);
    EXPECT_NEAR(c.g, 0.75f, 1e-6f);
    EXPECT_EQ(c.b, 0.f);

    DotsTexture dots(uv, Const(1), Const(0));
    int withDot = 0;
    for (int s = -5; s < 5; ++s)
        for (int t = -5; t < 5; ++t) {
            bool has = PerlinNoise(s + .5f, t + .5f, .5f) > 0;
            withDot += has;
            // The dot (radius 0.35, jittered by at most 0.15) always covers its cell centre
            // and never reaches the cell corners.
            EXPECT_EQ(dots.Evaluate(AtUV(float(s), float(t))).r, has ? 1.f : 0.f);
            EXPECT_EQ(dots.Evaluate(AtUV(s + 0.49f, t + 0.49f)).r, 0.f);
        }
    EXPECT_GT(withDot, 10);
    EXPECT_LT(withDot, 90);
}

TEST(Texture, DirectionMixWeighsTex1ByTheNormalAlongDir) {
    const DirectionMixTexture t(std::make_shared<ConstantTexture>(RGB(1, 0, 0)),
                                std::make_shared<ConstantTexture>(RGB(0, 0, 1)), Vec3f(0, 0, 1));
    TextureContext c = AtUV(0, 0);
    c.n = Vec3f(0, 0, -1);  // either side of the surface
    EXPECT_EQ(t.Evaluate(c), RGB(1, 0, 0));
    c.n = Vec3f(1, 0, 0);
    EXPECT_EQ(t.Evaluate(c), RGB(0, 0, 1));
    c.n = Vec3f(std::sqrt(0.75f), 0, 0.5f);  // 60 degrees from dir
    const RGB v = t.Evaluate(c);
    EXPECT_NEAR(v.r, 0.5f, 1e-6f);
    EXPECT_NEAR(v.b, 0.5f, 1e-6f);
}

SceneDescription Parse(const std::string &world, Diagnostics &diag) {
    return ParsePbrtString("WorldBegin\nLightSource \"point\"\n" + world, "tex.pbrt", diag);
}

// `d` built at 4x4 pixels (the textures are what the tests read).
RenderScene BuildTiny(const SceneDescription &d, Diagnostics &diag) {
    BuildSettings o;
    o.resolution = {4, 4};
    return BuildRenderScene(d, o, diag);
}

TEST(TextureScene, ThreeDTexturesUseTheInverseCTM) {
    Diagnostics diag;
    SceneDescription d = Parse(
        "AttributeBegin\nScale 2 2 2\n"
        "Texture \"n\" \"spectrum\" \"fbm\" \"integer octaves\" 4\n"
        "AttributeEnd\n"
        "Material \"matte\" \"texture Kd\" \"n\"\nShape \"sphere\"\n",
        diag);
    RenderScene s = BuildTiny(d, diag);
    const Material &m = s.materials[size_t(s.shapes[0].material)];
    Vec3f pWorld(0.7f, -0.4f, 1.3f);
    Vec3f pRender = Vec3f(s.renderFromWorld.Point(Vec3d(pWorld)));
    ASSERT_TRUE(m.ModelAs<MatteMaterial>());
    EXPECT_NEAR(m.ModelAs<MatteMaterial>()->Kd()->Evaluate(AtP(pRender)).g,
                FBm(pWorld * 0.5f, 0.5f, 4), 1e-5f);
    EXPECT_EQ(diag.Count(), size_t(0));
}

// "dir" is in the texture's space: Rotate 90 about x turns its y into world z.
TEST(TextureScene, DirectionMixDirFollowsTheTextureTransform) {
    Diagnostics diag;
    SceneDescription d = Parse(
        "AttributeBegin\nRotate 90 1 0 0\n"
        "Texture \"t\" \"spectrum\" \"directionmix\" \"rgb tex1\" [1 0 0] \"rgb tex2\" [0 0 1] "
        "\"vector dir\" [0 2 0]\n"
        "AttributeEnd\n"
        "Material \"matte\" \"texture Kd\" \"t\"\nShape \"sphere\"\n",
        diag);
    RenderScene s = BuildTiny(d, diag);
    EXPECT_EQ(diag.Count(), size_t(0));
    const Material &m = s.materials[size_t(s.shapes[0].material)];
    ASSERT_TRUE(m.ModelAs<MatteMaterial>());
    const Texture &kd = *m.ModelAs<MatteMaterial>()->Kd();
    TextureContext c = AtUV(0, 0);
    c.n = Normalize(Vec3f(s.renderFromWorld.Vector(Vec3d(0, 0, 1))));
    EXPECT_NEAR(kd.Evaluate(c).r, 1, 1e-5f);
    c.n = Normalize(Vec3f(s.renderFromWorld.Vector(Vec3d(0, 1, 0))));
    EXPECT_NEAR(kd.Evaluate(c).b, 1, 1e-5f);

    Diagnostics d2;
    SceneDescription bad = Parse(
        "Texture \"t\" \"float\" \"directionmix\" \"vector dir\" [0 0 0]\nShape \"sphere\"\n", d2);
    const std::string err = ErrorOf<SceneError>([&] { BuildTiny(bad, d2); });
    EXPECT_NE(
        err.find("tex.pbrt:3:36: error: directionmix \"dir\" must be a nonzero, finite vector"),
        std::string::npos)
        << err;
}

TEST(TextureScene, EveryClassBuildsAndPtexWarns) {
    Diagnostics diag;
    SceneDescription d = Parse(
        "Texture \"a\" \"float\" \"bilerp\" \"float v00\" 0.5\n"
        "Texture \"b\" \"spectrum\" \"uv\" \"float uscale\" 2\n"
        "Texture \"c\" \"spectrum\" \"dots\" \"rgb inside\" [1 0 0]\n"
        "Texture \"d\" \"float\" \"wrinkled\" \"float roughness\" 0.6\n"
        "Texture \"e\" \"float\" \"windy\"\n"
        "Texture \"f\" \"spectrum\" \"marble\" \"float scale\" 3 \"float variation\" 0.5\n"
        "Texture \"g\" \"spectrum\" \"ptex\" \"string filename\" \"x.ptx\"\n"
        "Texture \"h\" \"spectrum\" \"scale\" \"texture tex\" \"c\" \"float scale\" 2\n"
        "Shape \"sphere\"\n",
        diag);
    RenderScene s = BuildTiny(d, diag);
    ASSERT_EQ(diag.Count(), size_t(1)) << diag.Warnings()[0].ToString();
    EXPECT_NE(diag.Warnings()[0].message.find("ptex"), std::string::npos);
    EXPECT_TRUE(s.features.textures);
    Diagnostics d2;
    SceneDescription bad =
        Parse("Texture \"n\" \"float\" \"fbm\" \"integer octaves\" 100000\n", d2);
    EXPECT_THROW(BuildTiny(bad, d2), SceneError);
}

// Every class of render/texture_list.inc is made by its own Create; a class the list lacks and
// the float variants pbrt-v3 lacks are ignored, each with one warning at its directive.
TEST(TextureScene, UnknownClassesAndMissingFloatVariantsAreIgnoredWithAWarning) {
    Diagnostics diag;
    SceneDescription d = Parse(
        "Texture \"u\" \"float\" \"uv\"\n"
        "Texture \"m\" \"float\" \"marble\"\n"
        "Texture \"z\" \"spectrum\" \"zigzag\"\n"
        "Shape \"sphere\"\n",
        diag);
    RenderScene s = BuildTiny(d, diag);
    ASSERT_EQ(diag.Count(), size_t(3));
    const std::vector<Warning> w = diag.Warnings();
    EXPECT_NE(w[0].message.find("\"uv\" has no float variant"), std::string::npos) << w[0].message;
    EXPECT_NE(w[1].message.find("\"marble\" has no float variant"), std::string::npos);
    EXPECT_NE(w[2].message.find("\"zigzag\" is not supported"), std::string::npos);
    // One warning per directive, at its line.
    for (int i = 1; i < 3; ++i) EXPECT_EQ(w[size_t(i)].loc.line, w[0].loc.line + i);
    EXPECT_TRUE(w[0].loc.Valid());
    EXPECT_FALSE(s.features.textures);
}

}  // namespace
}  // namespace prism
