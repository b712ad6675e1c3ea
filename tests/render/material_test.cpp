// Uber, substrate, translucent and mix against closed forms, and the scene-level material
// plumbing (named mixes, cycles, fallbacks, v4 names).
#include "render/material.h"

#include <gtest/gtest.h>

#include <cmath>

#include "assembly/build_scene.h"
#include "render/materials.h"
#include "scene/pbrt_parser.h"

namespace prism {
namespace {

TexturePtr Const(RGB v) { return std::make_shared<ConstantTexture>(v); }
TexturePtr Const(float v) { return Const(RGB(v)); }

SurfaceInteraction FlatHit() {
    SurfaceInteraction si;
    si.n = si.ns = {0, 0, 1};
    si.dpdu = {1, 0, 0};
    return si;
}

UberMaterial::Params UberParams(float kd, float ks, float kr, float kt, float opacity) {
    UberMaterial::Params u;
    u.Kd = Const(kd);
    u.Ks = Const(ks);
    u.Kr = Const(kr);
    u.Kt = Const(kt);
    u.roughness = Const(0.1f);
    u.index = Const(1.5f);
    u.opacity = Const(opacity);
    return u;
}

Material Uber(float kd, float ks, float kr, float kt, float opacity) {
    return Material(std::make_shared<UberMaterial>(UberParams(kd, ks, kr, kt, opacity)), "uber");
}

std::shared_ptr<Material> Matte(RGB kd) {
    return std::make_shared<Material>(std::make_shared<MatteMaterial>(Const(kd), Const(0.f)),
                                      "matte");
}

Material Mix(std::shared_ptr<const Material> m1, std::shared_ptr<const Material> m2,
             TexturePtr amount) {
    return Material(std::make_shared<MixMaterial>(std::move(m1), std::move(m2), std::move(amount)),
                    "mix");
}

TEST(Material, UberWithOnlyKrIsAFresnelMirror) {
    Material m = Uber(0, 0, 1, 0, 1);
    BSDF b = m.GetBSDF(FlatHit(), {});
    EXPECT_FALSE(b.HasNonSpecular());
    for (float theta : {0.f, 0.5f, 1.0f, 1.4f}) {
        Vec3f wo(std::sin(theta), 0, std::cos(theta)), wi;
        RGB w;
        ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wi, &w));
        EXPECT_NEAR(wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(wi.z, wo.z, 1e-6f);
        EXPECT_NEAR(w.g, FrDielectric(std::cos(theta), 1.f, 1.5f), 1e-6f);
        EXPECT_FALSE(b.SampleSpecularTransmission(0, wo, &wi, &w));
    }
}

TEST(Material, UberOpacityAddsAStraightPassThrough) {
    Material m = Uber(0.5f, 0, 0, 0, 0.25f);
    EXPECT_EQ(m.MaxParts(), 2);
    EXPECT_TRUE(m.MayTransmit());
    BSDF b = m.GetBSDF(FlatHit(), {});
    ASSERT_EQ(b.NumParts(), 2);
    Vec3f wo = Normalize(Vec3f(0.3f, 0.2f, 1)), wi;
    RGB w;
    ASSERT_TRUE(b.SampleSpecularTransmission(0, wo, &wi, &w));
    EXPECT_EQ(wi, -wo);
    EXPECT_NEAR(w.r, 0.75f, 1e-6f);
    // The diffuse lobe is scaled by the opacity.
    Vec3f light = Normalize(Vec3f(-0.2f, 0.1f, 1));
    EXPECT_NEAR(b.f(wo, light).r, 0.25f * 0.5f * float(InvPi), 1e-6f);
}

TEST(Material, SubstrateAtNormalIncidence) {
    Material m(std::make_shared<SubstrateMaterial>(Const(RGB(0.6f, 0.4f, 0.2f)), Const(0.05f),
                                                   Roughness{Const(0.1f), Const(0.1f), true}),
               "substrate");
    BSDF b = m.GetBSDF(FlatHit(), {});
    Vec3f n(0, 0, 1);
    RGB f = b.f(n, n);
    float alpha = RoughnessToAlpha(0.1f);
    float k = 1 - std::pow(0.5f, 5.f);
    float diffuseScale = 28.f / (23.f * float(Pi)) * (1 - 0.05f) * k * k;
    // D(normal) = 1 / (pi alpha^2); Schlick's Fresnel at cos 1 is Rs; denominator 4·1·1.
    float specular = float(1 / (Pi * alpha * alpha)) / 4 * 0.05f;
    EXPECT_NEAR(f.r, 0.6f * diffuseScale + specular, 1e-4f * f.r);
    EXPECT_NEAR(f.b, 0.2f * diffuseScale + specular, 1e-4f * f.b);
    // Grazing light: the Fresnel-weighted diffuse term vanishes as cos → 0.
    EXPECT_LT(b.f(n, Normalize(Vec3f(1, 0, 1e-4f))).r, 0.2f * f.r);
}

Material Translucent(float ks) {
    return Material(
        std::make_shared<TranslucentMaterial>(Const(RGB(0.8f, 0.6f, 0.4f)), Const(ks), Const(0.3f),
                                              Const(0.7f), Const(0.1f), true),
        "translucent");
}

TEST(Material, TranslucentTransmitsLightFromTheBack) {
    BSDF b = Translucent(0).GetBSDF(FlatHit(), {});
    Vec3f wo = Normalize(Vec3f(0.2f, 0, 1));
    Vec3f back = Normalize(Vec3f(0.5f, 0.3f, -1)), front = Normalize(Vec3f(-0.4f, 0, 1));
    RGB t = b.f(wo, back), r = b.f(wo, front);
    EXPECT_NEAR(t.r, 0.7f * 0.8f * float(InvPi), 1e-6f);
    EXPECT_NEAR(r.r, 0.3f * 0.8f * float(InvPi), 1e-6f);
    // With a glossy part, transmission peaks along the refracted direction (eta 1.5).
    BSDF g = Translucent(1).GetBSDF(FlatHit(), {});
    Vec3f woT = Normalize(Vec3f(0.5f, 0, 1));
    float sinT = woT.x / 1.5f;
    Vec3f refracted(-sinT, 0, -std::sqrt(1 - sinT * sinT));
    RGB peak = g.f(woT, refracted) - b.f(woT, refracted);
    RGB off =
        g.f(woT, Normalize(Vec3f(0.6f, 0.4f, -1))) - b.f(woT, Normalize(Vec3f(0.6f, 0.4f, -1)));
    EXPECT_GT(peak.r, 1.f);
    EXPECT_GT(peak.r, 20 * off.r);
    EXPECT_TRUE(peak.IsFinite());
    // Closed form at the exact refraction (pbrt-v3 MicrofacetTransmission, eta 1.5): the
    // generalized half vector is the normal, so D = 1 / (pi alpha^2), and
    // f = t Ks (1 - Fr(cos o)) D G / (cos o - eta cos t)^2 with Smith G for Trowbridge-Reitz.
    double x = std::log(0.1);  // pbrt-v3 RoughnessToAlpha(0.1)
    double alpha = 1.62142 + 0.819955 * x + 0.1734 * x * x + 0.0171201 * x * x * x +
                   0.000640711 * x * x * x * x;
    double eta = 1.5, sinO = double(woT.x), cosO = double(woT.z);
    double sinI = sinO / eta, cosI = std::sqrt(1 - sinI * sinI);
    auto lambda = [&](double sin, double cos) {
        double tan = sin / cos;
        return (-1 + std::sqrt(1 + alpha * alpha * tan * tan)) / 2;
    };
    double G = 1 / (1 + lambda(sinO, cosO) + lambda(sinI, cosI));
    double rParl = (eta * cosO - cosI) / (eta * cosO + cosI);
    double rPerp = (cosO - eta * cosI) / (cosO + eta * cosI);
    double Fr = (rParl * rParl + rPerp * rPerp) / 2;
    double D = 1 / (Pi * alpha * alpha);
    double want = 0.7 * (1 - Fr) * D * G / ((cosO - eta * cosI) * (cosO - eta * cosI));
    EXPECT_NEAR(peak.r, want, 1e-4 * want);
    EXPECT_NEAR(peak.b, want, 1e-4 * want);  // Ks is grey: the same in every channel
}

TEST(Material, MixOfMattesIsTheBlendedMatte) {
    // pbrt-v3 MixMaterial: namedmaterial1 weighted by amount, namedmaterial2 by 1 - amount.
    RGB A(0.8f, 0.1f, 0.3f), B(0.2f, 0.9f, 0.5f);
    float a = 0.3f;
    Material mix = Mix(Matte(A), Matte(B), Const(a));
    BSDF b = mix.GetBSDF(FlatHit(), {});
    Material blended = *Matte(A * a + B * (1 - a));
    BSDF want = blended.GetBSDF(FlatHit(), {});
    Vec3f wo = Normalize(Vec3f(0.1f, 0.3f, 1)), wi = Normalize(Vec3f(-0.5f, 0.2f, 1));
    RGB got = b.f(wo, wi), exp = want.f(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], exp[c], 1e-6f);
}

