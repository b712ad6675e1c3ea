// glTF 2.0 metallic-roughness material (render/gltf_material.h): values against the
// specification's Appendix B formulas written out again here, white furnace, reciprocity,
// importance sampling of the glossy lobes, the polished limit (a mirror) and
// KHR_texture_transform.
#include "render/gltf_material.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/gltf_sampling.h"
#include "render/material.h"

namespace prism {
namespace {

constexpr double kPi = 3.14159265358979323846;

TexturePtr Const(RGB v) { return std::make_shared<ConstantTexture>(v); }

struct Params {
    RGB base{1, 1, 1};
    float metallic = 0, roughness = 0.5f;
    float ior = 1.5f, transmission = 0, specular = 1, clearcoat = 0, clearcoatRoughness = 0;
};

Material Gltf(const Params &p) {
    GltfMaterialParams g;
    g.baseColor = Const(p.base);
    g.metallic = p.metallic;
    g.roughness = p.roughness;
    g.ior = p.ior;
    g.transmission = p.transmission;
    g.specular = p.specular;
    g.clearcoat = p.clearcoat;
    g.clearcoatRoughness = p.clearcoatRoughness;
    return Material(std::make_shared<GltfMaterial>(std::move(g)), "gltf");
}

BSDF FlatBSDF(const Material &m) {
    SurfaceInteraction si;
    si.n = si.ns = {0, 0, 1};
    si.dpdu = {1, 0, 0};
    return m.GetBSDF(si, {});
}

Vec3f Dir(double theta, double phi) {
    return Vec3f(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                 float(std::cos(theta)));
}

// The specification's Appendix B, in double precision, for one colour channel.
double SpecBrdf(double base, double metallic, double roughness, const Vec3f &v, const Vec3f &l) {
    const double a = roughness * roughness, a2 = a * a;
    double hx = v.x + l.x, hy = v.y + l.y, hz = v.z + l.z;
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= hl, hy /= hl, hz /= hl;
    const double NdotL = l.z, NdotV = v.z, NdotH = hz;
    const double VdotH = std::abs(v.x * hx + v.y * hy + v.z * hz);
    if (NdotL <= 0 || NdotV <= 0) return 0;
    const double d = NdotH * NdotH * (a2 - 1) + 1;
    const double D = a2 / (kPi * d * d);
    const double V = 0.5 / (NdotL * std::sqrt(NdotV * NdotV * (1 - a2) + a2) +
                            NdotV * std::sqrt(NdotL * NdotL * (1 - a2) + a2));
    const double specular_brdf = V * D;
    const double diffuse = base / kPi;
    const double w = std::pow(1 - VdotH, 5);
    const double conductor_fresnel = (base + (1 - base) * w) * specular_brdf;
    const double fr = 0.04 + (1 - 0.04) * w;
    const double fresnel_mix = (1 - fr) * diffuse + fr * specular_brdf;
    return (1 - metallic) * fresnel_mix + metallic * conductor_fresnel;
}

TEST(GltfMaterial, MatchesTheSpecificationFormulas) {
    for (float metallic : {0.f, 0.3f, 1.f})
        for (float roughness : {0.3f, 0.6f, 1.f})
            for (double to : {0.1, 0.7, 1.3})
                for (double ti : {0.2, 0.9, 1.45})
                    for (double phi : {0.0, 1.0, 3.0}) {
                        Params p;
                        p.base = RGB(0.8f, 0.5f, 0.2f);
                        p.metallic = metallic;
                        p.roughness = roughness;
                        BSDF b = FlatBSDF(Gltf(p));
                        Vec3f wo = Dir(to, 0), wi = Dir(ti, phi);
                        RGB f = b.f(wo, wi);
                        for (int c = 0; c < 3; ++c) {
                            double ref = SpecBrdf(p.base[c], metallic, roughness, wo, wi);
                            EXPECT_NEAR(f[c], ref, 1e-4 + 2e-4 * ref)
                                << "m " << metallic << " r " << roughness << " to " << to << " ti "
                                << ti << " phi " << phi << " c " << c;
                        }
                    }
}

// ∫ f cos dωi over the sphere on a (theta, phi) grid, for one channel.
double Albedo(const BSDF &b, const Vec3f &wo, int n = 600, bool glossyOnly = false) {
    double sum = 0;
    const double dt = kPi / n, dp = 2 * kPi / n;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt;
        for (int j = 0; j < n; ++j) {
            Vec3f wi = Dir(t, (j + 0.5) * dp);
            RGB f = glossyOnly ? b.f(wo, wi) - b.fDiffuse(wo, wi) : b.f(wo, wi);
            sum += f.g * std::abs(std::cos(t)) * std::sin(t) * dt * dp;
        }
    }
    return sum;
}

TEST(GltfMaterial, WhiteFurnace) {
    for (float metallic : {0.f, 1.f})
        for (float roughness : {0.3f, 0.5f, 0.75f, 1.f})
            for (double to : {0.0, 0.8, 1.3}) {
                Params p;
                p.metallic = metallic;
                p.roughness = roughness;
                BSDF b = FlatBSDF(Gltf(p));
                double a = Albedo(b, Dir(to, 0));
                SCOPED_TRACE(testing::Message() << "metallic " << metallic << " roughness "
                                                << roughness << " theta " << to << " albedo " << a);
                if (metallic == 1) {
                    EXPECT_LE(a, 1.005);
                    // A white conductor loses only single-scattering energy: little for smooth
                    // lobes, about 70% for alpha = 1 at normal incidence (0.307, integrated
                    // independently from the specification's D and V).
                    double lower = roughness <= 0.3f   ? 0.93
                                   : roughness <= 0.5f ? 0.82
                                   : roughness < 1     ? 0.55
                                                       : 0.29;
                    EXPECT_GE(a, lower);
                } else {
                    // The specification's fresnel_mix weights the diffuse base by 1 - F(v·h),
                    // which is not energy conserving toward grazing angles: up to 1.14 at 75°
                    // for roughness 0.3 (the same with SpecBrdf above). Conserving up to 60°.
                    EXPECT_LE(a, to < 1.1 ? 1.005 : 1.15);
                    EXPECT_GE(a, 0.6);  // the white diffuse base takes what is not reflected
                }
            }
}

TEST(GltfMaterial, Reciprocity) {
    Params p;
    p.base = RGB(0.9f, 0.4f, 0.1f);
    p.metallic = 0.4f;
    p.roughness = 0.45f;
    p.clearcoat = 0.7f;
    p.clearcoatRoughness = 0.3f;
    p.transmission = 0.5f;
    p.specular = 0.8f;
    BSDF b = FlatBSDF(Gltf(p));
    for (double to : {0.2, 0.8, 1.4})
        for (double ti : {0.1, 0.6, 1.2, 1.9, 2.8})
            for (double phi : {0.3, 2.0, 4.0}) {
                Vec3f wo = Dir(to, 0), wi = Dir(ti, phi);
                RGB a = b.f(wo, wi), c = b.f(wi, wo);
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], c[k], 1e-5f + 1e-4f * a[k]);
            }
}

