// Participating media (render/medium.h, render/kernel_media.h, assembly/media.cpp): transmittance
// of homogeneous media through boundaries and nested media, ratio and delta tracking of grids
// against the closed form, single scattering from a point light against a quadrature, the
// Henyey–Greenstein phase function and its sampling, and media-free scenes unchanged.
#include "render/medium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "assembly/build_scene.h"
#include "image/image_compare.h"
#include "image/image_io.h"
#include "render/kernel.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

Rendered RenderText(const std::string &name, const std::string &text, int w = 1, int h = 1,
                    int spp = 1, const std::string &integrator = "") {
    BuildSettings s = SizedSettings(w, h, spp, integrator);
    s.defaultIntegrator = "whitted";  // the media kernel's
    return RenderSceneText("medium", name, text, s);
}

RGB Pixel(const Image &img, int x = 0, int y = 0) {
    const float *p =
        &img.pixels[(size_t(y) * size_t(img.width) + size_t(x)) * size_t(img.channels)];
    return {p[0], p[1], p[2]};
}

// A closed box [x0,x1]x[y0,y1]x[z0,z1] with outward normals, as a trianglemesh Shape.
std::string Box(double x0, double y0, double z0, double x1, double y1, double z1) {
    std::ostringstream s;
    s << "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 "
         "3 7 6 3 6 2 0 4 7 0 7 3 1 2 6 1 6 5 ]\n  \"point3 P\" [ "
      << x0 << " " << y0 << " " << z0 << " " << x1 << " " << y0 << " " << z0 << " " << x1 << " "
      << y1 << " " << z0 << " " << x0 << " " << y1 << " " << z0 << " " << x0 << " " << y0 << " "
      << z1 << " " << x1 << " " << y0 << " " << z1 << " " << x1 << " " << y1 << " " << z1 << " "
      << x0 << " " << y1 << " " << z1 << " ]\n";
    return s.str();
}

void ExpectRel(float got, double want, double tol, const char *what) {
    EXPECT_NEAR(got, want, tol * std::abs(want)) << what;
}

TEST(Medium, HomogeneousTransmittanceIsExponential) {
    HomogeneousMedium m(RGB(0.1f, 0.4f, 0.0f), RGB(0.2f, 0.1f, 0.0f), 0.f, 0.f);
    MediumSampler sampler(1);
    // A non-unit direction: distances are t times |d|.
    Ray ray{Vec3f(1, 2, 3), Vec3f(0, 3, 4), 0.7f};
    const RGB tr = m.Tr(ray, sampler);
    const double d = 0.7 * 5;
    ExpectRel(tr.r, std::exp(-0.3 * d), 1e-6, "r");
    ExpectRel(tr.g, std::exp(-0.5 * d), 1e-6, "g");
    EXPECT_EQ(tr.b, 1.f);  // σt = 0 transmits everything
    // Sampling: a channel with σt = 0 never scatters, even along an unbounded ray; the others
    // always do there.
    {
        HomogeneousMedium blue(RGB(0, 0, 0), RGB(0.5f, 0.5f, 0), 0.f, 0.f);
        Ray unbounded{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Infinity};
        int passed = 0;
        for (int i = 0; i < 3000; ++i) {
            MediumSampler s(uint64_t(i) + 99);
            MediumInteraction mi;
            bool scattered;
            const RGB w = blue.Sample(unbounded, s, &mi, &scattered);
            EXPECT_TRUE(w.IsFinite());
            if (!scattered) {
                ++passed;
                EXPECT_EQ(w.r, 0.f);  // red and green never get through
                EXPECT_GT(w.b, 0.f);  // blue always does
            } else {
                EXPECT_LT(mi.t, Infinity);
            }
        }
        EXPECT_NEAR(passed / 3000.0, 1.0 / 3, 0.03);  // when the blue channel is chosen
    }
    ray.tMax = Infinity;
    EXPECT_EQ(m.Tr(ray, sampler).r, 0.f);
    EXPECT_EQ(m.Tr(ray, sampler).b, 1.f);  // even infinitely far (no 0 · ∞)
}

