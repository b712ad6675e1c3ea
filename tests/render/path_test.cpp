// The path and directlighting integrators (Integrator "path", "directlighting"): a furnace with
// an analytic answer, BSDF sampling against f and its density for every lobe kind, the light
// densities MIS needs, the power heuristic, path vs directlighting at maxdepth 1, strategy one
// vs all, Russian roulette, and the same image for 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "core/equal_area.h"
#include "geometry/sphere.h"
#include "render/bsdf.h"
#include "render/infinite_light.h"
#include "render/light_sampling.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

RenderScene BuildText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return BuildSceneText("prism_path", name, text, opts);
}

Image RenderText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return RenderSceneText("prism_path", name, text, opts).image;
}

// The camera inside a closed sphere of albedo a whose inside emits Le everywhere: the radiance
// is Le (1 + a + ... + a^maxdepth) (Le / (1 - a) as maxdepth grows).
std::string Furnace(float albedo, int maxDepth, float rrThreshold, int spp) {
    return "Film \"image\" \"integer xresolution\" [8] \"integer yresolution\" [8]\n"
           "Sampler \"stratified\" \"integer xsamples\" [" +
           std::to_string(spp) + "] \"integer ysamples\" [1]\n" +
           "Integrator \"path\" \"integer maxdepth\" [" + std::to_string(maxDepth) +
           "] \"float rrthreshold\" [" + std::to_string(rrThreshold) + "]\n" +
           "Camera \"perspective\" \"float fov\" [90]\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
           "Material \"matte\" \"rgb Kd\" [" +
           std::to_string(albedo) + " " + std::to_string(albedo) + " " + std::to_string(albedo) +
           "]\nShape \"sphere\" \"float radius\" [3]\nAttributeEnd\n";
}

TEST(PathIntegrator, FurnaceIsTheGeometricSeries) {
    // Without Russian roulette every estimator here has zero variance (inside a sphere, area
    // sampling and cosine sampling both give weight a), so the series is met to rounding.
    for (int depth : {1, 3, 8}) {
        const float a = 0.6f;
        Image img = RenderText("furnace" + std::to_string(depth), Furnace(a, depth, 0, 4));
        double expected = (1 - std::pow(double(a), depth + 1)) / (1 - a);
        RGB m = MeanRGB(img);
        EXPECT_NEAR(m.r, expected, 2e-3 * expected) << "maxdepth " << depth;
        EXPECT_NEAR(m.g, expected, 2e-3 * expected) << "maxdepth " << depth;
    }
}

TEST(PathIntegrator, RussianRouletteIsUnbiased) {
    // Deep paths with roulette from the fourth bounce on: the mean stays the series, and the
    // roulette does cut paths (the image is noisy, unlike the roulette-free one).
    const float a = 0.8f;
    const int depth = 30;
    Image rr = RenderText("rr", Furnace(a, depth, 1, 64));
    Image exact = RenderText("norr", Furnace(a, depth, 0, 4));
    const double expected = (1 - std::pow(double(a), depth + 1)) / (1 - a);
    EXPECT_NEAR(MeanRGB(exact).r, expected, 2e-3 * expected);
    EXPECT_NEAR(MeanRGB(rr).r, expected, 0.02 * expected);
    double spread = 0;
    for (int y = 0; y < rr.height; ++y)
        for (int x = 0; x < rr.width; ++x)
            spread = std::max(spread, std::abs(double(rr.pixels[rr.PixelOffset(x, y)]) - expected));
    EXPECT_GT(spread, 1e-3) << "Russian roulette never ended a path";
}

TEST(PathIntegrator, PowerHeuristicWeightsSumToOne) {
    for (int i = 0; i < 1000; ++i) {
        float a = std::exp(10 * (HashFloat(uint32_t(i), 1) - 0.5f));
        float b = std::exp(10 * (HashFloat(uint32_t(i), 2) - 0.5f));
        EXPECT_NEAR(PowerHeuristic(1, a, 1, b) + PowerHeuristic(1, b, 1, a), 1.0, 1e-6);
    }
    EXPECT_EQ(PowerHeuristic(1, 1, 1, 0), 1.f);
    EXPECT_EQ(PowerHeuristic(1, 0, 1, 1), 0.f);
    EXPECT_FLOAT_EQ(PowerHeuristic(1, 1, 1, 1), 0.5f);
}