// The glossy rays' weights f·|cos|/pdf average to the integral of the glossy lobes.
double SampledGlossyAlbedo(const BSDF &b, const Vec3f &wo, int n = 300) {
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec2f u(float((i + 0.5) / n), float((j + 0.5) / n));
            float uc = float(((i * 7919 + j * 104729) % 1000) + 0.5) / 1000;
            for (int part = 0; part < b.NumParts(); ++part) {
                Vec3f wi;
                RGB w;
                if (b.SampleGlossy(part, wo, u, uc, &wi, &w)) sum += w.g;
            }
        }
    return sum / (double(n) * n);
}

// A material of the sampling tests: a warm base colour, clearcoat roughness 0.5.
struct Case {
    float metallic, roughness, transmission, clearcoat;
};
BSDF CaseBSDF(const Case &c) {
    Params p;
    p.base = RGB(0.9f, 0.7f, 0.5f);
    p.metallic = c.metallic;
    p.roughness = c.roughness;
    p.transmission = c.transmission;
    p.clearcoat = c.clearcoat;
    p.clearcoatRoughness = 0.5f;
    return FlatBSDF(Gltf(p));
}

TEST(GltfMaterial, ImportanceSamplingMatchesTheIntegral) {
    for (Case c : {Case{1, 0.3f, 0, 0}, Case{1, 0.8f, 0, 0}, Case{0, 0.5f, 0, 0},
                   Case{0, 0.6f, 1, 0}, Case{0.5f, 0.4f, 0, 1}})
        for (double to : {0.3, 1.1}) {
            BSDF b = CaseBSDF(c);
            Vec3f wo = Dir(to, 0);
            double integral = Albedo(b, wo, 800, /*glossyOnly=*/true);
            double sampled = SampledGlossyAlbedo(b, wo);
            EXPECT_NEAR(sampled, integral, 0.01 + 0.02 * integral)
                << "metallic " << c.metallic << " roughness " << c.roughness << " transmission "
                << c.transmission << " clearcoat " << c.clearcoat << " theta " << to;
        }
}