TEST(Material, MixWeightsDeltaLobes) {
    auto mirror =
        std::make_shared<Material>(std::make_shared<MirrorMaterial>(Const(1.f)), "mirror");
    // Per-channel weights, as pbrt's Spectrum.
    Material mix = Mix(mirror, Matte(RGB(0.5f)), Const(RGB(0.25f, 0.5f, 1.f)));
    EXPECT_TRUE(mix.MayReflectSpecularly());
    BSDF b = mix.GetBSDF(FlatHit(), {});
    Vec3f wo = Normalize(Vec3f(0.3f, 0, 1)), wi;
    RGB w;
    ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wi, &w));
    EXPECT_EQ(w, RGB(0.25f, 0.5f, 1.f));
    // The matte share is 1 - amount (blue: none).
    RGB f = b.f(wo, Normalize(Vec3f(-0.3f, 0.1f, 1)));
    EXPECT_NEAR(f.r, 0.75f * 0.5f * float(InvPi), 1e-6f);
    EXPECT_EQ(f.b, 0.f);
}

// ---- Through the scene builder ----------------------------------------------------------

RenderScene Build(const std::string &world, Diagnostics &diag) {
    SceneDescription d = ParsePbrtString(
        "Camera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n" + world,
        "test.pbrt", diag);
    BuildSettings o;
    o.resolution = {8, 8};
    return BuildRenderScene(d, o, diag);
}