BSDF Frame() {
    BSDF b;
    b.SetFrame(Vec3f(0, 0, 1), Vec3f(1, 0, 0), Vec3f(0, 0, 1));
    return b;
}

// Every kind of lobe Prism's materials build (matte, plastic, rough glass, translucent,
// substrate, glTF): Sample_f's density is Pdf's, and the mean of
// f |cos| / pdf is the albedo ∫ f |cos| dω, integrated numerically.
TEST(PathIntegrator, BsdfSamplingMatchesFAndPdf) {
    std::vector<BSDF> bsdfs;
    {  // matte (Oren–Nayar)
        BSDF b = Frame();
        BxDFLobes &l = b.AddPart();
        l.kd = RGB(0.5f);
        l.orenNayar = true;
        l.orenNayarA = 0.8f;
        l.orenNayarB = 0.3f;
        bsdfs.push_back(b);
    }
    {  // plastic: Lambertian plus dielectric microfacet
        BSDF b = Frame();
        BxDFLobes &l = b.AddPart();
        l.kd = RGB(0.4f);
        l.ks = RGB(0.3f);
        l.alphaX = l.alphaY = 0.3f;
        l.glossyFresnel.kind = FresnelKind::Dielectric;
        bsdfs.push_back(b);
    }
    {  // rough glass: microfacet reflection and transmission
        BSDF b = Frame();
        BxDFLobes &l = b.AddPart();
        l.ks = l.ksTransmit = RGB(1);
        l.alphaX = l.alphaY = 0.4f;
        l.glossyFresnel.kind = FresnelKind::Dielectric;
        l.glossyEta = 1.5f;
        bsdfs.push_back(b);
    }
    {  // translucent-like: diffuse reflection and transmission, substrate's FresnelBlend
        BSDF b = Frame();
        BxDFLobes &l = b.AddPart(RGB(0.5f));
        l.kd = RGB(0.3f);
        l.kdTransmit = RGB(0.4f);
        BxDFLobes &m = b.AddPart(RGB(0.5f));
        m.fresnelBlend = true;
        m.blendRd = RGB(0.5f);
        m.blendRs = RGB(0.1f);
        m.alphaX = m.alphaY = 0.25f;
        bsdfs.push_back(b);
    }
    {  // glTF metallic-roughness: Fresnel-mixed diffuse, GGX specular, thin transmission, coat
        BSDF b = Frame();
        BxDFLobes &l = b.AddPart();
        l.gltfDiffuse = true;
        l.kd = RGB(0.5f);
        l.dielectricF0 = RGB(0.04f);
        l.dielectricF90 = RGB(1);
        l.ks = RGB(1);
        l.glossyFresnel.kind = FresnelKind::Schlick;
        l.glossyFresnel.f0 = RGB(0.04f);
        l.alphaX = l.alphaY = 0.3f;
        l.thinTransmit = RGB(0.5f);
        l.coat = 0.5f;
        bsdfs.push_back(b);
    }
    const Vec3f wo = Normalize(Vec3f(0.4f, -0.2f, 0.8f));
    for (size_t k = 0; k < bsdfs.size(); ++k) {
        const BSDF &b = bsdfs[k];
        const int n = 400;
        double sampled = 0;
        for (int i = 0; i < n * n; ++i) {
            Vec2f u((float(i % n) + HashFloat(uint32_t(i), 7)) / float(n),
                    (float(i / n) + HashFloat(uint32_t(i), 8)) / float(n));
            BSDFSample s;
            if (!b.Sample_f(wo, u, HashFloat(uint32_t(i), 9), false, &s)) continue;
            EXPECT_NEAR(s.pdf, b.Pdf(wo, s.wi), 1e-3f * s.pdf) << "bsdf " << k;
            sampled += s.weight.g;
        }
        sampled /= double(n) * n;
        double integral = 0;
        const int nt = 600, np = 600;
        for (int i = 0; i < nt; ++i) {
            double theta = (i + 0.5) * Pi / nt;
            for (int j = 0; j < np; ++j) {
                double phi = (j + 0.5) * 2 * Pi / np;
                Vec3f wi(float(std::sin(theta) * std::cos(phi)),
                         float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
                integral += double(b.f(wo, wi).g) * std::abs(std::cos(theta)) * std::sin(theta) *
                            (Pi / nt) * (2 * Pi / np);
            }
        }
        EXPECT_NEAR(sampled, integral, 0.01 * integral + 1e-4) << "bsdf " << k;
    }
}

TEST(PathIntegrator, DeltaLobesAreChosenByFresnel) {
    BSDF b = Frame();
    BxDFLobes &l = b.AddPart();
    l.kr = l.kt = RGB(1);
    l.specularFresnel.kind = FresnelKind::Dielectric;
    l.eta = 1.5f;
    const Vec3f wo = Normalize(Vec3f(0.3f, 0, 1));
    // The mean weight over both choices is what reflection and transmission carry together.
    double sum = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
        BSDFSample s;
        ASSERT_TRUE(b.Sample_f(wo, Vec2f(0.5f, 0.5f), (i + 0.5f) / n, true, &s));
        EXPECT_TRUE(s.specular);
        sum += s.weight.r;
    }
    Vec3f wi;
    RGB wr, wt;
    ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wi, &wr));
    ASSERT_TRUE(b.SampleSpecularTransmission(0, wo, &wi, &wt));
    EXPECT_NEAR(sum / n, wr.r + wt.r, 1e-3);
    EXPECT_EQ(b.Pdf(wo, wi), 0.f);  // delta lobes have no density
}

