// pbrt-v4's chromatic heterogeneous media (render/medium_tracked.h, assembly/media.cpp):
// ratio and delta tracking against closed forms per channel, the balance-heuristic weights of a
// chromatic medium, the RGB grid's lookup and the cloud's density, and both from a scene file.
#include "render/medium_tracked.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

// Means over n runs of Tr, of Sample's weight when it passes through (0 otherwise) and of its
// weight when it scatters (0 otherwise), per channel.
struct TrackingMeans {
    RGB tr, pass, scatter;
};

TrackingMeans Means(const Medium &m, const Ray &ray, int n) {
    TrackingMeans out;
    for (int i = 0; i < n; ++i) {
        MediumSampler a(uint64_t(i) * 7919 + 13), b(uint64_t(i) * 104729 + 7);
        out.tr += m.Tr(ray, a);
        MediumInteraction mi;
        bool scattered = false;
        const RGB w = m.Sample(ray, b, &mi, &scattered);
        if (scattered) {
            EXPECT_GT(mi.t, 0.f);
            EXPECT_LT(mi.t, ray.tMax);
            out.scatter += w;
        } else {
            out.pass += w;
        }
    }
    out.tr = out.tr / float(n);
    out.pass = out.pass / float(n);
    out.scatter = out.scatter / float(n);
    return out;
}

void ExpectNearRGB(const RGB &got, const RGB &want, float tol, const char *what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << " channel " << c;
}

// A 2^3 RGB grid of one chromatic value everywhere is, well inside it, the homogeneous medium
// of that value: per channel, Tr = exp(-σt d), the pass-through weight averages Tr and the
// scattering weight averages σs/σt (1 - exp(-σt d)), though the three channels' σt differ by
// 20 times (the balance heuristic over the channels keeps each unbiased).
TEST(TrackedMedium, ConstantChromaticGridIsHomogeneousPerChannel) {
    const RGB sa(0.05f, 0.3f, 1.2f), ss(0.05f, 0.5f, 0.8f);
    const Transform renderFromMedium = Translate(Vec3d(0, 0, 10)) * Scale(2, 2, 2);
    RGBGridMedium grid(0.f, 0.f, 2, 2, 2, std::vector<RGB>(8, sa), std::vector<RGB>(8, ss), 1.f,
                       Vec3f(-2, -2, -2), Vec3f(2, 2, 2), renderFromMedium);
    EXPECT_FLOAT_EQ(grid.Majorant(), 2.f);
    // From z = 9 to z = 10.5 (render space), with a non-unit direction: 1.5 units.
    const Ray ray{Vec3f(0, 0, 9), Vec3f(0, 0, 0.5f), 3.f};
    const TrackingMeans got = Means(grid, ray, 60000);
    RGB tr, scatter;
    for (int c = 0; c < 3; ++c) {
        const float st = sa[c] + ss[c];
        tr[c] = std::exp(-st * 1.5f);
        scatter[c] = ss[c] / st * (1 - tr[c]);
    }
    ExpectNearRGB(got.tr, tr, 0.01f, "Tr");
    ExpectNearRGB(got.pass, tr, 0.015f, "pass-through weight");
    ExpectNearRGB(got.scatter, scatter, 0.015f, "scattering weight");
    float t0, t1;
    ASSERT_TRUE(grid.Extent(Ray{Vec3f(0, 0, 0), Vec3f(0, 0, 1), 100.f}, &t0, &t1));
    EXPECT_NEAR(t0, 6.f, 1e-5);
    EXPECT_NEAR(t1, 14.f, 1e-5);
    ExpectNearRGB(grid.Tau(ray, 0, 1), (sa + ss) * 0.5f, 1e-6f, "Tau");
    ExpectNearRGB(grid.SigmaS(Vec3f(1, 1, 10)), ss, 1e-6f, "SigmaS");
    ExpectNearRGB(grid.SigmaS(Vec3f(1, 1, 20)), RGB(0), 0, "SigmaS outside");
}

// A grey medium's weights are exact: σs/σt when it scatters, 1 when it passes through.
TEST(TrackedMedium, GreyWeightsAreTheAlbedoAndOne) {
    RGBGridMedium grid(0.f, 0.f, 1, 1, 1, {RGB(0.25f)}, {RGB(0.75f)}, 2.f, Vec3f(0, 0, 0),
                       Vec3f(1, 1, 1), Transform());
    for (int i = 0; i < 200; ++i) {
        MediumSampler s(uint64_t(i) + 1);
        MediumInteraction mi;
        bool scattered = false;
        const RGB w =
            grid.Sample(Ray{Vec3f(0.5f, 0.5f, -1), Vec3f(0, 0, 1), 5.f}, s, &mi, &scattered);
        ExpectNearRGB(w, RGB(scattered ? 0.75f : 1.f), 1e-6f, "weight");
    }
}

// Values sit at voxel centres, trilinear between them, an absent grid is 1, `scale` multiplies.
TEST(TrackedMedium, RGBGridLookup) {
    const std::vector<RGB> sa = {RGB(1, 0, 0), RGB(0, 1, 0)};  // nx = 2: x = 1/4 and 3/4
    RGBGridMedium grid(0.f, 0.f, 2, 1, 1, sa, {}, 3.f, Vec3f(0, 0, 0), Vec3f(4, 1, 1), Transform());
    RGB a, s;
    grid.Coefficients(Vec3f(2, 0.5f, 0.5f), &a, &s);  // halfway between the centres
    ExpectNearRGB(a, RGB(1.5f, 1.5f, 0), 1e-6f, "sigma_a at the middle");
    ExpectNearRGB(s, RGB(3), 0, "absent sigma_s");
    grid.Coefficients(Vec3f(1, 0.5f, 0.5f), &a, &s);  // the first centre
    ExpectNearRGB(a, RGB(3, 0, 0), 1e-6f, "sigma_a at a centre");
    EXPECT_FLOAT_EQ(grid.Majorant(), 6.f);  // (1 + 1) * 3
    EXPECT_EQ(grid.SigmaA(), RGB(3, 3, 0));
}

