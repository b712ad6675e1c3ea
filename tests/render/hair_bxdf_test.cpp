// pbrt's hair fibre model (render/hair_bxdf.h) against quadrature: a fibre that absorbs
// nothing scatters all the light it meets, its sampling density integrates to 1 and is the
// density its samples are drawn from, the reflection off a tube peaks in the tube's mirror
// direction (the sign of h against the azimuth), and the material as a scene file declares it.
#include "render/hair_bxdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "assembly/build_scene.h"
#include "core/rng.h"
#include "geometry/curves.h"
#include "render/bsdf.h"
#include "render/hair_material.h"
#include "scene/pbrt_parser.h"
#include "support/render_text.h"

namespace prism {
namespace {

Vec3f Direction(float sinTheta, float phi) {
    const float c = std::sqrt(std::max(0.f, 1 - sinTheta * sinTheta));
    return {sinTheta, c * std::cos(phi), c * std::sin(phi)};
}

// ∫ g(wi) dωi over the sphere in the fibre's angles (dω = cos θ dθ dφ), midpoint rule.
template <typename G>
RGB Integrate(G g, int n = 1000) {
    RGB sum;
    const double dTheta = Pi / n, dPhi = 2 * Pi / n;
    for (int i = 0; i < n; ++i) {
        const double theta = -Pi / 2 + (i + 0.5) * dTheta;
        const float w = float(std::cos(theta) * dTheta * dPhi);
        for (int j = 0; j < n; ++j) {
            const float phi = float(-Pi + (j + 0.5) * dPhi);
            sum += g(Direction(float(std::sin(theta)), phi)) * w;
        }
    }
    return sum;
}

struct Case {
    float h, betaM, betaN, alpha, sinThetaO, phiO;
};
const Case kCases[] = {
    {0.f, 0.3f, 0.3f, 2.f, 0.f, 0.5f},     {0.6f, 0.3f, 0.3f, 2.f, 0.4f, -1.f},
    {-0.9f, 0.5f, 0.6f, -3.f, -0.7f, 2.f}, {0.3f, 0.15f, 0.2f, 2.f, 0.2f, 0.f},
    {0.95f, 0.8f, 0.9f, 10.f, 0.9f, 3.f},
};

TEST(HairLobe, AFibreThatAbsorbsNothingScattersEverything) {
    for (const Case &c : kCases) {
        const HairLobe l = HairLobe::Make(c.h, 1.55f, RGB(0), c.betaM, c.betaN, c.alpha);
        const Vec3f wo = Direction(c.sinThetaO, c.phiO);
        const RGB albedo = Integrate([&](const Vec3f &wi) { return l.f(wo, wi) * std::abs(wi.z); });
        EXPECT_NEAR(albedo.r, 1, 5e-3) << "h " << c.h << " betaM " << c.betaM;
        EXPECT_NEAR(albedo.b, 1, 5e-3);
        const RGB pdf = Integrate([&](const Vec3f &wi) { return RGB(l.Pdf(wo, wi)); });
        EXPECT_NEAR(pdf.g, 1, 5e-3);
    }
}

TEST(HairLobe, SamplesAreDrawnFromTheirDensity) {
    // An absorbing, coloured fibre: the paths are chosen by luminance, so the estimate of the
    // albedo is exact only if the samples follow the density they report.
    PCG32 rng(7);
    for (const Case &c : kCases) {
        const RGB sigmaA = HairLobe::SigmaAFromConcentration(0.8f, 0.5f);
        const HairLobe l = HairLobe::Make(c.h, 1.55f, sigmaA, c.betaM, c.betaN, c.alpha);
        const Vec3f wo = Direction(c.sinThetaO, c.phiO);
        const RGB albedo = Integrate([&](const Vec3f &wi) { return l.f(wo, wi) * std::abs(wi.z); });
        RGB estimate;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            Vec3f wi;
            float pdf = 0;
            if (!l.Sample(wo, rng.Uniform(), {rng.Uniform(), rng.Uniform()}, &wi, &pdf)) continue;
            ASSERT_NEAR(pdf, l.Pdf(wo, wi), 2e-3f * pdf + 1e-6f);
            estimate += l.f(wo, wi) * (std::abs(wi.z) / pdf);
        }
        estimate = estimate / float(n);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(estimate[k], albedo[k], 0.01f * albedo[k] + 1e-4f);
            EXPECT_NEAR(l.Albedo(wo)[k], albedo[k], 0.005f * albedo[k] + 1e-4f);  // the AOV's
        }
        EXPECT_LT(albedo.b, albedo.r);  // melanin absorbs blue most
    }
}