// Camera rays through a slab of one absorbing medium holding a nested slab of another, both
// bounded by invisible ("none") boxes, toward a constant environment: the pixel is exp(-Σσd).
TEST(Medium, TransmittanceThroughBoundariesAndNestedMedium) {
    const std::string scene =
        "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 10 ]\n"
        "MakeNamedMedium \"outer\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.3 0.5 "
        "0.1 ] \"rgb sigma_s\" [ 0 0 0 ]\n"
        "MakeNamedMedium \"inner\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.7 0.2 "
        "1.1 ] \"rgb sigma_s\" [ 0 0 0 ]\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nMaterial \"none\"\n"
        "AttributeBegin\nMediumInterface \"outer\" \"\"\n" +
        Box(-10, -10, 2, 10, 10, 5) +
        "AttributeEnd\nAttributeBegin\nMediumInterface \"inner\" \"outer\"\n" +
        Box(-5, -5, 3, 5, 5, 4) + "AttributeEnd\n";
    Rendered r = RenderText("slab.pbrt", scene);
    EXPECT_EQ(r.stats.kernelMask, KernelMediaMask);
    const RGB p = Pixel(r.image);
    ExpectRel(p.r, std::exp(-0.3 * 2 - 0.7 * 1), 1e-6, "r");
    ExpectRel(p.g, std::exp(-0.5 * 2 - 0.2 * 1), 1e-6, "g");
    ExpectRel(p.b, std::exp(-0.1 * 2 - 1.1 * 1), 1e-6, "b");
    EXPECT_EQ(r.stats.rays.passThrough, 4u);  // four invisible faces crossed
}

// Shadow rays: a matte floor under a point light, an absorbing slab with a nested one between
// them; the camera below the slab sees the floor point under the light in vacuum.
TEST(Medium, ShadowRaysPassThroughMediaAndBoundaries) {
    const std::string scene =
        "LookAt 0 -0.5 -3  0 -1 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 5 ]\n"
        "MakeNamedMedium \"outer\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.4 0.4 "
        "0.4 ] \"rgb sigma_s\" [ 0 0 0 ]\n"
        "MakeNamedMedium \"inner\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 2 2 2 ] "
        "\"rgb sigma_s\" [ 0 0 0 ]\n"
        "WorldBegin\nLightSource \"point\" \"point3 from\" [ 0 3 0 ] \"rgb I\" [ 16 16 16 ]\n"
        "Material \"matte\" \"rgb Kd\" [ 0.5 0.5 0.5 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "  \"point3 P\" [ -10 -1 -10  10 -1 -10  10 -1 10  -10 -1 10 ]\n"
        "Material \"none\"\nAttributeBegin\nMediumInterface \"outer\" \"\"\n" +
        Box(-20, 0, -20, 20, 1, 20) +
        "AttributeEnd\nAttributeBegin\nMediumInterface \"inner\" \"outer\"\n" +
        Box(-10, 0.25, -10, 10, 0.5, 10) + "AttributeEnd\n";
    Rendered r = RenderText("shadow.pbrt", scene);
    const double want = 0.5 / Pi * 16 / 16 * std::exp(-0.4 * 0.75 - 2 * 0.25);
    ExpectRel(Pixel(r.image).g, want, 1e-5, "floor radiance");
}