// The full sampling (diffuse and glossy lobes, GltfSampleF): f·|cos|/pdf averages to the
// integrated albedo, and the density it reports is the one GltfPdf gives.
TEST(GltfMaterial, FullSamplingMatchesTheIntegral) {
    for (Case c : {Case{0, 0.5f, 0, 0}, Case{0.5f, 0.3f, 0, 0}, Case{1, 0.7f, 0, 0},
                   Case{0, 0.6f, 0.5f, 0}, Case{0.2f, 0.4f, 0, 1}})
        for (double to : {0.3, 1.0}) {
            BSDF b = CaseBSDF(c);
            Vec3f wo = Dir(to, 0);
            double integral = Albedo(b, wo, 800);
            const int n = 256;
            double sum = 0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    Vec2f u(float((i + 0.5) / n), float((j + 0.5) / n));
                    float uc = float(((i * 7919 + j * 104729) % 4096) + 0.5) / 4096;
                    Vec3f wi;
                    float pdf;
                    RGB f = GltfSampleF(b, wo, u, uc, &wi, &pdf);
                    if (!(pdf > 0)) continue;
                    EXPECT_NEAR(pdf, GltfPdf(b, wo, wi), 1e-3f * pdf);
                    sum += f.g * std::abs(wi.z) / pdf;
                }
            EXPECT_NEAR(sum / (double(n) * n), integral, 0.01 + 0.02 * integral)
                << "metallic " << c.metallic << " roughness " << c.roughness << " transmission "
                << c.transmission << " clearcoat " << c.clearcoat << " theta " << to;
        }
}

// The density integrates to at most 1 over the sphere (less where a sample is rejected).
TEST(GltfMaterial, PdfIsNormalized) {
    Params p;
    p.metallic = 0.3f;
    p.roughness = 0.6f;
    p.transmission = 0.4f;
    BSDF b = FlatBSDF(Gltf(p));
    Vec3f wo = Dir(0.7, 0);
    const int n = 600;
    double sum = 0;
    const double dt = kPi / n, dp = 2 * kPi / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double t = (i + 0.5) * dt;
            sum += GltfPdf(b, wo, Dir(t, (j + 0.5) * dp)) * std::sin(t) * dt * dp;
        }
    EXPECT_LE(sum, 1.01);
    EXPECT_GE(sum, 0.9);
}

TEST(GltfMaterial, PolishedMetalIsAMirror) {
    Params p;
    p.base = RGB(0.9f, 0.6f, 0.3f);
    p.metallic = 1;
    p.roughness = 0;
    BSDF b = FlatBSDF(Gltf(p));
    EXPECT_FALSE(b.HasNonSpecular());
    for (double t : {0.0, 0.5, 1.0, 1.4}) {
        Vec3f wo = Dir(t, 0.7), wi;
        RGB w;
        ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wi, &w));
        EXPECT_NEAR(wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(wi.y, -wo.y, 1e-6f);
        EXPECT_NEAR(wi.z, wo.z, 1e-6f);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(w[c], p.base[c] + (1 - p.base[c]) * std::pow(1 - std::cos(t), 5), 1e-5);
        EXPECT_FALSE(b.SampleSpecularTransmission(0, wo, &wi, &w));
    }
    Material m = Gltf(p);
    EXPECT_TRUE(m.MayReflectSpecularly());
}

