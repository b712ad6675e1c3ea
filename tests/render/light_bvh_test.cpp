// The light BVH (render/light_bvh.h): a part's importance is zero only where it cannot light
// the point, a node's bounds hold its children's, the probabilities of the choices sum to one
// and are those Sample draws with, and in a scene of a thousand lamps the path tracer's image
// is the same as by power but far less noisy.
#include "render/light_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "core/rng.h"
#include "core/transform.h"
#include "geometry/triangle_mesh.h"
#include "render/area_light.h"
#include "render/light.h"
#include "support/image_stats.h"
#include "support/render_text.h"

namespace prism {
namespace {

using namespace test;

Vec3f RandomPoint(PCG32 &rng, float scale) {
    return Vec3f(rng.Uniform() - 0.5f, rng.Uniform() - 0.5f, rng.Uniform() - 0.5f) * scale;
}

Vec3f RandomDirection(PCG32 &rng) {
    const float z = 1 - 2 * rng.Uniform(), phi = 6.2831853f * rng.Uniform();
    const float r = std::sqrt(std::max(0.f, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// The bounds of a one-sided emitting triangle (a, b, c), normal (b - a) x (c - a).
LightBounds TriangleBounds(const Vec3f &a, const Vec3f &b, const Vec3f &c, bool twoSided) {
    LightBounds lb;
    lb.bounds = Bounds3f(a, b);
    lb.bounds.Expand(c);
    lb.w = Normalize(Cross(b - a, c - a));
    lb.phi = 1;
    lb.cosTheta_o = 1;
    lb.cosTheta_e = 0;
    lb.twoSided = twoSided;
    return lb;
}

// Whether any of many points of triangle (a, b, c) emits toward p (its front faces p).
bool TriangleFacesPoint(const Vec3f &a, const Vec3f &b, const Vec3f &c, const Vec3f &p,
                        PCG32 &rng) {
    const Vec3f n = Normalize(Cross(b - a, c - a));
    for (int i = 0; i < 64; ++i) {
        float u = rng.Uniform(), v = rng.Uniform();
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const Vec3f q = a + (b - a) * u + (c - a) * v;
        if (Dot(n, p - q) > 1e-4f * Length(p - q)) return true;
    }
    return false;
}

TEST(LightBounds, OneSidedEmitterLightsOnlyItsFront) {
    // A unit square's triangle at z = 1 facing down.
    const LightBounds lb = TriangleBounds({0, 0, 1}, {0, 1, 1}, {1, 0, 1}, false);
    ASSERT_NEAR(lb.w.z, -1.f, 1e-6f);
    EXPECT_GT(lb.Importance({0.3f, 0.3f, 0}, {0, 0, 1}), 0.f);
    EXPECT_GT(lb.Importance({5, 5, 0.9f}, {0, 0, 0}), 0.f);  // grazing, still below
    EXPECT_EQ(lb.Importance({0.3f, 0.3f, 2}, {0, 0, 1}), 0.f);
    EXPECT_EQ(lb.Importance({5, 5, 3}, {0, 0, 0}), 0.f);
    LightBounds both = lb;
    both.twoSided = true;
    EXPECT_GT(both.Importance({0.3f, 0.3f, 2}, {0, 0, 1}), 0.f);
    // Farther is less important, about as 1/d^2.
    const float near = lb.Importance({0.3f, 0.3f, -9}, {0, 0, 1});
    const float far = lb.Importance({0.3f, 0.3f, -19}, {0, 0, 1});
    EXPECT_NEAR(far / near, 0.25f, 0.02f);
}

TEST(LightBounds, ZeroImportanceMeansTheTriangleCannotLightThePoint) {
    PCG32 rng(7);
    int zeros = 0, positives = 0;
    for (int t = 0; t < 4000; ++t) {
        const Vec3f a = RandomPoint(rng, 2), b = a + RandomPoint(rng, 1),
                    c = a + RandomPoint(rng, 1);
        if (!(LengthSquared(Cross(b - a, c - a)) > 1e-6f)) continue;
        const LightBounds lb = TriangleBounds(a, b, c, false);
        const Vec3f p = RandomPoint(rng, 6);
        const Vec3f n = rng.Uniform() < 0.5f ? Vec3f(0, 0, 0) : RandomDirection(rng);
        if (lb.Importance(p, n) > 0) {
            ++positives;
            continue;
        }
        ++zeros;
        EXPECT_FALSE(TriangleFacesPoint(a, b, c, p, rng)) << "trial " << t;
    }
    // Both outcomes are exercised.
    EXPECT_GT(zeros, 500);
    EXPECT_GT(positives, 500);
}

TEST(LightBounds, TheUnionOfTwoPartsBoundsBoth) {
    PCG32 rng(11);
    int zeros = 0;
    for (int t = 0; t < 4000; ++t) {
        LightBounds parts[2];
        for (LightBounds &lb : parts) {
            const Vec3f a = RandomPoint(rng, 4);
            lb = TriangleBounds(a, a + RandomPoint(rng, 1), a + RandomPoint(rng, 1),
                                rng.Uniform() < 0.2f);
            if (rng.Uniform() < 0.3f) {  // a cone of normals, as a node of several triangles
                lb.cosTheta_o = 2 * rng.Uniform() - 1;
                lb.w = RandomDirection(rng);
            }
            lb.phi = 0.5f + rng.Uniform();
        }
        const LightBounds u = Union(parts[0], parts[1]);
        EXPECT_FLOAT_EQ(u.phi, parts[0].phi + parts[1].phi);
        for (const LightBounds &lb : parts) {
            EXPECT_LE(u.bounds.pMin.x, lb.bounds.pMin.x);
            EXPECT_GE(u.bounds.pMax.z, lb.bounds.pMax.z);
            // The union's cone holds the part's: the part's axis is within theta_u -
            // theta_part of the union's axis (any cone, when the union's is the sphere).
            if (u.cosTheta_o <= -1) continue;
            const float thetaU = std::acos(std::clamp(u.cosTheta_o, -1.f, 1.f));
            const float thetaP = std::acos(std::clamp(lb.cosTheta_o, -1.f, 1.f));
            const float thetaD = std::acos(std::clamp(Dot(u.w, lb.w), -1.f, 1.f));
            EXPECT_LE(thetaD + thetaP, thetaU + 1e-3f) << "trial " << t;
        }
        for (int k = 0; k < 4; ++k) {
            const Vec3f p = RandomPoint(rng, 10);
            const Vec3f n = RandomDirection(rng);
            if (u.Importance(p, n) > 0) continue;
            ++zeros;
            EXPECT_EQ(parts[0].Importance(p, n), 0.f) << "trial " << t;
            EXPECT_EQ(parts[1].Importance(p, n), 0.f) << "trial " << t;
        }
    }
    EXPECT_GT(zeros, 100);
}

TEST(LightBounds, SpotLightLightsOnlyInsideItsCone) {
    SpotLight spot({0, 0, 0}, {0, 0, -1}, RGB(1), 30, 5);
    std::vector<LightPartBounds> parts;
    spot.Bounds(&parts);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_EQ(parts[0].prim, -1);
    const LightBounds &lb = parts[0].lb;
    const float t29 = std::tan(29 * 3.14159265f / 180), t31 = std::tan(31 * 3.14159265f / 180);
    EXPECT_GT(lb.Importance({t29, 0, -1}, {0, 0, 0}), 0.f);
    EXPECT_EQ(lb.Importance({t31, 0, -1}, {0, 0, 0}), 0.f);
    EXPECT_EQ(lb.Importance({0, 0, 1}, {0, 0, 0}), 0.f);
}

// A mesh of n random one-sided triangles in a 10-unit box, as an emissive mesh.
std::unique_ptr<TriangleMesh> RandomTriangles(int n, uint64_t seed) {
    PCG32 rng(seed);
    std::vector<Vec3f> P;
    std::vector<uint32_t> idx;
    for (int i = 0; i < n; ++i) {
        const Vec3f a = RandomPoint(rng, 10);
        for (const Vec3f &p : {a, a + RandomPoint(rng, 0.5f), a + RandomPoint(rng, 0.5f)}) {
            idx.push_back(uint32_t(P.size()));
            P.push_back(p);
        }
    }
    return std::make_unique<TriangleMesh>(Transform(), false, P, idx, std::vector<Vec3f>{},
                                          std::vector<Vec2f>{});
}

struct Lights {
    std::unique_ptr<TriangleMesh> mesh;
    std::vector<std::unique_ptr<Light>> owned;
    std::vector<const Light *> list;
    void Add(std::unique_ptr<Light> l) {
        list.push_back(l.get());
        owned.push_back(std::move(l));
    }
};

// An emissive mesh of 300 triangles, a point light, a spot light and a distant light.
Lights MixedLights() {
    Lights l;
    l.mesh = RandomTriangles(300, 3);
    l.Add(std::make_unique<DiffuseAreaLight>(nullptr, l.mesh.get(), RGB(1, 2, 3), false, 1));
    l.Add(std::make_unique<PointLight>(Vec3f(1, 2, 3), RGB(10)));
    l.Add(std::make_unique<SpotLight>(Vec3f(-3, 4, 0), Vec3f(0, -1, 0), RGB(30), 40, 10));
    l.Add(std::make_unique<DistantLight>(Vec3f(0, 1, 0), RGB(1)));
    return l;
}

TEST(LightBVH, ChoicesSumToOneAndAreDrawnWithTheirProbability) {
    Lights l = MixedLights();
    const LightBVH bvh(l.list);
    EXPECT_EQ(bvh.NumParts(), 302u);  // 300 triangles, the point and the spot light
    EXPECT_EQ(bvh.NumNodes(), 2 * 302u - 1);
    PCG32 rng(5);
    for (int trial = 0; trial < 8; ++trial) {
        const Vec3f p = RandomPoint(rng, 12);
        const Vec3f n = trial % 2 ? RandomDirection(rng) : Vec3f(0, 0, 0);
        // Every (light, prim), the mesh's triangles one by one.
        std::map<std::pair<int, int>, double> pmf;
        double sum = 0;
        for (int prim = 0; prim < 300; ++prim) sum += pmf[{0, prim}] = bvh.Pmf(p, n, 0, prim);
        // (A triangle that cannot light p has probability 0: checked below by its count.)
        for (int light = 1; light < 4; ++light) sum += pmf[{light, -1}] = bvh.Pmf(p, n, light, -1);
        // At most 1: a node's bounds may allow light its children's do not (the share of u
        // that chooses no light: a third here, where half the triangles face away from p in
        // every direction; little where emitters face one way, as lamps do).
        EXPECT_LE(sum, 1.0 + 1e-5) << "trial " << trial;
        EXPECT_GT(sum, 0.5) << "trial " << trial;
        // The distant light: one light from infinitely far, against the BVH's one.
        EXPECT_NEAR((pmf[{3, -1}]), 0.5, 1e-6);
        // Drawn with stratified u: each choice's frequency is its probability, and Sample
        // reports that probability.
        const int draws = 1 << 16;
        std::map<std::pair<int, int>, int> count;
        int none = 0;
        for (int i = 0; i < draws; ++i) {
            const LightPick pick = bvh.Sample((float(i) + 0.5f) / float(draws), p, n);
            if (pick.light < 0) {
                ++none;
                continue;
            }
            const auto key = std::make_pair(pick.light, pick.prim);
            ++count[key];
            ASSERT_NEAR(pick.prob, pmf[key], 1e-5 + 1e-4 * pmf[key]);
        }
        EXPECT_NEAR(double(none) / draws, 1 - sum, 0.002) << "trial " << trial;
        double tv = 0;  // total variation distance
        for (const auto &[key, q] : pmf) tv += std::abs(double(count[key]) / draws - q);
        EXPECT_LT(tv, 0.01) << "trial " << trial;
    }
}

TEST(LightBVH, AChoiceThatCannotLightThePointIsNeverMade) {
    // Five squares' triangles at y = 1 facing down (more than a mesh chosen whole has): a
    // point above them has no light to choose.
    Lights l;
    std::vector<Vec3f> P;
    std::vector<uint32_t> idx;
    for (int i = 0; i < 5; ++i) {
        const float x = float(i) * 2;
        const uint32_t b = uint32_t(P.size());
        for (const Vec3f &p :
             {Vec3f(x, 1, 0), Vec3f(x + 1, 1, 0), Vec3f(x + 1, 1, 1), Vec3f(x, 1, 1)})
            P.push_back(p);
        for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(b + k);
    }
    l.mesh = std::make_unique<TriangleMesh>(Transform(), false, P, idx, std::vector<Vec3f>{},
                                            std::vector<Vec2f>{});
    l.Add(std::make_unique<DiffuseAreaLight>(nullptr, l.mesh.get(), RGB(1), false, 1));
    const LightBVH bvh(l.list);
    ASSERT_EQ(bvh.NumParts(), 10u);
    const Vec3f below(3, 0, 0.5f), above(3, 2, 0.5f);
    const Vec3f n = Normalize(Cross(P[1] - P[0], P[2] - P[0]));
    ASSERT_LT(n.y, 0.f) << "the squares must face down";
    EXPECT_GE(bvh.Sample(0.3f, below, {0, 1, 0}).light, 0);
    EXPECT_EQ(bvh.Sample(0.3f, above, {0, 1, 0}).light, -1);
    EXPECT_EQ(bvh.Pmf(above, {0, 1, 0}, 0, 3), 0.f);
    // The square right above the point is chosen most often: the BVH weighs by importance.
    int nearest = 0;
    for (int i = 0; i < 1000; ++i)
        nearest += bvh.Sample((float(i) + 0.5f) / 1000, {0.5f, 0, 0.5f}, {0, 1, 0}).prim / 2 == 0;
    EXPECT_GT(nearest, 600);
}

TEST(LightBVH, LightsFromInfinitelyFarTakeAShareByImportance) {
    // A spot light pointing down from y = 2 and two distant lights of importance 1 and 3.
    Lights l;
    l.Add(std::make_unique<SpotLight>(Vec3f(0, 2, 0), Vec3f(0, -1, 0), RGB(10), 30, 5));
    l.Add(std::make_unique<DistantLight>(Vec3f(0, 1, 0), RGB(1)));
    l.Add(std::make_unique<DistantLight>(Vec3f(1, 0, 0), RGB(1)));
    const LightBVH bvh(l.list, {0, 1, 3});
    const Vec3f up(0, 1, 0);
    std::vector<LightPartBounds> spot;
    l.list[0]->Bounds(&spot);
    for (const Vec3f &p : {Vec3f(0, 1.9f, 0), Vec3f(0, 0, 0), Vec3f(0, -40, 0), Vec3f(5, 0, 0)}) {
        const double root = spot[0].lb.Importance(p, up);
        // The share of the distant lights: half by importance, 4 / (4 + root), half even; all
        // of it where the spot light cannot reach.
        const double share = root > 0 ? 0.25 + 0.5 * (4 / (4 + root)) : 1.0;
        EXPECT_NEAR(bvh.Pmf(p, up, 1, -1), 0.25 * share, 1e-6) << p.y;
        EXPECT_NEAR(bvh.Pmf(p, up, 2, -1), 0.75 * share, 1e-6) << p.y;
        EXPECT_NEAR(bvh.Pmf(p, up, 0, -1), 1 - share, 1e-6) << p.y;
        int counts[3] = {0, 0, 0};
        const int draws = 4000;
        for (int i = 0; i < draws; ++i) {
            const LightPick pick = bvh.Sample((float(i) + 0.5f) / draws, p, up);
            ASSERT_GE(pick.light, 0);
            ++counts[pick.light];
            EXPECT_NEAR(pick.prob, bvh.Pmf(p, up, pick.light, -1), 1e-6);
        }
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(double(counts[k]) / draws, bvh.Pmf(p, up, k, -1), 1e-3) << k;
    }
    // Close under the spot light the even half still goes to the distant lights; outside its
    // cone the spot gets none.
    EXPECT_NEAR(bvh.Pmf({0, 1.9f, 0}, up, 0, -1), 0.75, 1e-3);
    EXPECT_EQ(bvh.Pmf({5, 0, 0}, up, 0, -1), 0.f);
}

TEST(LightBVH, AMeshOfFewTrianglesIsChosenWhole) {
    // A quad (two triangles): one part, prim -1, chosen always where it is the only light.
    Lights l;
    l.mesh = std::make_unique<TriangleMesh>(
        Transform(), false, std::vector<Vec3f>{{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
        std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, std::vector<Vec3f>{}, std::vector<Vec2f>{});
    l.Add(std::make_unique<DiffuseAreaLight>(nullptr, l.mesh.get(), RGB(1), false, 1));
    std::vector<LightPartBounds> parts;
    l.list[0]->Bounds(&parts);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_EQ(parts[0].prim, -1);
    EXPECT_NEAR(parts[0].lb.phi, 3.14159265f, 1e-5f);  // pi x area 1 x L 1
    const LightBVH bvh(l.list);
    const LightPick pick = bvh.Sample(0.7f, {0.5f, 0, 0.5f}, {0, 1, 0});
    EXPECT_EQ(pick.light, 0);
    EXPECT_EQ(pick.prim, -1);
    EXPECT_EQ(pick.prob, 1.f);
    EXPECT_EQ(bvh.Pmf({0.5f, 0, 0.5f}, {0, 1, 0}, 0, -1), 1.f);
}

TEST(LightBVH, AMovingMeshIsOnePartOverItsWholeWay) {
    // 20 triangles moving 5 units along x during the shutter: one part, every direction,
    // whose box holds both ends.
    Lights l;
    l.mesh = RandomTriangles(20, 8);
    l.mesh->SetMotionSteps({Translate(Vec3d(5, 0, 0))});
    l.Add(std::make_unique<DiffuseAreaLight>(nullptr, l.mesh.get(), RGB(1), false, 1));
    std::vector<LightPartBounds> parts;
    l.list[0]->Bounds(&parts);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_EQ(parts[0].prim, -1);
    EXPECT_EQ(parts[0].lb.cosTheta_o, -1.f);
    const Bounds3f start = l.mesh->RenderBounds();
    EXPECT_LE(parts[0].lb.bounds.pMin.x, start.pMin.x);
    EXPECT_GE(parts[0].lb.bounds.pMax.x, start.pMax.x + 5 - 1e-4f);
}

TEST(LightBVH, DepthStaysBoundedOnDegenerateLayouts) {
    // Triangles at exponentially growing distances along a line, then all at one place.
    for (const bool coincident : {false, true}) {
        std::vector<Vec3f> P;
        std::vector<uint32_t> idx;
        for (int i = 0; i < 5000; ++i) {
            const float x = coincident ? 0.f : std::ldexp(1.f, i % 100) * (1 + float(i) / 5000);
            for (const Vec3f &p : {Vec3f(x, 0, 0), Vec3f(x, 1, 0), Vec3f(x, 0, 1)}) {
                idx.push_back(uint32_t(P.size()));
                P.push_back(p);
            }
        }
        Lights l;
        l.mesh = std::make_unique<TriangleMesh>(Transform(), false, P, idx, std::vector<Vec3f>{},
                                                std::vector<Vec2f>{});
        l.Add(std::make_unique<DiffuseAreaLight>(nullptr, l.mesh.get(), RGB(1), true, 1));
        const LightBVH bvh(l.list);
        EXPECT_EQ(bvh.NumParts(), 5000u);
        EXPECT_LE(bvh.Depth(), 64 + 14) << coincident;
        double sum = 0;
        for (int prim = 0; prim < 5000; ++prim) sum += bvh.Pmf({3, 2, 1}, {0, 0, 0}, 0, prim);
        EXPECT_LE(sum, 1.0 + 1e-4) << coincident;
        EXPECT_GT(sum, 0.5) << coincident;
    }
}

// A floor under a grid of 12 x 12 small lamps of random colours and heights, seen from above
// (maxdepth 1: direct light only, where the light choice is all the noise).
std::string ManyLamps(const std::string &sampler, int spp) {
    PCG32 rng(9);
    std::string s =
        "LookAt 0 6 9  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
        "Film \"rgb\" \"integer xresolution\" 40 \"integer yresolution\" 30\n"
        "Sampler \"independent\" \"integer pixelsamples\" " +
        std::to_string(spp) + "\nIntegrator \"path\" \"integer maxdepth\" 1 " +
        "\"string lightsampler\" \"" + sampler +
        "\"\nWorldBegin\nMaterial \"diffuse\"\n"
        "Shape \"trianglemesh\" \"point3 P\" [-10 0 -10 10 0 -10 10 0 10 -10 0 10] "
        "\"integer indices\" [0 2 1 0 3 2]\n";
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) {
            const float x = -8 + 16 * (float(i) + 0.5f) / 12, z = -8 + 16 * (float(j) + 0.5f) / 12;
            const float y = 0.5f + 0.6f * rng.Uniform(), e = 0.1f;
            char buf[400];
            std::snprintf(buf, sizeof buf,
                          "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [%g %g %g]\n"
                          "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point3 P\" "
                          "[%g %g %g %g %g %g %g %g %g %g %g %g]\nAttributeEnd\n",
                          4 * rng.Uniform(), 4 * rng.Uniform(), 4 * rng.Uniform(), x - e, y, z - e,
                          x + e, y, z - e, x + e, y, z + e, x - e, y, z + e);
            s += buf;
        }
    return s;
}

TEST(LightBVH, ManyLampsRenderTheSameImageWithFarLessNoise) {
    const Image ref = RenderSceneText("light_bvh", "lamps_ref", ManyLamps("bvh", 1024)).image;
    const Image bvh = RenderSceneText("light_bvh", "lamps_bvh", ManyLamps("bvh", 16)).image;
    const Image power = RenderSceneText("light_bvh", "lamps_power", ManyLamps("power", 16)).image;
    const Image powerRef =
        RenderSceneText("light_bvh", "lamps_power_ref", ManyLamps("power", 256)).image;
    // The same image: the converged means agree within the noise of the power render.
    EXPECT_NEAR(MeanValue(powerRef), MeanValue(ref), 0.01 * MeanValue(ref));
    // At 16 spp the BVH's error is under a third of power's (0.2 when written).
    EXPECT_LT(RelL1(bvh, ref), 0.33 * RelL1(power, ref));
}

}  // namespace
}  // namespace prism