TEST(Medium, ConstantDensityGridMatchesHomogeneous) {
    const float sa = 0.2f, ss = 0.3f;
    // A 4^3 grid of density 1 over the box [0,2]^3 of its space, moved by its transform.
    const Transform renderFromMedium = Translate(Vec3d(5, 0, 0));
    GridDensityMedium grid(RGB(sa), RGB(ss), 0.f, 0.f, 4, 4, 4, std::vector<float>(64, 1.f),
                           Vec3f(0, 0, 0), Vec3f(2, 2, 2), renderFromMedium);
    EXPECT_FLOAT_EQ(grid.Density(Vec3f(6, 1, 1)), 1.f);
    EXPECT_FLOAT_EQ(grid.Density(Vec3f(4.7f, 1, 1)), 0.f);
    auto meanTr = [&](const Ray &ray, double *passFraction) {
        const int n = 40000;
        double sum = 0, pass = 0;
        for (int i = 0; i < n; ++i) {
            MediumSampler s(uint64_t(i) * 7919 + 13);
            sum += grid.Tr(ray, s).r;
            MediumInteraction mi;
            bool scattered;
            MediumSampler s2(uint64_t(i) * 104729 + 7);
            const RGB w = grid.Sample(ray, s2, &mi, &scattered);
            if (scattered) {
                EXPECT_NEAR(w.r, ss / (sa + ss), 1e-6);
                EXPECT_GT(mi.t, 0.f);
                EXPECT_LT(mi.t, ray.tMax);
            } else {
                pass += 1;
            }
        }
        *passFraction = pass / n;
        return sum / n;
    };
    // Inside the grid, at least half a voxel from its faces, the density is exactly 1: the
    // homogeneous medium's transmittance. A non-unit direction, as from SpawnRayTo.
    Ray inner{Vec3f(5.3f, 1, 1), Vec3f(1.4f, 0, 0), 1.f};
    HomogeneousMedium homogeneous(RGB(sa), RGB(ss), 0.f, 0.f);
    MediumSampler unused(0);
    const double want = homogeneous.Tr(inner, unused).r;
    ExpectRel(float(want), std::exp(-0.5 * 1.4), 1e-6, "homogeneous");
    double pass;
    EXPECT_NEAR(meanTr(inner, &pass), want, 0.01);
    EXPECT_NEAR(pass, want, 0.01);  // delta tracking passes through with probability Tr
    EXPECT_NEAR(grid.Tau(inner, 0, 1).r, 0.5 * 1.4, 1e-5);
    // Across the whole grid: within half a voxel of each face the density falls to 1/2
    // (pbrt-v3's trilinear lookup with zero outside), 1/16 of a unit less on each side.
    Ray across{Vec3f(3, 1, 1), Vec3f(1, 0, 0), 6.f};
    const double wantAcross = std::exp(-0.5 * (2 - 2 * 0.0625));
    EXPECT_NEAR(meanTr(across, &pass), wantAcross, 0.01);
    EXPECT_NEAR(pass, wantAcross, 0.01);
    float t0, t1;
    ASSERT_TRUE(grid.Extent(across, &t0, &t1));
    EXPECT_NEAR(t0, 2.f, 1e-5);
    EXPECT_NEAR(t1, 4.f, 1e-5);
}

// A grid medium of type `type`, density 1 over [-5, 5]^2 x [0, 1] of its space (absorbing
// 0.8 per unit), placed at z = 3 by the CTM, inside an invisible box the camera looks through
// along +z at a white sky.
std::string AbsorbingGridScene(const std::string &type) {
    return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 1 ]\n"
           "WorldBegin\nAttributeBegin\nTranslate 0 0 3\n"
           "MakeNamedMedium \"smoke\" \"string type\" \"" +
           type +
           "\" \"rgb sigma_a\" [ 0.8 0.8 0.8 ] \"rgb sigma_s\" [ 0 0 0 ] \"integer nx\" 2 "
           "\"integer ny\" 2 \"integer nz\" 2 \"float density\" [ 1 1 1 1 1 1 1 1 ] "
           "\"point3 p0\" [ -5 -5 0 ] \"point3 p1\" [ 5 5 1 ]\n"
           "AttributeEnd\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nMaterial \"none\"\n"
           "MediumInterface \"smoke\" \"\"\n" +
           Box(-10, -10, 2, 10, 10, 5);
}

