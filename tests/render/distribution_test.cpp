// The distribution integrator (Integrator "distribution"): glossy sampling against numerically
// integrated albedos, a glossy sphere under a uniform environment, roughness -> 0 converging
// to the mirror and smooth glass, the glossy-ray counter, and Whitted left as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "image/image_compare.h"
#include "image/image_io.h"
#include "render/bsdf.h"
#include "render/distribution_integrator.h"
#include "render/materials.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

// ∫ f_glossy |cos θi| dωi over the sphere by the midpoint rule in (θ, φ). Transmission
// through a microfacet that faces away from wo is left out: pbrt-v3's MicrofacetTransmission::f
// counts it, but neither its sampling nor Prism's (both of the normals visible from wo) can
// reach it, and pbrt-v4 drops it from f. It matters only at grazing angles on rough glass.
RGB NumericAlbedo(const BSDF &b, const Vec3f &wo, int nTheta = 1000, int nPhi = 1000) {
    const BxDFLobes &l = b.Part(0);
    auto facesWo = [&](const Vec3f &wi) {
        float eta = wo.z > 0 ? l.glossyEta : 1 / l.glossyEta;
        Vec3f wh = Normalize(wo + wi * eta);
        if (wh.z < 0) wh = -wh;
        return Dot(wo, wh) * wo.z > 0;
    };
    double sum[3] = {0, 0, 0};
    const double dTheta = Pi / nTheta, dPhi = 2 * Pi / nPhi;
    for (int i = 0; i < nTheta; ++i) {
        double theta = (i + 0.5) * dTheta, st = std::sin(theta), ct = std::cos(theta);
        for (int j = 0; j < nPhi; ++j) {
            double phi = (j + 0.5) * dPhi;
            Vec3f wi(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
            bool reflect = wi.z * wo.z > 0;
            if (!reflect && !facesWo(wi)) continue;
            RGB f = l.fGlossy(wo, wi, reflect);
            double w = std::abs(ct) * st * dTheta * dPhi;
            for (int c = 0; c < 3; ++c) sum[c] += double(f[c]) * w;
        }
    }
    return RGB(float(sum[0]), float(sum[1]), float(sum[2]));
}

// The mean weight of n x n stratified SampleGlossy samples (what the integrator averages).
RGB SampledAlbedo(const BSDF &b, const Vec3f &wo, int n = 300) {
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < n * n; ++i) {
        Vec2f u((float(i % n) + HashFloat(uint32_t(i), 1)) / float(n),
                (float(i / n) + HashFloat(uint32_t(i), 2)) / float(n));
        Vec3f wi;
        RGB w;
        if (!b.SampleGlossy(0, wo, u, HashFloat(uint32_t(i), 3), &wi, &w)) continue;
        for (int c = 0; c < 3; ++c) sum[c] += double(w[c]);
    }
    double inv = 1.0 / (double(n) * n);
    return RGB(float(sum[0] * inv), float(sum[1] * inv), float(sum[2] * inv));
}

BSDF FlatBSDF() {
    BSDF b;
    b.SetFrame(Vec3f(0, 0, 1), Vec3f(1, 0, 0), Vec3f(0, 0, 1));
    return b;
}

Fresnel Conductor() {
    Fresnel f;
    f.kind = FresnelKind::Conductor;
    f.eta = RGB(0.2f, 0.92f, 1.1f);
    f.k = RGB(3.9f, 2.45f, 2.14f);
    return f;
}

void ExpectWithin(const RGB &got, const RGB &want, double rel, const std::string &what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], rel * std::abs(want[c]) + 1e-5) << what << " channel " << c;
}

