// pbrt-v3's subsurface scattering (render/bssrdf.h, render/subsurface.h): the Fresnel moments
// and the exit's normalisation against quadrature, the beam-diffusion table's albedos, radii
// drawn from the profile's own density, kdsubsurface's inversion, and whole renders of both
// materials against pbrt-v3's own images of the same scenes.
#include "render/bssrdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "render/bsdf.h"
#include "render/subsurface_material.h"
#include "support/image_stats.h"
#include "support/render_text.h"

namespace prism {
namespace {

// ∫0^1 g(μ) dμ by the midpoint rule.
template <typename G>
double Quad(G g, int n = 200000) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += g((i + 0.5) / n);
    return sum / n;
}

TEST(Bssrdf, FresnelMomentsMatchQuadrature) {
    // η is the index inside over the index outside, light arriving from inside (d'Eon and
    // Irving's fits: about 1% of the moments over pbrt's range of η).
    for (float eta : {0.7f, 1.f / 1.33f, 1.2f, 1.33f, 1.5f, 2.f}) {
        const double m1 = Quad([&](double mu) { return FrDielectric(float(mu), eta, 1) * mu; });
        const double m2 =
            Quad([&](double mu) { return FrDielectric(float(mu), eta, 1) * mu * mu; });
        EXPECT_NEAR(FresnelMoment1(eta), m1, 0.01 * m1 + 2e-3) << eta;
        EXPECT_NEAR(FresnelMoment2(eta), m2, 0.01 * m2 + 2e-3) << eta;
    }
}

TEST(Bssrdf, TheExitLobeIsNormalised) {
    // ∫ Sw cos dω = 1 over the hemisphere, up to the moment fit.
    for (float eta : {1.f, 1.33f, 1.5f}) {
        const double total =
            2 * Pi * Quad([&](double mu) { return SubsurfaceSw(float(mu), eta) * mu; });
        EXPECT_NEAR(total, 1, 0.01) << eta;
    }
    // As a BSDF lobe: η² Sw, sampled by the cosine, on wo's side only.
    BSDF b;
    b.SetFrame({0, 0, 1}, {1, 0, 0}, {0, 0, 1});
    b.AddPart().subsurfaceEta = 1.33f;
    const Vec3f wo(0, 0, 1), wi = Normalize(Vec3f(0.3f, 0.2f, 0.8f));
    EXPECT_NEAR(b.f(wo, wi).g, 1.33f * 1.33f * SubsurfaceSw(wi.z, 1.33f), 1e-6f);
    EXPECT_EQ(b.f(wo, Vec3f(wi.x, wi.y, -wi.z)).g, 0.f);
    BSDFSample s;
    ASSERT_TRUE(b.Sample_f(wo, {0.3f, 0.6f}, 0.5f, true, &s));
    EXPECT_NEAR(s.pdf, s.wi.z / float(Pi), 1e-5f);
    EXPECT_FALSE(s.specular);
}

TEST(Bssrdf, TheTableAlbedoGrowsWithTheSingleScatteringAlbedo) {
    const auto t = BeamDiffusionTable(0, 1.33f);
    ASSERT_EQ(t->NumRho(), 100);
    ASSERT_EQ(t->NumRadius(), 64);
    EXPECT_EQ(t->rho.front(), 0.f);
    EXPECT_FLOAT_EQ(t->rho.back(), 1.f);
    EXPECT_EQ(t->rhoEff.front(), 0.f);
    for (int i = 1; i < t->NumRho(); ++i) EXPECT_GT(t->rhoEff[size_t(i)], t->rhoEff[size_t(i - 1)]);
    // Without absorption nearly all light comes back out (the diffusion model is not exact).
    EXPECT_GT(t->rhoEff.back(), 0.8f);
    EXPECT_LT(t->rhoEff.back(), 1.05f);
    // One table per (g, η), shared.
    EXPECT_EQ(BeamDiffusionTable(0, 1.33f).get(), t.get());
    EXPECT_NE(BeamDiffusionTable(0.5f, 1.33f).get(), t.get());
}

TEST(Bssrdf, RadiiAreDrawnFromTheProfilesDensity) {
    const auto t = BeamDiffusionTable(0, 1.33f);
    const SeparableBssrdf b(*t, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec3f(1, 0, 0), 1.33f,
                            RGB(0.05f, 0.5f, 2.f), RGB(4, 3, 2));
    for (int ch = 0; ch < 3; ++ch) {
        // The density integrates to 1 over the plane.
        const float rMax = b.SampleSr(ch, 0.9999f);
        ASSERT_GT(rMax, 0);
        double total = 0;
        constexpr int Q = 200000;
        for (int q = 0; q < Q; ++q) {
            const double r = 2.0 * rMax * (q + 0.5) / Q;
            total += b.PdfSr(ch, float(r)) * 2 * Pi * r * (2.0 * rMax / Q);
        }
        EXPECT_NEAR(total, 1, 0.01) << ch;
        // Samples below each radius in the share the density gives.
        PCG32 rng(11 + uint64_t(ch));
        constexpr int N = 100000;
        for (float frac : {0.02f, 0.1f, 0.3f}) {
            const float edge = frac * rMax;
            int below = 0;
            for (int k = 0; k < N; ++k) below += b.SampleSr(ch, rng.Uniform()) < edge;
            double expect = 0;
            for (int q = 0; q < Q; ++q) {
                const double r = edge * (q + 0.5) / Q;
                expect += b.PdfSr(ch, float(r)) * 2 * Pi * r * (edge / double(Q));
            }
            EXPECT_NEAR(double(below) / N, expect, 0.006) << ch << " " << frac;
        }
    }
    // A channel that does not scatter gives no radius.
    const SeparableBssrdf none(*t, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec3f(1, 0, 0), 1.33f, RGB(0),
                               RGB(0));
    EXPECT_LT(none.SampleSr(0, 0.5f), 0);
}

TEST(Bssrdf, ADiffuseColourIsTheAlbedoOfItsCoefficients) {
    const auto t = BeamDiffusionTable(0, 1.33f);
    RGB sa, ss;
    const RGB kd(0.8f, 0.5f, 0.1f), mfp(0.5f, 1, 2);
    SubsurfaceFromDiffuse(*t, kd, mfp, &sa, &ss);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sa[c] + ss[c], 1 / mfp[c], 1e-5f) << c;
        // The table's effective albedo at ρ = σs / σt is the colour asked for.
        const float rho = ss[c] / (sa[c] + ss[c]);
        int off;
        float w[4];
        ASSERT_TRUE(CatmullRomWeights(t->rho, rho, &off, w));
        double eff = 0;
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0) eff += double(w[k]) * t->rhoEff[size_t(off + k)];
        EXPECT_NEAR(eff, kd[c], 1e-3) << c;
    }
}