const Material &ShapeMaterial(const RenderScene &s) {
    return s.materials[size_t(s.shapes[0].material)];
}

// pbrt-v4's thindielectric: a slab whose delta reflection is R' = R + T²R/(1 - R²) (2R/(1 + R)
// at normal incidence, R = ((eta - 1)/(eta + 1))²) and whose transmission, 1 - R', goes
// straight through; Sample_f chooses them in that proportion, so its weights average to 1.
TEST(MaterialScene, ThinDielectricReflectsTheSlabAndTransmitsTheRestStraight) {
    Diagnostics diag;
    RenderScene s =
        Build("Material \"thindielectric\" \"float eta\" 1.5\nShape \"sphere\"\n", diag);
    EXPECT_EQ(diag.Count(), size_t(0));
    const Material &m = ShapeMaterial(s);
    EXPECT_TRUE(m.MayReflectSpecularly());
    EXPECT_TRUE(m.MayTransmit());
    const BSDF b = m.GetBSDF(FlatHit(), {});
    const double R0 = 0.04, slab = 2 * R0 / (1 + R0);
    for (float cosO : {1.f, 0.5f, 0.1f}) {
        const Vec3f wo(std::sqrt(1 - cosO * cosO), 0, cosO);
        Vec3f wr, wt;
        RGB r, t;
        ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wr, &r));
        ASSERT_TRUE(b.SampleSpecularTransmission(0, wo, &wt, &t));
        EXPECT_NEAR(r.g + t.g, 1, 1e-6) << cosO;  // nothing absorbed
        EXPECT_EQ(wt, -wo);                       // not bent
        EXPECT_NEAR(wr.z, cosO, 1e-6);
        if (cosO == 1) EXPECT_NEAR(r.g, slab, 1e-6);
        // More than a single face reflects: the second face's bounces add to it.
        EXPECT_GT(r.g, FrDielectric(cosO, 1.f, 1.5f)) << cosO;
        // From inside the slab's other side, the same.
        Vec3f wr2;
        RGB r2;
        ASSERT_TRUE(b.SampleSpecularReflection(0, -wo, &wr2, &r2));
        EXPECT_NEAR(r2.g, r.g, 1e-6);
        double sum = 0, reflected = 0;
        const int n = 4000;
        for (int i = 0; i < n; ++i) {
            BSDFSample bs;
            ASSERT_TRUE(b.Sample_f(wo, {0.5f, 0.5f}, (i + 0.5f) / n, true, &bs));
            ASSERT_TRUE(bs.specular);
            sum += bs.weight.g;
            if (!bs.transmission) reflected += 1;
        }
        EXPECT_NEAR(sum / n, 1, 1e-3) << cosO;
        EXPECT_NEAR(reflected / n, r.g, 2e-3) << cosO;
    }
    // An index of 1 is no slab: all of it passes.
    Diagnostics d2;
    RenderScene none = Build("Material \"thindielectric\" \"float eta\" 1\nShape \"sphere\"\n", d2);
    EXPECT_FALSE(ShapeMaterial(none).MayReflectSpecularly());
}