TEST(GlossySampling, WeightsAverageToTheNumericAlbedo) {
    const Vec3f wos[] = {Normalize(Vec3f(0, 0, 1)), Normalize(Vec3f(0.5f, 0.2f, 0.8f)),
                         Normalize(Vec3f(-0.8f, 0.1f, 0.35f))};
    for (float alpha : {0.1f, 0.3f, 0.6f}) {
        for (const Vec3f &wo : wos) {
            std::string at = " alpha " + std::to_string(alpha) + " wo.z " + std::to_string(wo.z);
            {  // rough metal
                BSDF b = FlatBSDF();
                BxDFLobes &l = b.AddPart();
                l.ks = RGB(1);
                l.alphaX = l.alphaY = alpha;
                l.glossyFresnel = Conductor();
                ExpectWithin(SampledAlbedo(b, wo), NumericAlbedo(b, wo), 0.01, "metal" + at);
            }
            {  // anisotropic metal
                BSDF b = FlatBSDF();
                BxDFLobes &l = b.AddPart();
                l.ks = RGB(1);
                l.alphaX = alpha;
                l.alphaY = 0.5f * alpha + 0.1f;
                l.glossyFresnel = Conductor();
                ExpectWithin(SampledAlbedo(b, wo), NumericAlbedo(b, wo), 0.01, "aniso" + at);
            }
            {  // plastic's coat (pbrt-v3's FresnelDielectric(1.5, 1))
                BSDF b = FlatBSDF();
                BxDFLobes &l = b.AddPart();
                l.kd = RGB(0.5f);
                l.ks = RGB(0.3f, 0.4f, 0.5f);
                l.alphaX = l.alphaY = alpha;
                l.glossyFresnel = Dielectric(1.5f, 1.f);
                ExpectWithin(SampledAlbedo(b, wo), NumericAlbedo(b, wo), 0.01, "plastic" + at);
            }
            {  // substrate's glossy coat
                BSDF b = FlatBSDF();
                BxDFLobes &l = b.AddPart();
                l.fresnelBlend = true;
                l.blendRd = RGB(0.5f);
                l.blendRs = RGB(0.05f, 0.1f, 0.2f);
                l.alphaX = l.alphaY = alpha;
                ExpectWithin(SampledAlbedo(b, wo), NumericAlbedo(b, wo), 0.01, "substrate" + at);
            }
            // Rough glass, from outside and from inside: reflection and transmission.
            for (float side : {1.f, -1.f}) {
                BSDF b = FlatBSDF();
                BxDFLobes &l = b.AddPart();
                l.kr = l.kt = RGB(1);
                l.eta = 1.5f;
                l.specularFresnel = Dielectric(1.f, 1.5f);
                l.roughAlphaX = l.roughAlphaY = alpha;
                ASSERT_TRUE(b.MakeRoughSpecularGlossy());
                Vec3f w(wo.x, wo.y, wo.z * side);
                ExpectWithin(SampledAlbedo(b, w), NumericAlbedo(b, w), 0.01,
                             std::string(side > 0 ? "glass outside" : "glass inside") + at);
            }
        }
    }
}

TEST(GlossySampling, SmoothLimitIsTheMirrorDirection) {
    BSDF b = FlatBSDF();
    BxDFLobes &l = b.AddPart();
    l.ks = RGB(1);
    l.alphaX = l.alphaY = 1e-4f;
    l.glossyFresnel = Conductor();
    Vec3f wo = Normalize(Vec3f(0.3f, -0.2f, 0.9f));
    Vec3f wi;
    RGB w;
    ASSERT_TRUE(b.SampleGlossy(0, wo, Vec2f(0.37f, 0.81f), 0.5f, &wi, &w));
    EXPECT_NEAR(wi.x, -wo.x, 1e-3);
    EXPECT_NEAR(wi.y, -wo.y, 1e-3);
    EXPECT_NEAR(wi.z, wo.z, 1e-3);
    // The weight tends to the conductor Fresnel term (what the delta mirror uses).
    RGB F = Conductor().Evaluate(wo.z);
    ExpectWithin(w, F, 1e-3, "weight");
}

Rendered RenderText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return RenderSceneText("prism_distribution", name, text, opts);
}