TEST(PathIntegrator, SpherePdfMatchesItsSampling) {
    // The solid-angle density of a sampled point, recomputed from the point (what MIS uses for
    // a BSDF-sampled ray that hits the light), outside (cone sampling) and inside (area).
    auto sphere = std::make_unique<Sphere>(Translate(Vec3d(0, 0, 5)), false, 1.0, -1.0, 1.0, 360.0);
    for (Vec3f ref : {Vec3f(0, 0, 0), Vec3f(0.2f, 0.1f, 5.3f)}) {
        for (int i = 0; i < 64; ++i) {
            ShapeSample ss;
            Vec2f u(HashFloat(uint32_t(i), 3), HashFloat(uint32_t(i), 4));
            if (!sphere->Sample(ref, u, &ss)) continue;
            EXPECT_NEAR(sphere->Pdf(ref, ss.p, ss.n), ss.pdf, 1e-3f * ss.pdf);
        }
    }
}

TEST(PathIntegrator, InfiniteLightPdfMatchesItsSampling) {
    // An environment map with a bright spot: SampleLi's density is PdfLi's for the same
    // direction (what MIS weighs an escaping BSDF-sampled ray with).
    auto map = std::make_shared<Image>(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) map->At(x, y, c) = (x == 3 && y == 2) ? 50.f : 0.5f + x;
    InfiniteLight light(Transform(), RGB(1), map, 1);
    SurfaceInteraction si;
    si.n = si.ns = Vec3f(0, 0, 1);
    si.wo = Vec3f(0, 0, 1);
    int n = 0;
    for (int i = 0; i < 256; ++i) {
        LightSample ls;
        Vec2f u(HashFloat(uint32_t(i), 5), HashFloat(uint32_t(i), 6));
        if (!light.SampleLi(si, u, &ls)) continue;
        ++n;
        EXPECT_NEAR(light.PdfLi(si, ls.wi, nullptr), ls.pdf, 2e-3f * ls.pdf) << i;
    }
    EXPECT_GT(n, 200);
}