// A heterogeneous medium placed by the CTM at MakeNamedMedium, inside an invisible box: camera
// rays through it by ratio tracking average to the grid's transmittance (density 1 with
// pbrt-v3's half-voxel falloff at the faces along z: 1 - 1/8 of the unit depth).
TEST(Medium, HeterogeneousGridPlacedByTheCtm) {
    Rendered r = RenderText("grid.pbrt", AbsorbingGridScene("heterogeneous"), 1, 1, 1024);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
    EXPECT_NEAR(Pixel(r.image).r, std::exp(-0.8 * 0.875), 0.01);
}

// pbrt-v4's "uniformgrid" is the density grid of pbrt-v3's "heterogeneous", and a file read by
// pbrt-v4's rules takes pbrt-v4's default coefficients (sigma_a = sigma_s = 1) where pbrt-v3
// takes whole milk; pbrt-v4's presets are there; its emission is read and warned about.
TEST(Medium, PbrtV4UniformGridAndDefaults) {
    Rendered r = RenderText("uniformgrid.pbrt", AbsorbingGridScene("uniformgrid"), 1, 1, 1024);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
    EXPECT_NEAR(Pixel(r.image).r, std::exp(-0.8 * 0.875), 0.01);

    const std::string media =
        "MakeNamedMedium \"h\" \"string type\" \"homogeneous\"\n"
        "MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"float density\" [ 2 ]\n"
        "MakeNamedMedium \"p\" \"string type\" \"homogeneous\" \"string preset\" "
        "\"Cappuccino Powder\"\n"
        "MakeNamedMedium \"e\" \"string type\" \"homogeneous\" \"rgb Le\" [ 1 1 1 ]\n";
    for (int version : {3, 4}) {
        SCOPED_TRACE(version);
        Diagnostics diag(false);
        PbrtParseOptions opts;
        opts.pbrtVersion = version;
        const SceneDescription d = ParsePbrtString(media + "WorldBegin\n", "v.pbrt", diag, opts);
        BuildSettings s = SizedSettings(1, 1, 1);
        const RenderScene scene = BuildRenderScene(d, s, diag);
        ASSERT_EQ(scene.media.size(), 4u);
        const RGB h = scene.media[0]->SigmaA();
        if (version == 4)
            EXPECT_EQ(h, RGB(1));
        else
            EXPECT_NEAR(h.b, 0.014f, 1e-6);
        EXPECT_EQ(scene.media[1]->SigmaA(), RGB(1));  // a pbrt-v4 type: pbrt-v4's defaults
        EXPECT_NEAR(scene.media[2]->SigmaA().r, 35.844f, 1e-3);
        bool warned = false;
        for (const Warning &w : diag.Warnings())
            warned |= w.message.find("\"Le\"") != std::string::npos &&
                      w.message.find("do not emit") != std::string::npos;
        EXPECT_TRUE(warned);
    }
}

// The graphics state: media are named globally, MediumInterface is scoped by AttributeBegin,
// one name is both media, and the camera takes the outside medium current at Camera.
TEST(Medium, GraphicsState) {
    Diagnostics diag(false);
    SceneDescription d =
        LoadScene(WriteTestFile(ScratchDir("medium") / "state.pbrt",
                                "MakeNamedMedium \"a\" \"string type\" \"homogeneous\"\n"
                                "MediumInterface \"a\"\nCamera \"perspective\"\nWorldBegin\n"
                                "AttributeBegin\nTranslate 1 2 3\n"
                                "MakeNamedMedium \"b\" \"string type\" \"homogeneous\"\n"
                                "MediumInterface \"b\" \"\"\nShape \"sphere\"\nAttributeEnd\n"
                                "Shape \"sphere\"\nMediumInterface \"\" \"b\"\nShape \"sphere\"\n"),
                  diag);
    ASSERT_EQ(d.media.size(), 2u);
    EXPECT_EQ(d.media[1].worldFromMedium.Point(Vec3d(0, 0, 0)), Vec3d(1, 2, 3));
    EXPECT_EQ(d.camera.medium, 0);
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[0].mediumInside, 1);
    EXPECT_EQ(d.shapes[0].mediumOutside, -1);
    EXPECT_EQ(d.shapes[0].mediumLoc.line, 8);
    // After AttributeEnd: the interface before it ("a" on both sides: no transition).
    EXPECT_EQ(d.shapes[1].mediumInside, 0);
    EXPECT_EQ(d.shapes[1].mediumOutside, 0);
    EXPECT_EQ(d.shapes[2].mediumInside, -1);
    EXPECT_EQ(d.shapes[2].mediumOutside, 1);
}