// A sphere seen head-on through a 0.2-degree field of view: every camera ray meets it within
// a few thousandths of normal incidence.
std::string CentreOfSphere(const std::string &material, const std::string &integrator) {
    return "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 0.2 ]\n"
           "Film \"image\" \"integer xresolution\" [ 2 ] \"integer yresolution\" [ 2 ]\n"
           "Sampler \"stratified\" \"integer xsamples\" [ 16 ] \"integer ysamples\" [ 16 ]\n"
           "PixelFilter \"box\"\nIntegrator \"" +
           integrator +
           "\" \"integer maxdepth\" [ 5 ]\nWorldBegin\n"
           "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n" +
           material + "\nShape \"sphere\" \"float radius\" [ 1 ]\nWorldEnd\n";
}

TEST(DistributionIntegrator, GlossySphereUnderUniformSkyReflectsItsAlbedo) {
    // Rough copper: alpha 0.3 (area lights would be light-sampled) and 0.08 (glossy rays bring
    // every light back): the sky reaches the sphere through glossy rays either way.
    for (float alpha : {0.3f, 0.08f}) {
        std::string mat =
            "Material \"metal\" \"rgb eta\" [ 0.2 0.92 1.1 ] \"rgb k\" [ 3.9 2.45 2.14 ] "
            "\"float roughness\" [ " +
            std::to_string(alpha) + " ] \"bool remaproughness\" \"false\"";
        Rendered r = RenderText("sky_metal", CentreOfSphere(mat, "distribution"));
        BSDF b = FlatBSDF();
        BxDFLobes &l = b.AddPart();
        l.ks = RGB(1);
        l.alphaX = l.alphaY = alpha;
        l.glossyFresnel = Conductor();
        RGB albedo = NumericAlbedo(b, Vec3f(0, 0, 1));
        ExpectWithin(MeanRGB(r.image), albedo, 0.01, "alpha " + std::to_string(alpha));
        // DefaultGlossySamples per camera ray, less those that fall below the surface.
        EXPECT_LE(r.stats.rays.glossy, 4u * 256u * uint64_t(DefaultGlossySamples));
        EXPECT_GT(r.stats.rays.glossy, 4u * 256u * uint64_t(DefaultGlossySamples) * 9 / 10);
        EXPECT_EQ(r.stats.rays.shadow, 0u);  // the sky reaches metal through glossy rays only
    }
    // Rough plastic with a black base: only its glossy coat reflects.
    std::string mat =
        "Material \"plastic\" \"rgb Kd\" [ 0 0 0 ] \"rgb Ks\" [ 1 1 1 ] \"float roughness\" "
        "[ 0.2 ] \"bool remaproughness\" \"false\"";
    Rendered r = RenderText("sky_plastic", CentreOfSphere(mat, "distribution"));
    BSDF b = FlatBSDF();
    BxDFLobes &l = b.AddPart();
    l.ks = RGB(1);
    l.alphaX = l.alphaY = 0.2f;
    l.glossyFresnel = Dielectric(1.5f, 1.f);
    ExpectWithin(MeanRGB(r.image), NumericAlbedo(b, Vec3f(0, 0, 1)), 0.01, "plastic");
}

// A checkered floor, a blue ball and a sphere of `material`, under an area light and a sky (no
// delta light: its glossy highlight would tend to a point of infinite radiance that a mirror
// cannot show).
std::string ReflectingScene(const std::string &material) {
    return R"(LookAt 0 1.5 -5  0 0.8 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "image" "integer xresolution" [ 48 ] "integer yresolution" [ 32 ]
Sampler "stratified" "integer xsamples" [ 4 ] "integer ysamples" [ 4 ]
PixelFilter "box"
Integrator "distribution" "integer maxdepth" [ 5 ] "integer glossysamples" [ 16 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
Translate -2 4 -2
Shape "sphere" "float radius" [ 0.7 ]
AttributeEnd
LightSource "infinite" "rgb L" [ 0.3 0.35 0.5 ]
Texture "checks" "spectrum" "checkerboard" "rgb tex1" [ 0.9 0.9 0.9 ] "rgb tex2" [ 0.1 0.1 0.1 ]
Material "matte" "texture Kd" "checks"
Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ]
  "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
  "point2 uv" [ -20 -20  20 -20  20 20  -20 20 ]
AttributeBegin
Material "matte" "rgb Kd" [ 0.1 0.2 0.8 ]
Translate 1.2 0.5 1.5
Shape "sphere" "float radius" [ 0.5 ]
AttributeEnd
AttributeBegin
)" + material +
           R"(