// pbrt-v4's equal-area maps (LightSource "infinite" "filename"): SampleLi's density is PdfLi's,
// the directions land where the map is bright, the map is oriented as pbrt-v4's (+z at the
// centre, -z at the corners, +x at the right edge's midpoint), and the irradiance on an
// upward plane is the map's cosine-weighted integral.
TEST(PathIntegrator, EqualAreaEnvironmentMapIsSampledAndLookedUpAsPbrtV4) {
    const int n = 16;
    auto map = std::make_shared<Image>(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) map->SetRGB(x, y, RGB(0.2f + 0.05f * float(x), 0.5f, 1));
    map->SetRGB(n / 2, n / 2, RGB(100, 0, 0));  // the zenith
    map->SetRGB(n - 1, n / 2, RGB(0, 100, 0));  // +x on the horizon
    map->SetRGB(0, 0, RGB(0, 0, 100));          // the nadir
    const InfiniteLight light(Transform(), RGB(1), map, 1, InfiniteLight::Projection::EqualArea);
    auto le = [&](Vec3f d) { return light.Le(Ray{Vec3f(0, 0, 0), d}); };
    EXPECT_EQ(le({0, 0, 1}), RGB(100, 0, 0));
    EXPECT_EQ(le({1, 0, 0.001f}), RGB(0, 100, 0));
    EXPECT_EQ(le(Normalize(Vec3f(-0.01f, -0.01f, -1))), RGB(0, 0, 100));

    SurfaceInteraction si;
    si.n = si.ns = Vec3f(0, 0, 1);
    si.wo = Vec3f(0, 0, 1);
    double irradiance = 0, red = 0;
    const int samples = 20000;
    for (int i = 0; i < samples; ++i) {
        LightSample ls;
        Vec2f u(HashFloat(uint32_t(i), 5), HashFloat(uint32_t(i), 6));
        ASSERT_TRUE(light.SampleLi(si, u, &ls));
        ASSERT_NEAR(light.PdfLi(si, ls.wi, nullptr), ls.pdf, 2e-3f * ls.pdf) << i;
        // The density is the texel's luminance share over its 4π/n² of solid angle.
        ASSERT_NEAR(ls.pdf, ls.Li.Luminance() / (light.Power(1) / Pi) / (4 * Pi), 1e-3 * ls.pdf);
        if (ls.wi.z > 0) irradiance += ls.Li.g * ls.wi.z / ls.pdf;
        if (ls.Li.r == 100) red += 1;
    }
    // The bright zenith texel: its luminance share of the map.
    double lumSum = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) lumSum += map->GetRGB(x, y).Luminance();
    EXPECT_NEAR(red / samples, RGB(100, 0, 0).Luminance() / lumSum, 0.01);
    // The irradiance in green by quadrature over the square instead (4π per unit area; the
    // +x texel straddles the horizon): the sampled estimate agrees.
    const int q = 1024;
    double quadrature = 0;
    for (int j = 0; j < q; ++j)
        for (int i = 0; i < q; ++i) {
            const Vec2d p((i + 0.5) / q, (j + 0.5) / q);
            const double z = EqualAreaSquareToSphere(p).z;
            if (z > 0) quadrature += map->GetRGB(i * n / q, j * n / q).g * z;
        }
    quadrature *= 4 * Pi / (double(q) * q);
    EXPECT_GT(quadrature, 0.5 * Pi * 1.05);
    EXPECT_NEAR(irradiance / samples, quadrature, 0.02 * quadrature);
}

TEST(PathIntegrator, DiffuseSphereUnderUniformSky) {
    // A convex diffuse sphere of albedo a under a uniform sky L sees the whole sky from every
    // point: at maxdepth 1 its radiance is a L (light and BSDF samples both exact here).
    const std::string scene =
        "Film \"image\" \"integer xresolution\" [8] \"integer yresolution\" [8]\n"
        "Sampler \"stratified\" \"integer xsamples\" [2] \"integer ysamples\" [2]\n"
        "Integrator \"path\" \"integer maxdepth\" [1]\n"
        "LookAt 0 0 -10  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [2]\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [2 2 2]\n"
        "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\nShape \"sphere\" \"float radius\" [1]\n";
    RGB m = MeanRGB(RenderText("sky", scene));
    EXPECT_NEAR(m.g, 1.0, 2e-3);
}