// The cloud is full below y = 0 of its space and thins upward: noise whose mean grows with
// "density".
TEST(TrackedMedium, CloudDensity) {
    auto cloud = [](float density) {
        return CloudMedium(RGB(1), RGB(1), 0.f, 0.f, density, 1.f, 5.f, Vec3f(-1, -1, -1),
                           Vec3f(2, 2, 2), Transform());
    };
    const CloudMedium thin = cloud(0.5f), thick = cloud(2.f);
    double meanThin = 0, meanThick = 0;
    int partial = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3f p(0.013f * float(i), 0.6f, 0.37f + 0.005f * float(i));
        EXPECT_EQ(thin.Density(Vec3f(p.x, -0.01f, p.z)), 1.f);
        EXPECT_LT(thin.Density(Vec3f(p.x, 1.01f, p.z)), 0.01f);
        const float d = thick.Density(p);
        EXPECT_GE(d, 0.f);
        EXPECT_LE(d, 1.f);
        partial += d > 0 && d < 1;
        meanThin += thin.Density(p);
        meanThick += d;
    }
    EXPECT_GT(partial, 100);
    EXPECT_GT(meanThick, 1.5 * meanThin);
    // Below y = 0 the cloud is homogeneous: Tr = exp(-σt d).
    const Ray ray{Vec3f(-0.5f, -0.5f, -1.f), Vec3f(0, 0, 1), 1.5f};
    const TrackingMeans got = Means(thin, ray, 20000);
    ExpectNearRGB(got.tr, RGB(std::exp(-2.f * 1.5f)), 0.005f, "Tr in the full part");
}

RGB Pixel(const Image &img) { return {img.pixels[0], img.pixels[1], img.pixels[2]}; }

// From a scene file: an absorbing chromatic "rgbgrid" slab placed by the CTM, seen against a
// white sky, transmits exp(-σa d) per channel (7/8 of the unit depth: the half-voxel falloff at
// the two faces along z of a 2-voxel grid), and so does pbrt-v4's "uniformgrid" of chromatic
// σa (pbrt-v3's "heterogeneous" would take the red channel's, with a warning); a "cloud"
// renders without warnings.
TEST(TrackedMedium, FromSceneFile) {
    const std::string head =
        "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 1 ]\n"
        "WorldBegin\nAttributeBegin\nTranslate 0 0 3\n";
    const std::string tail =
        "AttributeEnd\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nMaterial \"interface\"\n"
        "MediumInterface \"smoke\" \"\"\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 3 7 6 "
        "3 6 2 0 4 7 0 7 3 1 2 6 1 6 5 ] \"point3 P\" [ -10 -10 2 10 -10 2 10 10 2 -10 10 2 "
        "-10 -10 5 10 -10 5 10 10 5 -10 10 5 ]\n";
    // Delta tracking weighed over channels whose σt differ 8 times is noisy: 0.02 at 1024 spp.
    BuildSettings s = SizedSettings(1, 1, 16384, "volpath");
    const std::string grid =
        "MakeNamedMedium \"smoke\" \"string type\" \"rgbgrid\" \"integer nz\" 2 "
        "\"rgb sigma_a\" [ 0.2 0.8 1.6  0.2 0.8 1.6 ] \"rgb sigma_s\" [ 0 0 0  0 0 0 ] "
        "\"point3 p0\" [ -5 -5 0 ] \"point3 p1\" [ 5 5 1 ]\n";
    // pbrt-v4's "uniformgrid" with the same chromatic coefficients times a density grid.
    const std::string densityGrid =
        "MakeNamedMedium \"smoke\" \"string type\" \"uniformgrid\" \"integer nz\" 2 "
        "\"float density\" [ 2 2 ] \"rgb sigma_a\" [ 0.1 0.4 0.8 ] \"rgb sigma_s\" [ 0 0 0 ] "
        "\"point3 p0\" [ -5 -5 0 ] \"point3 p1\" [ 5 5 1 ]\n";
    const RGB want(std::exp(-0.2f * 0.875f), std::exp(-0.8f * 0.875f), std::exp(-1.6f * 0.875f));
    for (const std::string &medium : {grid, densityGrid}) {
        SCOPED_TRACE(medium);
        Rendered r = RenderSceneText("tracked", "grid.pbrt", head + medium + tail, s);
        EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
        ExpectNearRGB(Pixel(r.image), want, 0.01f, "chromatic slab");
    }

    const std::string cloud =
        "MakeNamedMedium \"smoke\" \"string type\" \"cloud\" \"float g\" 0.5\n";
    Rendered r = RenderSceneText("tracked", "cloud.pbrt", head + cloud + tail, s);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
    const RGB p = Pixel(r.image);
    EXPECT_TRUE(p.IsFinite());
    EXPECT_LT(p.r, 1.f);  // the unit box in front of the camera takes some light out
}

}  // namespace
}  // namespace prism