TEST(MaterialScene, NamedMixResolvesAndBlends) {
    Diagnostics diag;
    RenderScene s = Build(
        "MakeNamedMaterial \"red\" \"string type\" \"matte\" \"rgb Kd\" [1 0 0]\n"
        "MakeNamedMaterial \"blue\" \"string type\" \"matte\" \"rgb Kd\" [0 0 1]\n"
        "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string namedmaterial1\" \"red\"\n"
        "  \"string namedmaterial2\" \"blue\" \"rgb amount\" [0.25 0.25 0.25]\n"
        "NamedMaterial \"m\"\nShape \"sphere\"\n",
        diag);
    const Material &m = ShapeMaterial(s);
    ASSERT_TRUE(m.ModelAs<MixMaterial>());
    BSDF b = m.GetBSDF(FlatHit(), {});
    Vec3f n(0, 0, 1);
    RGB f = b.f(n, n);
    EXPECT_NEAR(f.r, 0.25f * float(InvPi), 1e-6f);
    EXPECT_NEAR(f.b, 0.75f * float(InvPi), 1e-6f);
    EXPECT_EQ(diag.Count(), size_t(0));
}

TEST(MaterialScene, MixCycleIsAnErrorWithLocation) {
    Diagnostics diag;
    try {
        Build(
            "MakeNamedMaterial \"a\" \"string type\" \"mix\" \"string namedmaterial1\" \"b\"\n"
            "  \"string namedmaterial2\" \"b\"\n"
            "MakeNamedMaterial \"b\" \"string type\" \"mix\" \"string namedmaterial1\" \"a\"\n"
            "  \"string namedmaterial2\" \"a\"\n"
            "NamedMaterial \"a\"\nShape \"sphere\"\n",
            diag);
        FAIL() << "expected a SceneError";
    } catch (const SceneError &e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("refers to itself"), std::string::npos) << msg;
        EXPECT_NE(msg.find("test.pbrt:"), std::string::npos) << msg;
    }
    Diagnostics d2;
    EXPECT_THROW(
        Build("MakeNamedMaterial \"s\" \"string type\" \"mix\" \"string namedmaterial1\" \"s\"\n"
              "  \"string namedmaterial2\" \"s\"\nNamedMaterial \"s\"\nShape \"sphere\"\n",
              d2),
        SceneError);
}