// A sphere of each subsurface material under a quad light, seen against black; pbrt-v3's
// means of these exact scenes (4096 spp, `pbrt --nthreads 2`).

TEST(Subsurface, RendersAsPbrtV3) {
    struct Case {
        const char *material;
        RGB pbrt3;
    };
    const Case cases[] = {
        {"Material \"kdsubsurface\" \"rgb Kd\" [0.8 0.5 0.3] \"rgb mfp\" [0.2 0.1 0.05]",
         RGB(0.158829f, 0.100230f, 0.060609f)},
        {"Material \"subsurface\" \"string name\" \"Ketchup\" \"float scale\" 20 \"float eta\" 1.5",
         RGB(0.044782f, 0.027972f, 0.027619f)},
    };
    for (const Case &c : cases) {
        const test::Rendered r =
            test::RenderSceneText("bssrdf", "sphere", test::LitSphereScene(c.material, 1024));
        const RGB m = test::MeanRGB(r.image);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(m[ch], c.pbrt3[ch], 0.03f * c.pbrt3[ch]) << c.material << " " << ch;
        EXPECT_GT(r.stats.rays.subsurface, 0u);
        EXPECT_TRUE(r.scene.features.effects.Has(Effect::Subsurface));
    }
}

TEST(Subsurface, OtherIntegratorsRenderTheInterfaceAndSaySo) {
    const std::string scene = test::LitSphereScene(
        "Material \"kdsubsurface\" \"rgb Kd\" [0.8 0.5 0.3] \"rgb mfp\" [0.2 0.1 0.05]", 16);
    const test::Rendered path = test::RenderSceneText("bssrdf", "path", scene);
    const test::Rendered whitted = test::RenderSceneText(
        "bssrdf", "whitted", scene, test::SizedSettings(32, 32, 16, "whitted"));
    EXPECT_EQ(whitted.stats.rays.subsurface, 0u);
    EXPECT_FALSE(whitted.scene.features.effects.Has(Effect::Subsurface));
    bool warned = false;
    for (const Warning &w : whitted.warnings)
        warned |= w.message.find("interface alone") != std::string::npos;
    EXPECT_TRUE(warned);
    // Glass shows the light's reflection only: far darker than the lit, scattering sphere.
    EXPECT_LT(test::MeanValue(whitted.image), 0.5 * test::MeanValue(path.image));
}