Translate 0 0.8 0
Shape "sphere" "float radius" [ 0.8 ]
AttributeEnd
WorldEnd
)";
}

TEST(DistributionIntegrator, RoughnessToZeroConvergesToTheMirrorImage) {
    // Polished metal (alpha 0: a delta conductor) and smooth glass are the limits.
    struct Case {
        std::string smooth, rough;  // rough: "%" stands for the roughness (alpha)
    };
    const Case cases[] = {
        {"Material \"metal\" \"float roughness\" [ 0 ] \"bool remaproughness\" \"false\"",
         "Material \"metal\" \"float roughness\" [ % ] \"bool remaproughness\" \"false\""},
        {"Material \"glass\"",
         "Material \"glass\" \"float roughness\" [ % ] \"bool remaproughness\" \"false\""},
    };
    for (const Case &c : cases) {
        Image mirror = RenderText("smooth", ReflectingScene(c.smooth)).image;
        double last = 1e9, first = 0;
        for (const char *alpha : {"0.4", "0.15", "0.05", "0.021"}) {
            std::string m = c.rough;
            m.replace(m.find('%'), 1, alpha);
            Rendered r = RenderText("rough", ReflectingScene(m));
            EXPECT_GT(r.stats.rays.glossy, 0u);
            double rmse = CompareImages(r.image, mirror, 0.05f).rmse;
            EXPECT_LT(rmse, last) << c.rough << " alpha " << alpha;
            if (last > 1e8) first = rmse;
            last = rmse;
        }
        // The difference falls about in proportion to alpha (0.088 -> 0.015 for the metal,
        // 0.061 -> 0.012 for the glass, when written).
        EXPECT_LT(last, 0.02) << c.rough;
        EXPECT_LT(last, 0.25 * first) << c.rough;
    }
}

// Glossy rays are stratified over the pixel's samples like the light samples: the error
// falls at least as fast as with independent samples (1/sqrt(spp)).
TEST(DistributionIntegrator, GlossyNoiseFallsWithSamplesPerPixel) {
    std::string scene = ReflectingScene(
        "Material \"metal\" \"float roughness\" [ 0.15 ] \"bool remaproughness\" \"false\"");
    auto render = [&](int spp) {
        BuildSettings opts;
        opts.spp = spp;
        opts.resolution = {24, 16};
        return RenderText("noise", scene, opts).image;
    };
    Image ref = render(1024);
    double e4 = CompareImages(render(4), ref, 1).rmse, e64 = CompareImages(render(64), ref, 1).rmse;
    EXPECT_LT(e64, e4 / 4) << "spp 4: " << e4 << ", spp 64: " << e64;
}

TEST(DistributionIntegrator, NoGlossyMaterialTracesNoGlossyRaysAndMatchesWhitted) {
    std::string scene = ReflectingScene("Material \"glass\"");
    BuildSettings whitted;
    whitted.integrator = "whitted";
    Rendered d = RenderText("noglossy", scene), w = RenderText("noglossy", scene, whitted);
    EXPECT_EQ(d.stats.rays.glossy, 0u);
    EXPECT_GT(d.stats.rays.refraction, 0u);
    EXPECT_TRUE(d.image.pixels == w.image.pixels);
}

TEST(DistributionIntegrator, WhittedTracesNoGlossyRays) {
    std::string scene = ReflectingScene("Material \"metal\" \"float roughness\" [ 0.1 ]");
    BuildSettings whitted;
    whitted.integrator = "whitted";
    EXPECT_EQ(RenderText("rough", scene, whitted).stats.rays.glossy, 0u);
    BuildSettings few;
    few.glossySamples = 2;  // --glossy-samples overrides "glossysamples"
    Rendered d = RenderText("rough", scene, few);
    EXPECT_GT(d.stats.rays.glossy, 0u);
    // 16 rays per first glossy hit, less those that fall below the surface.
    uint64_t all = RenderText("rough", scene).stats.rays.glossy;
    EXPECT_GT(d.stats.rays.glossy * 8, all * 9 / 10);
    EXPECT_LT(d.stats.rays.glossy * 8, all * 11 / 10);
}