TEST(HairLobe, PigmentAndColourGiveTheAbsorption) {
    const RGB e = HairLobe::SigmaAFromConcentration(1.3f, 0);
    EXPECT_NEAR(e.r, 1.3f * 0.419f, 1e-6f);
    EXPECT_NEAR(e.b, 1.3f * 1.37f, 1e-6f);
    // A darker colour absorbs more; white absorbs (almost) nothing.
    const RGB s = HairLobe::SigmaAFromReflectance(RGB(0.2f, 0.5f, 0.99f), 0.3f);
    EXPECT_GT(s.r, s.g);
    EXPECT_GT(s.g, s.b);
    EXPECT_LT(s.b, 1e-3f);
}

// A tube of radius 1 along x, seen from +z: a ray at height y = h meets it at h across its
// width, and the tube's normal there mirrors the ray to a direction whose azimuth the R lobe
// must peak at, whatever the sign of h.
TEST(HairMaterial, ReflectionPeaksInTheTubesMirrorDirection) {
    const CurveSet tube(Transform(), false, CurveType::Cylinder,
                        {{-1, 0, 0}, {-1.f / 3, 0, 0}, {1.f / 3, 0, 0}, {1, 0, 0}}, 2.f, 2.f);
    HairMaterial::Params p;
    p.sigmaA = std::make_shared<ConstantTexture>(RGB(50));  // only R leaves
    p.eta = std::make_shared<ConstantTexture>(RGB(1.55f));
    p.betaM = std::make_shared<ConstantTexture>(RGB(0.3f));
    p.betaN = std::make_shared<ConstantTexture>(RGB(0.1f));
    p.alpha = std::make_shared<ConstantTexture>(RGB(0.f));
    const Material m(std::make_shared<HairMaterial>(p), "hair");
    for (float h : {-0.7f, -0.3f, 0.4f, 0.8f}) {
        const float z = std::sqrt(1 - h * h);
        const Vec3f o(0, h, 5), d(0, 0, -1);
        const SurfaceInteraction si = tube.Interaction(0, 0.5f, 0, 5 - z, o, d, 0, 0);
        ASSERT_NEAR(si.uv.y, 0.5f * (1 + h), 1e-3f);  // pbrt's h = -1 + 2v
        TextureContext tc;
        tc.uv = si.uv;
        const BSDF b = m.GetBSDF(si, tc);
        const Vec3f wo(0, 0, 1), n(0, h, z);
        const Vec3f mirror = n * (2 * Dot(wo, n)) - wo;
        // The brightest direction across the tube (reflected radiance: f |cos| at the normal).
        float best = -1, bestPhi = 0;
        for (int i = 0; i < 3600; ++i) {
            const float phi = float(2 * Pi * i / 3600);
            const Vec3f wi(0, std::cos(phi), std::sin(phi));
            const float v = b.f(wo, wi).g * AbsDot(wi, b.ns);
            if (v > best) best = v, bestPhi = phi;
        }
        const Vec3f peak(0, std::cos(bestPhi), std::sin(bestPhi));
        EXPECT_GT(Dot(peak, mirror), std::cos(0.03f)) << "h " << h;
    }
}

TEST(HairMaterial, TheBsdfSamplesAndWeighsTheFibreOnBothSides) {
    const HairLobe l = HairLobe::Make(0.4f, 1.55f, RGB(0.2f, 0.5f, 1.f), 0.3f, 0.3f, 2.f);
    BSDF b;
    // The frame of a tube hit: the fibre along x, the normal tilted towards the viewer.
    b.SetFrame(Normalize(Vec3f(0, 0.4f, 0.9f)), {1, 0, 0}, Normalize(Vec3f(0, 0.4f, 0.9f)));
    b.AddPart(RGB(1)).hair = l;
    const Vec3f woW = Normalize(Vec3f(0.3f, 0.1f, 1));
    const Vec3f wo = b.ToLocal(woW);
    const RGB albedo = Integrate([&](const Vec3f &wi) { return l.f(wo, wi) * std::abs(wi.z); });
    PCG32 rng(3);
    RGB estimate;
    int behind = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        BSDFSample s;
        if (!b.Sample_f(woW, {rng.Uniform(), rng.Uniform()}, rng.Uniform(), true, &s)) continue;
        EXPECT_FALSE(s.specular);
        EXPECT_NEAR(s.pdf, b.Pdf(woW, s.wi, true), 2e-3f * s.pdf);
        estimate += s.weight;
        behind += Dot(s.wi, b.ng) < 0;
    }
    estimate = estimate / float(n);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(estimate[k], albedo[k], 0.015f * albedo[k]);
    EXPECT_GT(behind, n / 10);  // TT leaves through the far side
}