TEST(MaterialScene, UnsupportedMaterialFallsBackToMatteWithItsColour) {
    Diagnostics diag;
    RenderScene s = Build(
        "Material \"velvet\" \"rgb color\" [0.2 0.4 0.6] \"float metallic\" 1\n"
        "Shape \"sphere\"\n",
        diag);
    const Material &m = ShapeMaterial(s);
    ASSERT_TRUE(m.ModelAs<MatteMaterial>());
    EXPECT_EQ(m.LambertianKd({}), RGB(0.2f, 0.4f, 0.6f));
    ASSERT_EQ(diag.Count(), size_t(1));
    EXPECT_NE(diag.Warnings()[0].message.find("velvet"), std::string::npos);
}

TEST(MaterialScene, V4Names) {
    Diagnostics diag;
    RenderScene s =
        Build("Material \"conductor\" \"rgb reflectance\" [0.9 0.5 0.2]\nShape \"sphere\"\n", diag);
    const Material &m = ShapeMaterial(s);
    const MetalMaterial *metal = m.ModelAs<MetalMaterial>();
    ASSERT_TRUE(metal);
    EXPECT_TRUE(m.MayReflectSpecularly());  // v4 conductors default to roughness 0
    RGB r0 = FrConductor(1.f, RGB(1), metal->Eta(), metal->K());
    EXPECT_NEAR(r0.r, 0.9f, 1e-4f);
    EXPECT_NEAR(r0.b, 0.2f, 1e-4f);
    Diagnostics d2;
    RenderScene t = Build(
        "Material \"diffusetransmission\" \"rgb transmittance\" [0.5 0.5 0.5]\n"
        "Shape \"sphere\"\n",
        d2);
    EXPECT_TRUE(ShapeMaterial(t).ModelAs<TranslucentMaterial>());
    BSDF b = ShapeMaterial(t).GetBSDF(FlatHit(), {});
    EXPECT_NEAR(b.f({0, 0, 1}, {0, 0, -1}).r, 0.5f * float(InvPi), 1e-6f);
    EXPECT_EQ(d2.Count(), size_t(0));
}

TEST(MaterialScene, LoopSubdivShapeBecomesAMesh) {
    Diagnostics diag;
    RenderScene s = Build(
        "Shape \"loopsubdiv\" \"integer levels\" [2] \"integer indices\" "
        "[0 1 2 0 3 1 0 2 3 1 3 2] \"point3 P\" [1 1 1 1 -1 -1 -1 1 -1 -1 -1 1]\n",
        diag);
    EXPECT_EQ(s.features.triangles, size_t(4 * 16));
    EXPECT_EQ(diag.Count(), size_t(0));
    Diagnostics d2;
    EXPECT_THROW(Build("Shape \"loopsubdiv\" \"integer nlevels\" [30] \"integer indices\" [0 1 2] "
                       "\"point3 P\" [0 0 0 1 0 0 0 1 0]\n",
                       d2),
                 SceneError);
}

// A texture that varies with uv (any non-constant texture makes a material read uv).
struct UTexture final : Texture {
    RGB Evaluate(const TextureContext &c) const override { return RGB(c.uv.x); }
};

TEST(Material, SurfaceNeedsFollowTexturesAndAnisotropy) {
    EXPECT_EQ(Matte(RGB(0.5f))->SurfaceNeeds(), unsigned(NeedNone));
    Material textured(std::make_shared<MatteMaterial>(std::make_shared<UTexture>(), Const(0.f)),
                      "matte");
    EXPECT_EQ(textured.SurfaceNeeds(), unsigned(NeedUV));
    auto metal = [](TexturePtr v) {
        return Material(std::make_shared<MetalMaterial>(RGB(1), RGB(1),
                                                        Roughness{Const(0.1f), std::move(v), true}),
                        "metal");
    };
    EXPECT_EQ(metal(Const(0.1f)).SurfaceNeeds(), unsigned(NeedNone));  // isotropic: no frame
    EXPECT_EQ(metal(Const(0.3f)).SurfaceNeeds(), unsigned(NeedDpdu));
    EXPECT_EQ(metal(std::make_shared<UTexture>()).SurfaceNeeds(), unsigned(NeedAll));
    Material uber = Uber(0.5f, 0.5f, 0, 0, 1);
    EXPECT_EQ(uber.SurfaceNeeds(), unsigned(NeedNone));
    UberMaterial::Params anisotropic = UberParams(0.5f, 0.5f, 0, 0, 1);
    anisotropic.vRoughness = Const(0.4f);
    EXPECT_EQ(Material(std::make_shared<UberMaterial>(anisotropic), "uber").SurfaceNeeds(),
              unsigned(NeedDpdu));
    EXPECT_EQ(Mix(Matte(RGB(0.2f)), Matte(RGB(0.8f)), Const(0.3f)).SurfaceNeeds(),
              unsigned(NeedNone));
    EXPECT_EQ(Mix(Matte(RGB(0.2f)), Matte(RGB(0.8f)), std::make_shared<UTexture>()).SurfaceNeeds(),
              unsigned(NeedUV));
}