// Single scattering from a point light into a camera inside an unbounded homogeneous medium,
// against ∫ Tr(0,t) σs p(θ) I / d² Tr(t, light) dt by Simpson's rule.
TEST(Medium, SingleScatteringMatchesQuadrature) {
    const double sa = 0.1, ss = 0.2, st = sa + ss, g = 0.4, I = 10;
    const double lx = 0, ly = 1, lz = 3;
    std::ostringstream s;
    s << "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ " << sa << " "
      << sa << " " << sa << " ] \"rgb sigma_s\" [ " << ss << " " << ss << " " << ss
      << " ] \"float g\" " << g << " \"float stepsize\" 0.005\n"
      << "MediumInterface \"\" \"fog\"\nLookAt 0 0 0  0 0 1  0 1 0\n"
      << "Camera \"perspective\" \"float fov\" [ 10 ]\nWorldBegin\n"
      << "LightSource \"point\" \"point3 from\" [ " << lx << " " << ly << " " << lz
      << " ] \"rgb I\" [ " << I << " " << I << " " << I << " ]\n";
    Rendered r = RenderText("single.pbrt", s.str());
    EXPECT_TRUE(r.scene.features.effects.Has(Effect::Media));
    auto f = [&](double t) {
        const double dx = -lx, dy = -ly, dz = t - lz;  // from the light to the ray point
        const double d2 = dx * dx + dy * dy + dz * dz, d = std::sqrt(d2);
        const double cosTheta = -dz / d;  // between the light's travel and the way to the eye
        const double phase = (1 - g * g) / (4 * Pi * std::pow(1 + g * g - 2 * g * cosTheta, 1.5));
        return std::exp(-st * t) * ss * phase * I / d2 * std::exp(-st * d);
    };
    const int n = 400000;
    const double a = 0, b = 200, h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
    const double want = sum * h / 3;
    ExpectRel(Pixel(r.image).r, want, 0.01, "single scattering");
    EXPECT_GT(r.stats.rays.shadow, 1000u);  // the march's shadow rays
}

TEST(Medium, HenyeyGreensteinIntegratesToOneAndSamplesItself) {
    for (float g : {-0.7f, 0.f, 0.3f, 0.9f}) {
        SCOPED_TRACE(g);
        // 2π ∫ p dcosθ over [-1, 1].
        const int n = 200000;
        double integral = 0;
        for (int i = 0; i < n; ++i) {
            const float c = -1 + 2 * (float(i) + 0.5f) / float(n);
            integral += PhaseHG(c, g) * (2.0 / n);
        }
        EXPECT_NEAR(2 * Pi * integral, 1.0, 1e-3);
        // Sampled cosines follow p: a histogram of cos(wo, wi) against p's mass per bin.
        HenyeyGreenstein hg(g);
        const Vec3f wo = Normalize(Vec3f(0.3f, -0.5f, 0.8f));
        const int bins = 20, samples = 200000;
        std::vector<double> hist(bins, 0);
        PCG32 rng(42);
        for (int i = 0; i < samples; ++i) {
            Vec3f wi;
            const float pdf = hg.Sample_p(wo, &wi, Vec2f(rng.Uniform(), rng.Uniform()));
            ASSERT_NEAR(Length(wi), 1.f, 1e-4f);
            const float c = Dot(wo, wi);
            ASSERT_NEAR(pdf, hg.p(wo, wi), 2e-3f * pdf + 1e-5f);
            hist[size_t(std::clamp(int((c + 1) / 2 * bins), 0, bins - 1))] += 1.0 / samples;
        }
        for (int b = 0; b < bins; ++b) {
            double mass = 0;
            for (int k = 0; k < 1000; ++k) {
                const double c = -1 + (b + (k + 0.5) / 1000) * 2.0 / bins;
                mass += 2 * Pi * PhaseHG(float(c), g) * (2.0 / bins / 1000);
            }
            EXPECT_NEAR(hist[size_t(b)], mass, 0.004) << "bin " << b;
        }
    }
}