// ---- Through the scene builder ----------------------------------------------------------

HairLobe LobeOf(const Material &m, float v) {
    SurfaceInteraction si;
    si.n = si.ns = {0, 0, 1};
    si.dpdu = {1, 0, 0};
    TextureContext tc;
    tc.uv = {0.5f, v};
    const BSDF b = m.GetBSDF(si, tc);
    EXPECT_EQ(b.NumParts(), 1);
    return b.Part(0).hair;
}

TEST(HairMaterial, ReadsPbrtsParametersAndDefaults) {
    Diagnostics diag;
    RenderScene keep;
    // No absorption given: eumelanin 1.3.
    HairLobe l = LobeOf(test::BuildSphereMaterial("Material \"hair\"\n", diag, keep), 0.75f);
    EXPECT_FLOAT_EQ(l.h, 0.5f);
    EXPECT_FLOAT_EQ(l.eta, 1.55f);
    EXPECT_NEAR(l.sigmaA.g, 1.3f * 0.697f, 1e-5f);
    EXPECT_EQ(l.sigmaA, HairLobe::Make(0, 1.55f, l.sigmaA, 0.3f, 0.3f, 2).sigmaA);
    EXPECT_FLOAT_EQ(l.v0, HairLobe::Make(0, 1.55f, RGB(0), 0.3f, 0.3f, 2).v0);
    EXPECT_FLOAT_EQ(l.s, HairLobe::Make(0, 1.55f, RGB(0), 0.3f, 0.3f, 2).s);
    // A pbrt-v3 file: pbrt-v3's tilt, the other way along the fibre from pbrt-v4's.
    EXPECT_FLOAT_EQ(l.sinAlpha, -std::sin(float(Radians(2))));
    EXPECT_EQ(diag.Count(), size_t(0));

    // Pheomelanin alone: no eumelanin.
    l = LobeOf(test::BuildSphereMaterial("Material \"hair\" \"float pheomelanin\" 2\n", diag, keep),
               0.5f);
    EXPECT_NEAR(l.sigmaA.r, 2 * 0.187f, 1e-5f);

    // sigma_a wins over colour and melanin, which are warned.
    l = LobeOf(
        test::BuildSphereMaterial("Material \"hair\" \"rgb sigma_a\" [0.1 0.2 0.3] \"rgb color\" "
                                  "[0.5 0.5 0.5] \"float eumelanin\" 3 \"float beta_m\" 0.5 "
                                  "\"float beta_n\" 0.7 \"float alpha\" 0 \"float eta\" 1.4\n",
                                  diag, keep),
        0);
    EXPECT_EQ(l.sigmaA, RGB(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(l.h, -1);
    EXPECT_FLOAT_EQ(l.eta, 1.4f);
    EXPECT_EQ(l.sinAlpha, 0);
    EXPECT_FLOAT_EQ(l.v0, HairLobe::Make(0, 1, RGB(0), 0.5f, 0.7f, 0).v0);
    EXPECT_EQ(diag.Count(), size_t(2));

    // pbrt-v4's "reflectance" is pbrt-v3's "color", and a pbrt-v4 file tilts the lobes as
    // pbrt-v4 does.
    l = LobeOf(test::BuildSphereMaterial("Material \"hair\" \"rgb reflectance\" [0.3 0.2 0.1]\n",
                                         diag, keep),
               0.5f);
    EXPECT_EQ(l.sigmaA, HairLobe::SigmaAFromReflectance(RGB(0.3f, 0.2f, 0.1f), 0.3f));
    EXPECT_FLOAT_EQ(l.sinAlpha, std::sin(float(Radians(2))));
}

TEST(HairMaterial, OutOfRangeConstantsAreErrorsAtTheParameter) {
    test::ExpectMaterialErrors("hair",
                               {"\"float beta_m\" 1.5", "\"float beta_n\" -0.1", "\"float eta\" 0",
                                "\"float eumelanin\" -1"},
                               "out of range");
}

}  // namespace
}  // namespace prism