// Whitted renders of glossy materials are exactly what they were before the distribution
// integrator existed: the golden image was rendered by the commit before it (4 spp). Its
// checkerboard was point-sampled then: texture filtering (--texture-filter none) stays off.
TEST(DistributionIntegrator, WhittedRenderOfGlossySceneIsUnchanged) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Source + "/scenes/glossy.pbrt", diag);
    BuildSettings opts;
    opts.integrator = "whitted";
    opts.textureFilter = "none";
    opts.resolution = {48, 30};
    RenderScene scene = BuildRenderScene(desc, opts, diag);
    RenderStats stats;
    Image img = Render(scene, &stats);
    EXPECT_EQ(stats.rays.glossy, 0u);
    Image golden = ReadImage(Source + "/tests/golden/glossy_whitted_48x30.exr");
    ImageDiff d = CompareImages(img, golden, 1e-4f);
    // Bit-identical on the machine that made it; the bound only absorbs other compilers/ISAs.
    EXPECT_LT(d.maxAbs, 1e-4);
    EXPECT_EQ(d.badPixels, 0);
}

// Rough glass keeps its roughness for the distribution integrator: pbrt-v3's "glass" remaps
// uroughness/vroughness with RoughnessToAlpha (smooth only when both are 0), pbrt-v4's
// "dielectric" remaps roughness to sqrt(roughness).
TEST(DistributionIntegrator, RoughGlassAlphas) {
    fs::path dir = fs::path(::testing::TempDir()) / "prism_distribution";
    fs::create_directories(dir);
    std::ofstream(dir / "glass.pbrt")
        << "Integrator \"distribution\"\nCamera \"perspective\"\nWorldBegin\n"
           "Material \"glass\" \"float uroughness\" [ 0.1 ] \"float vroughness\" [ 0 ]\n"
           "Shape \"sphere\"\n"
           "Material \"dielectric\" \"float roughness\" [ 0.04 ]\nShape \"sphere\"\n"
           "Material \"glass\"\nShape \"sphere\"\nWorldEnd\n";
    Diagnostics diag(false);
    SceneDescription desc = LoadScene((dir / "glass.pbrt").string(), diag);
    RenderScene scene = BuildRenderScene(desc, BuildSettings{}, diag);
    EXPECT_STREQ(scene.IntegratorName(), "distribution");
    SurfaceInteraction si;
    si.n = si.ns = Vec3f(0, 0, 1);
    si.dpdu = Vec3f(1, 0, 0);
    std::vector<std::pair<float, float>> alphas;
    for (const ShapeInfo &info : scene.shapes) {
        const Material &m = scene.materials[size_t(info.material)];
        BSDF b = m.GetBSDF(si, TextureContext{});
        alphas.push_back({b.Part(0).roughAlphaX, b.Part(0).roughAlphaY});
    }
    ASSERT_EQ(alphas.size(), 3u);
    EXPECT_FLOAT_EQ(alphas[0].first, RoughnessToAlpha(0.1f));
    EXPECT_FLOAT_EQ(alphas[0].second, RoughnessToAlpha(0.f));  // v3: 0 remaps to 0.047
    EXPECT_FLOAT_EQ(alphas[1].first, 0.2f);
    EXPECT_FLOAT_EQ(alphas[1].second, 0.2f);
    EXPECT_EQ(alphas[2].first, 0.f);  // smooth
    EXPECT_EQ(alphas[2].second, 0.f);
}

TEST(DistributionIntegrator, ObjAndGltfDefaultToIt) {
    fs::path dir = fs::path(::testing::TempDir()) / "prism_distribution";
    fs::create_directories(dir);
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    Diagnostics diag(false);
    EXPECT_EQ(LoadScene((dir / "tri.obj").string(), diag).integrator.type, "distribution");
}

}  // namespace
}  // namespace prism