// A metal is a delta mirror only at pbrt-v4's "effectively smooth" alpha (< 1e-3); sharper
// lobes above it stay microfacet lobes, as pbrt-v3 and pbrt-v4 render them (veach-mis's
// smoothest plates are alpha 0.005).
TEST(Material, OnlyAnEffectivelySmoothMetalIsAMirror) {
    auto metal = [](float alpha) {
        return Material(std::make_shared<MetalMaterial>(
                            RGB(0.2f), RGB(3), Roughness{Const(alpha), Const(alpha), false}),
                        "metal");
    };
    EXPECT_TRUE(metal(0).MayReflectSpecularly());
    EXPECT_FALSE(metal(0).MayReflectGlossily());
    EXPECT_TRUE(metal(0.0009f).MayReflectSpecularly());
    for (float a : {0.002f, 0.005f, 0.02f}) {
        const Material m = metal(a);
        EXPECT_FALSE(m.MayReflectSpecularly()) << a;
        EXPECT_TRUE(m.MayReflectGlossily()) << a;
        BSDF b = m.GetBSDF(FlatHit(), {});
        EXPECT_TRUE(b.HasGlossy()) << a;
    }
}

// Prepare builds the parts once; the BSDF a hit gets must be exactly the one built per hit.
TEST(Material, PreparedPartsEqualPerHitParts) {
    auto uber = std::make_shared<Material>(Uber(0.3f, 0.4f, 0.2f, 0.1f, 0.7f));
    Material mix = Mix(Matte(RGB(0.2f, 0.4f, 0.6f)), uber, Const(RGB(0.3f, 0.5f, 0.9f)));
    std::vector<Material> materials = {*Matte(RGB(0.5f)), Uber(0.3f, 0.4f, 0.2f, 0.1f, 0.7f), mix};
    for (Material &m : materials) {
        BSDF a = m.GetBSDF(FlatHit(), {});
        m.Prepare();
        BSDF b = m.GetBSDF(FlatHit(), {});
        ASSERT_EQ(a.NumParts(), b.NumParts());
        for (float theta : {0.1f, 0.7f, 1.3f}) {
            Vec3f wo(std::sin(theta), 0, std::cos(theta)), wi(-0.3f, 0.2f, 0.93f);
            wi = Normalize(wi);
            RGB fa = a.f(wo, wi), fb = b.f(wo, wi);
            EXPECT_EQ(fa.r, fb.r);
            EXPECT_EQ(fa.g, fb.g);
            EXPECT_EQ(fa.b, fb.b);
            for (int i = 0; i < a.NumParts(); ++i) {
                Vec3f wa, wb;
                RGB ra, rb;
                bool ha = a.SampleSpecularReflection(i, wo, &wa, &ra);
                ASSERT_EQ(ha, b.SampleSpecularReflection(i, wo, &wb, &rb));
                if (ha) EXPECT_EQ(ra.g, rb.g);
                ha = a.SampleSpecularTransmission(i, wo, &wa, &ra);
                ASSERT_EQ(ha, b.SampleSpecularTransmission(i, wo, &wb, &rb));
                if (ha) EXPECT_EQ(ra.g, rb.g);
            }
        }
    }
}

}  // namespace
}  // namespace prism