TEST(GltfMaterial, RoughnessToZeroConvergesToTheMirror) {
    // Just above the polished threshold the glossy lobe's samples cluster at the mirror
    // direction and carry the mirror's Fresnel weight.
    Params p;
    p.base = RGB(0.9f, 0.6f, 0.3f);
    p.metallic = 1;
    p.roughness = 0.033f;  // alpha 0.00109
    BSDF b = FlatBSDF(Gltf(p));
    ASSERT_TRUE(b.HasGlossy());
    Vec3f wo = Dir(0.6, 0);
    Vec3f mirror(-wo.x, -wo.y, wo.z);
    double sum = 0, cosSum = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec3f wi;
            RGB w;
            if (!b.SampleGlossy(0, wo, Vec2f((i + 0.5f) / n, (j + 0.5f) / n), 0.5f, &wi, &w))
                continue;
            sum += w.r;
            cosSum += Dot(wi, mirror);
        }
    double F = 0.9 + 0.1 * std::pow(1 - std::cos(0.6), 5);
    EXPECT_NEAR(sum / (n * n), F, 0.02);
    EXPECT_GT(cosSum / (n * n), 0.995);
}

TEST(GltfMaterial, SpecularAndIorSetTheDielectricF0) {
    EXPECT_NEAR(GltfDielectricF0(1.5f, 1, RGB(1)).g, 0.04f, 1e-6f);
    EXPECT_NEAR(GltfDielectricF0(2.f, 1, RGB(1)).g, 1.f / 9, 1e-6f);
    RGB f0 = GltfDielectricF0(1.5f, 0.5f, RGB(1, 0.5f, 0));
    EXPECT_NEAR(f0.r, 0.02f, 1e-6f);
    EXPECT_NEAR(f0.g, 0.01f, 1e-6f);
    EXPECT_NEAR(f0.b, 0.f, 1e-6f);
    // specular 0 turns the specular layer of a dielectric off: only the diffuse base is left.
    Params p;
    p.specular = 0;
    p.base = RGB(0.5f);
    BSDF b = FlatBSDF(Gltf(p));
    Vec3f wo = Dir(0.4, 0), wi = Dir(0.9, 2.0);
    EXPECT_NEAR(b.f(wo, wi).g, 0.5 / kPi, 1e-6);
}

TEST(GltfMaterial, ThinTransmissionGoesStraightThrough) {
    Params p;
    p.base = RGB(0.8f);
    p.transmission = 1;
    p.roughness = 0;
    BSDF b = FlatBSDF(Gltf(p));
    Vec3f wo = Dir(0.5, 0.2), wi;
    RGB w;
    ASSERT_TRUE(b.SampleSpecularTransmission(0, wo, &wi, &w));
    EXPECT_NEAR(wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(wi.z, -wo.z, 1e-6f);
    EXPECT_NEAR(w.g, 0.8 * (1 - (0.04 + 0.96 * std::pow(1 - std::cos(0.5), 5))), 1e-5);
    EXPECT_TRUE(Gltf(p).MayTransmit());
}

TEST(GltfMaterial, TextureTransform) {
    // KHR_texture_transform in glTF's coordinates (origin top-left): uv' = T R S uv.
    auto gltfUV = [](Vec2f prism) { return Vec2f(prism.x, 1 - prism.y); };
    const float rot = 0.6f;
    UVTransformTexture t(Const(RGB(1)), Vec2f(0.1f, 0.2f), rot, Vec2f(2, 3));
    for (Vec2f uv : {Vec2f(0, 0), Vec2f(0.25f, 0.75f), Vec2f(1, 0.5f)}) {
        Vec2f g = gltfUV(uv);
        double su = 2 * g.x, sv = 3 * g.y;
        double x = std::cos(rot) * su + std::sin(rot) * sv + 0.1;
        double y = -std::sin(rot) * su + std::cos(rot) * sv + 0.2;
        Vec2f out = gltfUV(t.Map(uv));
        EXPECT_NEAR(out.x, x, 1e-5);
        EXPECT_NEAR(out.y, y, 1e-5);
    }
    // The identity leaves uv alone.
    UVTransformTexture id(Const(RGB(1)), Vec2f(0, 0), 0, Vec2f(1, 1));
    EXPECT_NEAR(id.Map(Vec2f(0.3f, 0.8f)).x, 0.3f, 1e-6f);
    EXPECT_NEAR(id.Map(Vec2f(0.3f, 0.8f)).y, 0.8f, 1e-6f);
}

}  // namespace
}  // namespace prism