// A scene without media (a medium defined but used by nothing) renders exactly as the binary
// before media existed rendered it, with the same rays, in its specialized kernel.
TEST(Medium, SceneWithoutMediaIsUnchanged) {
    struct Case {
        const char *integrator, *golden;
        uint64_t shadow, reflection, passThrough, glossy;
    };
    for (const Case &c :
         {Case{"whitted", "nomedia_spot_64x48.exr", 12279, 2872, 1148, 0},
          Case{"distribution", "nomedia_spot_distribution_64x48.exr", 16756, 3441, 1410, 5370}}) {
        SCOPED_TRACE(c.integrator);
        Diagnostics diag(false);
        SceneDescription desc = LoadScene(Source + "/tests/golden/nomedia_spot.pbrt", diag);
        BuildSettings s;
        s.integrator = c.integrator;
        RenderScene scene = BuildRenderScene(desc, s, diag);
        EXPECT_FALSE(scene.features.effects.Has(Effect::Media));
        EXPECT_EQ(KernelMaskFor(scene) & KernelMedia, 0u);
        EXPECT_EQ(KernelAllFor(scene), KernelAll);
        RenderStats stats;
        Image img = Render(scene, &stats);
        Image golden = ReadImage(Source + "/tests/golden/" + c.golden);
        ImageDiff d = CompareImages(img, golden, 1e-5f);
        // Bit-identical on the machine that made it; the bound only absorbs other compilers
        // and Embree's kernels for other instruction sets (an AVX2-only machine rounds
        // triangle hits differently from an AVX-512 one: 1.3e-6 in one pixel).
        EXPECT_LT(d.maxAbs, 1e-5);
        EXPECT_EQ(d.badPixels, 0);
        EXPECT_EQ(stats.rays.camera, 12288u);
        EXPECT_EQ(stats.rays.shadow, c.shadow);
        EXPECT_EQ(stats.rays.reflection, c.reflection);
        EXPECT_EQ(stats.rays.passThrough, c.passThrough);
        EXPECT_EQ(stats.rays.glossy, c.glossy);
    }
}

// The effect set names the directive that brought media in; --effects all runs the same
// media kernel (same bits).
TEST(Medium, EffectReasonAndKernel) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Source + "/scenes/fog.pbrt", diag);
    BuildSettings s;
    s.resolution = Vec2i(32, 20);
    s.spp = 1;
    RenderScene scene = BuildRenderScene(desc, s, diag);
    EXPECT_TRUE(diag.Warnings().empty());
    ASSERT_TRUE(scene.features.effects.Has(Effect::Media));
    const std::string &why = scene.features.effects.reasons[size_t(Effect::Media)];
    EXPECT_NE(why.find("camera medium \"fog\""), std::string::npos) << why;
    EXPECT_NE(why.find("fog.pbrt:11:1"), std::string::npos) << why;
    EXPECT_EQ(scene.cameraMedium, 0);
    EXPECT_EQ(KernelMaskFor(scene), KernelMediaMask);
    EXPECT_EQ(KernelMaskName(KernelMediaMask), "all+media");
    RenderStats a, b;
    Image ia = Render(scene, &a);
    scene.allEffects = true;
    Image ib = Render(scene, &b);
    EXPECT_EQ(b.kernelMask, KernelMediaMask);
    EXPECT_EQ(CompareImages(ia, ib, 0.f).maxAbs, 0.0);
}

}  // namespace
}  // namespace prism