// A grey "subsurface" given by pbrt-v4's reflectance and mean free path, with a rough
// interface: pbrt-v4 renders it under volpath but not under path (whose interface alone it
// renders). Grey, so that pbrt-v4's spectra and Prism's RGB agree.
TEST(Subsurface, PbrtV4FilesRenderAsPbrtV4) {
    auto scene = [](const char *integrator) {
        return std::string(
                   "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
                   "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32\n"
                   "Sampler \"independent\" \"integer pixelsamples\" 1024\nIntegrator \"") +
               integrator +
               "\" \"integer maxdepth\" 8\nWorldBegin\nAttributeBegin\n"
               "AreaLightSource \"diffuse\" \"rgb L\" [10 10 10]\n"
               "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
               "  \"point3 P\" [-1 2 -1  1 2 -1  1 2 1  -1 2 1]\nAttributeEnd\n"
               "Material \"subsurface\" \"rgb reflectance\" [0.6 0.6 0.6] \"rgb mfp\" [0.1 0.1 "
               "0.1] "
               "\"float roughness\" 0.1\nShape \"sphere\" \"float radius\" 0.8\n";
    };
    const test::Rendered vol = test::RenderSceneText("bssrdf", "v4vol", scene("volpath"));
    // pbrt-v4's mean at 4096 spp: 0.11537 0.11534 0.11536.
    EXPECT_NEAR(test::MeanValue(vol.image), 0.11536, 0.03 * 0.11536);
    EXPECT_GT(vol.stats.rays.subsurface, 0u);
    const test::Rendered path = test::RenderSceneText("bssrdf", "v4path", scene("path"));
    EXPECT_EQ(path.stats.rays.subsurface, 0u);
    bool warned = false;
    for (const Warning &w : path.warnings)
        warned |= w.message.find("as pbrt-v4 does") != std::string::npos;
    EXPECT_TRUE(warned);
    EXPECT_LT(test::MeanValue(path.image), 0.5 * test::MeanValue(vol.image));
}

// Coefficients and distances at the ends of float's range: probes of enormous or vanishing
// radii, infinite or zero coefficients from a mean free path of 0 or 1e38. Every pixel stays
// finite and nothing aborts.
TEST(Subsurface, ExtremeCoefficientsRenderFiniteImages) {
    for (const char *material :
         {"Material \"subsurface\" \"rgb sigma_a\" [1e-30 1e-30 1e-30] \"rgb sigma_s\" [1e-30 "
          "1e-30 1e-30]",
          "Material \"subsurface\" \"rgb sigma_a\" [0 0 0] \"rgb sigma_s\" [1e-38 0 1e38]",
          "Material \"subsurface\" \"float scale\" 1e30 \"float g\" 0.99 \"float eta\" 10",
          "Material \"kdsubsurface\" \"rgb Kd\" [5 -1 0.5] \"rgb mfp\" [0 1e-38 1e38]",
          "Material \"disney\" \"rgb scatterdistance\" [1e30 1e-30 1e38]"}) {
        const test::Rendered r =
            test::RenderSceneText("bssrdf", "extreme", test::LitSphereScene(material, 4));
        for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v)) << material;
    }
}

TEST(Subsurface, ReadsItsParametersAndRefusesBadOnes) {
    Diagnostics diag;
    RenderScene keep;
    const Material &m = test::BuildSphereMaterial(
        "Material \"subsurface\" \"string name\" \"Skin1\" \"float g\" 0.4\n", diag, keep);
    ASSERT_TRUE(m.HasSubsurface());
    SeparableBssrdf b;
    ASSERT_TRUE(m.Model().SubsurfaceAt(TextureContext{}, Vec3f(0, 0, 0), Vec3f(0, 0, 1),
                                       Vec3f(1, 0, 0), &b));
    EXPECT_FLOAT_EQ(b.Eta(), 1.33f);
    EXPECT_TRUE(m.MayTransmit());
    // The measured medium's coefficients are reduced ones: g is warned and set to 0.
    EXPECT_EQ(diag.Count(), size_t(1));
    const Material &u = test::BuildSphereMaterial(
        "Material \"subsurface\" \"string name\" \"Unobtainium\"\n", diag, keep);
    ASSERT_TRUE(u.HasSubsurface());
    EXPECT_EQ(diag.Count(), size_t(2));
    test::ExpectMaterialErrors(
        "subsurface", {"\"float g\" 1", "\"float eta\" 0.5", "\"float scale\" -1"}, "out of range");
}

}  // namespace
}  // namespace prism