// A diffuse room: floor, back wall, a sphere, a quad light and a point light.
std::string DiffuseRoom(const std::string &integrator, int spp, int res = 16) {
    return "Film \"image\" \"integer xresolution\" [" + std::to_string(res) +
           "] \"integer yresolution\" [" + std::to_string(res) +
           "]\nSampler \"stratified\" \"integer xsamples\" [" + std::to_string(spp) +
           "] \"integer ysamples\" [1]\n" + integrator + "\n" + std::string(kLitFloorFromLookAt) +
           "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
           "  \"point P\" [-3 0 2  3 0 2  3 3 2  -3 3 2]\n"
           "Material \"matte\" \"rgb Kd\" [0.3 0.6 0.3] \"float sigma\" [20]\n"
           "AttributeBegin\nTranslate 0 0.6 0\nShape \"sphere\" \"float radius\" [0.6]\n"
           "AttributeEnd\n";
}

TEST(PathIntegrator, MaxDepthOneIsDirectLighting) {
    Image path = RenderText("p1", DiffuseRoom("Integrator \"path\" \"integer maxdepth\" [1]", 256));
    Image direct = RenderText(
        "d1", DiffuseRoom("Integrator \"directlighting\" \"integer maxdepth\" [1]", 256));
    EXPECT_LT(RelL1(path, direct), 0.03);
    RGB a = MeanRGB(path), b = MeanRGB(direct);
    EXPECT_NEAR(a.g, b.g, 0.01 * b.g);
    // And indirect light makes the path image brighter at depth 5.
    Image deep = RenderText("p5", DiffuseRoom("Integrator \"path\" \"integer maxdepth\" [5]", 64));
    EXPECT_GT(MeanRGB(deep).g, 1.1f * b.g);
}

TEST(PathIntegrator, DirectStrategyOneAndAllAgree) {
    Image all = RenderText(
        "all", DiffuseRoom("Integrator \"directlighting\" \"string strategy\" \"all\"", 256));
    Image one = RenderText(
        "one", DiffuseRoom("Integrator \"directlighting\" \"string strategy\" \"one\"", 256));
    RGB a = MeanRGB(all), b = MeanRGB(one);
    EXPECT_NEAR(a.r, b.r, 0.01 * a.r);
    EXPECT_NEAR(a.g, b.g, 0.01 * a.g);
    EXPECT_LT(RelL1(one, all), 0.05);
}

TEST(PathIntegrator, SameImageForOneAndTwoThreads) {
    for (const char *integrator : {"path", "directlighting"}) {
        RenderScene scene =
            BuildText(std::string("threads_") + integrator,
                      DiffuseRoom(std::string("Integrator \"") + integrator + "\"", 4, 40));
        Image one, two;
        RenderStats stats;
        tbb::task_arena(1).execute([&] { one = Render(scene, &stats); });
        tbb::task_arena(2).execute([&] { two = Render(scene, &stats); });
        EXPECT_TRUE(one.pixels == two.pixels) << integrator;
        EXPECT_GT(MeanRGB(one).g, 0.f);
    }
}

TEST(PathIntegrator, IntegratorOverrideAndReason) {
    BuildSettings opts;
    opts.integrator = "path";
    RenderScene s = BuildText("why", DiffuseRoom("", 1), opts);
    EXPECT_STREQ(s.IntegratorName(), "path");
    EXPECT_EQ(s.integratorWhy, "--integrator path");
    EXPECT_TRUE(s.features.effects.Has(Effect::IndirectIllumination));
    // No Integrator: pbrt-v3's default, path with maxdepth 5.
    RenderScene d = BuildText("why2", DiffuseRoom("", 1));
    EXPECT_STREQ(d.IntegratorName(), "path");
    EXPECT_EQ(d.integratorWhy, "pbrt-v3's default: the scene names no Integrator");
    EXPECT_EQ(d.trace.maxDepth, 5);
    EXPECT_TRUE(d.features.effects.Has(Effect::IndirectIllumination));
    RenderScene n = BuildText("why3", DiffuseRoom("Integrator \"directlighting\"", 1));
    EXPECT_STREQ(n.IntegratorName(), "directlighting");
    EXPECT_NE(n.integratorWhy.find("Integrator \"directlighting\" at "), std::string::npos);
}

}  // namespace
}  // namespace prism
