#include "geometry/curves.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/transform.h"
#include "geometry/accel.h"
#include "shape_test_util.h"

namespace prism {
namespace {

using testing_util::RandomDirD;

// A straight cubic Bézier from (x0,0,0) to (x1,0,0), evenly parameterized (u linear in x).
std::vector<Vec3f> StraightX(float x0, float x1) {
    std::vector<Vec3f> P;
    for (int k = 0; k < 4; ++k) P.push_back({x0 + (x1 - x0) * float(k) / 3, 0, 0});
    return P;
}

std::unique_ptr<CurveSet> Straight(CurveType type, float width, const std::vector<Vec3f> &N = {},
                                   const Transform &t = Transform()) {
    return std::make_unique<CurveSet>(t, false, type, StraightX(-1, 1), width, width, N);
}

TEST(Curves, SegmentCounts) {
    EXPECT_EQ(CurveSegmentCount(4, 3, false), 1u);
    EXPECT_EQ(CurveSegmentCount(7, 3, false), 2u);
    EXPECT_EQ(CurveSegmentCount(5, 3, false), 0u);
    EXPECT_EQ(CurveSegmentCount(3, 3, false), 0u);
    EXPECT_EQ(CurveSegmentCount(3, 2, false), 1u);
    EXPECT_EQ(CurveSegmentCount(5, 2, false), 2u);
    EXPECT_EQ(CurveSegmentCount(4, 2, false), 0u);
    EXPECT_EQ(CurveSegmentCount(4, 3, true), 1u);
    EXPECT_EQ(CurveSegmentCount(6, 3, true), 3u);
    EXPECT_EQ(CurveSegmentCount(3, 3, true), 0u);
    EXPECT_EQ(CurveSegmentCount(3, 2, true), 1u);
    EXPECT_EQ(CurveSegmentCount(2, 2, true), 0u);
    EXPECT_EQ(CurveSegmentCount(4, 4, false), 0u);
    EXPECT_THROW(CubicBezierSegments({{0, 0, 0}, {1, 0, 0}}, 3, false), std::invalid_argument);
    EXPECT_THROW(CubicBezierSegments(StraightX(0, 1), 1, false), std::invalid_argument);
}

// Every basis and degree becomes cubic Bézier segments that trace the same curve: checked
// against the uniform B-spline and Bézier basis functions evaluated directly.
TEST(Curves, BasisConversionIsExact) {
    PCG32 rng(7);
    std::vector<Vec3f> P;
    for (int i = 0; i < 7; ++i)
        P.push_back(
            {float(rng.UniformDouble()), float(rng.UniformDouble()), float(rng.UniformDouble())});
    auto check = [&](int degree, bool bspline, auto reference) {
        const std::vector<Vec3f> b = CubicBezierSegments(P, degree, bspline);
        const size_t n = CurveSegmentCount(P.size(), degree, bspline);
        ASSERT_EQ(b.size(), 4 * n);
        for (size_t s = 0; s < n; ++s)
            for (double t : {0.0, 0.2, 0.5, 0.77, 1.0}) {
                Vec3d c[4];
                for (int k = 0; k < 4; ++k) c[k] = Vec3d(b[4 * s + size_t(k)]);
                const Vec3d got = BezierPoint(c, t), want = reference(s, t);
                EXPECT_LT(Length(got - want), 1e-6)
                    << degree << bspline << " seg " << s << " t " << t;
            }
    };
    auto p = [&](size_t i) { return Vec3d(P[i]); };
    check(3, false, [&](size_t s, double t) {
        const double u = 1 - t;
        return p(3 * s) * (u * u * u) + p(3 * s + 1) * (3 * u * u * t) +
               p(3 * s + 2) * (3 * u * t * t) + p(3 * s + 3) * (t * t * t);
    });
    check(2, false, [&](size_t s, double t) {
        const double u = 1 - t;
        return p(2 * s) * (u * u) + p(2 * s + 1) * (2 * u * t) + p(2 * s + 2) * (t * t);
    });
    check(3, true, [&](size_t s, double t) {
        const double u = 1 - t;
        return p(s) * (u * u * u / 6) + p(s + 1) * ((3 * t * t * t - 6 * t * t + 4) / 6) +
               p(s + 2) * ((-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6) +
               p(s + 3) * (t * t * t / 6);
    });
    check(2, true, [&](size_t s, double t) {
        const double u = 1 - t;
        return p(s) * (u * u / 2) + p(s + 1) * ((-2 * t * t + 2 * t + 1) / 2) +
               p(s + 2) * (t * t / 2);
    });
}

// A straight "cylinder" curve of constant width is a tube of radius width/2 about the x axis:
// Embree's round-curve hits against the analytic tube in distance; the hit sits on the centre
// plane facing the ray with an error bound that covers the tube's point, and the normal is
// pbrt's: the ray's side at v = 0.5, turned about the axis by (0.5 - v)·180° towards v's edge
// the other way from the tube's own normal.
TEST(Curves, CylinderMatchesAnalyticTube) {
    const double r = 0.1;
    Accel accel;
    accel.AddCurves(Straight(CurveType::Cylinder, float(2 * r)));
    accel.Commit();
    PCG32 rng(3);
    double worst = 0;
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        // Rays from random points 3 to 5 away, aimed at a random point near the tube's middle.
        const Vec3d target(0.6 * (rng.UniformDouble() - 0.5),
                           0.98 * r * (2 * rng.UniformDouble() - 1),
                           0.98 * r * (2 * rng.UniformDouble() - 1));
        Vec3d dir = RandomDirD(rng);
        const Vec3d o = target - dir * (3 + 2 * rng.UniformDouble());
        if (std::abs(dir.x) > 0.9) continue;  // grazing along the axis
        // The analytic entry distance: |(o + t d)_yz| = r.
        const double a = dir.y * dir.y + dir.z * dir.z, b = 2 * (o.y * dir.y + o.z * dir.z),
                     c = o.y * o.y + o.z * o.z - r * r;
        const double disc = b * b - 4 * a * c;
        if (disc <= 0) continue;
        const double tWant = (-b - std::sqrt(disc)) / (2 * a);
        const Vec3d pWant = o + dir * tWant;
        if (std::abs(pWant.x) > 0.5) continue;
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(Ray{Vec3f(o), Vec3f(dir), Infinity}, &si)) << i;
        ++hits;
        worst = std::max(worst, std::abs(double(si.t) - tWant) / tWant);
        EXPECT_NEAR(double(si.t), tWant, 1e-4 * tWant) << i;
        // The side facing the ray and the direction across it, in the plane of the axis.
        const Vec3d wo = -dir;
        const Vec3d facing = Normalize(Vec3d(0, wo.y, wo.z));
        const Vec3d across = Normalize(Cross(facing, Vec3d(1, 0, 0)));
        const double offset = Dot(pWant, across);
        EXPECT_NEAR(double(si.uv.y), 0.5 + 0.5 * offset / r, 2e-3) << i;
        const double theta = (0.5 - double(si.uv.y)) * Pi;
        const Vec3d nWant = facing * std::cos(theta) + across * std::sin(theta);
        EXPECT_GT(Dot(Vec3d(si.n), nWant), 1 - 1e-4) << i;
        // On the centre plane, and the bound covers the tube's point.
        EXPECT_LT(std::abs(Dot(Vec3d(si.p), facing)), 1e-4) << i;
        for (int k = 0; k < 3; ++k)
            EXPECT_LE(std::abs(double(si.p[k]) - pWant[k]), double(si.pError[k]) + 1e-6) << i;
    }
    EXPECT_GT(hits, 500);
    std::printf("cylinder curve: %d hits, worst relative t error %.2g\n", hits, worst);
}

// A "flat" curve faces every ray: a ray hits it where it passes within width/2 of the centre
// line, at the plane through the centre line facing the ray.
TEST(Curves, FlatCurveHitWidthAndFacing) {
    const float r = 0.1f;
    Accel accel;
    accel.AddCurves(Straight(CurveType::Flat, 2 * r));
    accel.Commit();
    for (float y : {-0.098f, -0.05f, 0.f, 0.03f, 0.097f}) {
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(Ray{{0.2f, y, 5}, {0, 0, -1}, Infinity}, &si)) << y;
        EXPECT_NEAR(si.t, 5.f, 2e-4f) << y;
        EXPECT_NEAR(si.n.z, 1.f, 1e-5f);  // toward the ray
        EXPECT_NEAR(si.uv.y, 0.5f + 0.5f * std::abs(y) / r * (si.uv.y >= 0.5f ? 1 : -1), 2e-3f);
    }
    for (float y : {-0.102f, 0.103f, 0.2f}) {
        SurfaceInteraction si;
        EXPECT_FALSE(accel.Intersect(Ray{{0.2f, y, 5}, {0, 0, -1}, Infinity}, &si)) << y;
    }
    // Seen from the side it still faces the ray, now spanning z.
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0.3f, 4, 0.09f}, {0, -1, 0}, Infinity}, &si));
    EXPECT_NEAR(si.t, 4.f, 2e-4f);
    EXPECT_NEAR(si.n.y, 1.f, 1e-5f);
    EXPECT_FALSE(accel.Intersect(Ray{{0.3f, 4, 0.11f}, {0, -1, 0}, Infinity}, &si));
}

// A "ribbon" lies across its normals: with N = +z everywhere it is the band |y| <= r in the
// plane z = 0 (a ray along z hits it, one along y in that plane misses), and a twist from +z
// to +y turns it by 45 degrees at the middle.
TEST(Curves, RibbonFollowsNormals) {
    const float r = 0.1f;
    {
        Accel accel;
        accel.AddCurves(Straight(CurveType::Ribbon, 2 * r, {{0, 0, 1}, {0, 0, 1}}));
        accel.Commit();
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(Ray{{0.1f, 0.05f, 5}, {0, 0, -1}, Infinity}, &si));
        EXPECT_NEAR(si.t, 5.f, 1e-4f);
        EXPECT_NEAR(std::abs(si.n.z), 1.f, 1e-5f);
        EXPECT_NEAR(si.n.z, 1.f, 1e-5f);  // N itself, not turned toward the ray
        ASSERT_TRUE(accel.Intersect(Ray{{0.1f, 0.05f, -5}, {0, 0, 1}, Infinity}, &si));
        EXPECT_NEAR(si.n.z, 1.f, 1e-5f);
        EXPECT_FALSE(accel.Intersect(Ray{{0.1f, 0.12f, 5}, {0, 0, -1}, Infinity}, &si));
        // A ray parallel to the band, just off its plane, misses it.
        EXPECT_FALSE(accel.Intersect(Ray{{0.1f, 4, 0.02f}, {0, -1, 0}, Infinity}, &si));
    }
    {
        Accel accel;
        accel.AddCurves(Straight(CurveType::Ribbon, 2 * r, {{0, 0, 1}, {0, 1, 0}}));
        accel.Commit();
        // At x = 0 (u = 0.5) the normal is (0, 1, 1)/sqrt 2 and the band runs along (0, 1, -1):
        // a ray down z at y = 0.05 meets it at z = -0.05.
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(Ray{{0, 0.05f, 5}, {0, 0, -1}, Infinity}, &si));
        EXPECT_NEAR(si.t, 5.05f, 2e-3f);
        EXPECT_NEAR(si.uv.x, 0.5f, 1e-3f);
        EXPECT_GT(Dot(si.n, Normalize(Vec3f(0, 1, 1))), 0.999f);
        // Near the ends the band is close to its end normals' planes.
        ASSERT_TRUE(accel.Intersect(Ray{{-0.98f, 0.05f, 5}, {0, 0, -1}, Infinity}, &si));
        EXPECT_NEAR(si.t, 5.f, 5e-3f);
        ASSERT_TRUE(accel.Intersect(Ray{{0.98f, 5, 0.05f}, {0, -1, 0}, Infinity}, &si));
        EXPECT_NEAR(si.t, 5.f, 5e-3f);
    }
}

// uv: u runs along the whole curve over all its segments, v across it; dpdu is d/du of the
// whole curve and dpdv spans the width.
TEST(Curves, UvAndDerivatives) {
    std::vector<Vec3f> b = StraightX(-1, 0), second = StraightX(0, 1);
    b.insert(b.end(), second.begin(), second.end());
    Accel accel;
    accel.AddCurves(
        std::make_unique<CurveSet>(Transform(), false, CurveType::Cylinder, b, 0.2f, 0.2f));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0.5f, 0, 5}, {0, 0, -1}, Infinity}, &si));
    EXPECT_NEAR(si.uv.x, 0.75f, 1e-4f);
    EXPECT_NEAR(si.uv.y, 0.5f, 1e-3f);
    EXPECT_NEAR(si.dpdu.x, 2.f, 1e-4f);  // x runs -1..1 over u 0..1
    EXPECT_NEAR(Length(si.dpdv), 0.2f, 1e-5f);
    EXPECT_GT(Dot(Normalize(Cross(si.dpdu, si.dpdv)), si.n), 0.999f);
    ASSERT_TRUE(accel.Intersect(Ray{{-0.5f, 0.05f, 5}, {0, 0, -1}, Infinity}, &si));
    EXPECT_NEAR(si.uv.x, 0.25f, 1e-4f);
    EXPECT_NEAR(std::abs(si.uv.y - 0.5f), 0.25f, 1e-3f);
}

// Widths taper linearly from width0 to width1 over the whole curve, and scale with the
// transform (a uniform scale of 2 doubles them).
TEST(Curves, TaperAndScale) {
    CurveSet c(Scale(2, 2, 2), false, CurveType::Cylinder, StraightX(-1, 1), 0.4f, 0.2f);
    auto seg = c.SegmentAt(0);
    EXPECT_NEAR(seg.Radius(0), 0.4, 1e-6);
    EXPECT_NEAR(seg.Radius(0.5), 0.3, 1e-6);
    EXPECT_NEAR(seg.Radius(1), 0.2, 1e-6);
    Accel accel;
    accel.AddCurves(std::make_unique<CurveSet>(c));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0, 0, 5}, {0, 0, -1}, Infinity}, &si));  // r 0.3 at x 0
    EXPECT_NEAR(si.t, 4.7f, 1e-3f);
}

// Rays leaving a curve hit (shadow rays, reflected rays to the ray's side) never hit the
// curve they leave: straight curves of every type (a ribbon with constant normals, so that no
// other part of the curve can be in the way), thin and thick, under random placements at
// scales 0.01 to 100; cylinders: every direction into the outer hemisphere; flat curves and
// ribbons: every direction on the ray's side (grazing ones too at the origin; elsewhere
// directions within 3 degrees of the surface are left out).
TEST(Curves, SpawnedRaysDoNotSelfIntersect) {
    PCG32 rng(11);
    for (CurveType type : {CurveType::Flat, CurveType::Cylinder, CurveType::Ribbon}) {
        for (float width : {0.002f, 0.2f}) {
            for (int placement = 0; placement < 6; ++placement) {
                const Transform t =
                    placement == 0 ? Transform() : testing_util::RandomTransform(rng);
                // A curve fewer than ~100 float steps of its position wide is noise to Embree's
                // float intersector (Prism renders camera-relative, so that is its distance
                // from the camera): such placements are left out.
                const double r = 0.5 * width * Length(t.Vector(Vec3d(1, 0, 0)));
                if (r < 1e-5 * Length(t.Point(Vec3d(0, 0, 0)))) continue;
                Accel accel;
                accel.AddCurves(
                    std::make_unique<CurveSet>(t, false, type, StraightX(-1, 1), width, width,
                                               std::vector<Vec3f>{{0, 0.3f, 1}, {0, 0.3f, 1}}));
                accel.Commit();
                int hits = 0, rays = 0, self = 0;
                for (int i = 0; i < 1500; ++i) {
                    const Vec3d target = t.Point(Vec3d(rng.UniformDouble() - 0.5, 0, 0));
                    const Vec3d dir = RandomDirD(rng);
                    const double dist = 5 * Length(t.Vector(Vec3d(1, 0, 0)));
                    const Ray cam{Vec3f(target - dir * dist), Vec3f(dir), Infinity};
                    SurfaceInteraction si;
                    if (!accel.Intersect(cam, &si)) continue;
                    ++hits;
                    for (int j = 0; j < 8; ++j) {
                        Vec3f w = Vec3f(RandomDirD(rng));
                        // The hemisphere about n that the outgoing rays take.
                        const float sign =
                            type == CurveType::Cylinder || Dot(si.wo, si.n) >= 0 ? 1.f : -1.f;
                        if (Dot(w, si.n) * sign < 0) w = -w;
                        if (placement > 0 && std::abs(Dot(w, si.n)) < 0.05f) continue;
                        ++rays;
                        if (accel.Occluded(si.SpawnRayTo(si.p + w * float(dist)))) ++self;
                        SurfaceInteraction again;
                        if (accel.Intersect(si.SpawnRay(w), &again)) ++self;
                    }
                }
                EXPECT_GT(hits, 900) << int(type);
                EXPECT_EQ(self, 0) << "type " << int(type) << " width " << width << ": " << self
                                   << " of " << rays << " rays";
            }
        }
    }
}

// A cylinder, as hair scatters through it whole: rays leaving a hit in every direction, into the
// tube as well as out of it, never meet it again, and the hit lies on the plane through the centre
// line facing the ray, at v's offset across it.
TEST(Curves, FibreRaysLeaveInEveryDirection) {
    PCG32 rng(5);
    for (float width : {0.002f, 0.2f}) {
        for (int placement = 0; placement < 4; ++placement) {
            const Transform t = placement == 0 ? Transform() : testing_util::RandomTransform(rng);
            const double r = 0.5 * width * Length(t.Vector(Vec3d(1, 0, 0)));
            if (r < 1e-5 * Length(t.Point(Vec3d(0, 0, 0)))) continue;
            auto tube = std::make_unique<CurveSet>(t, false, CurveType::Cylinder, StraightX(-1, 1),
                                                   width, width);
            Accel accel;
            accel.AddCurves(std::move(tube));
            accel.Commit();
            int hits = 0, self = 0;
            for (int i = 0; i < 1000; ++i) {
                const Vec3d target = t.Point(Vec3d(rng.UniformDouble() - 0.5, 0, 0));
                const Vec3d dir = RandomDirD(rng);
                const double dist = 5 * Length(t.Vector(Vec3d(1, 0, 0)));
                const Ray cam{Vec3f(target - dir * dist), Vec3f(dir), Infinity};
                SurfaceInteraction si;
                if (!accel.Intersect(cam, &si)) continue;
                ++hits;
                // On the centre plane: as far from the axis as v says, along the ray's view.
                const Vec3d axisPoint = t.Point(Vec3d(0, 0, 0));
                const Vec3d axis = Normalize(t.Vector(Vec3d(1, 0, 0)));
                Vec3d radial = Vec3d(si.p) - axisPoint;
                radial = radial - axis * Dot(radial, axis);
                EXPECT_NEAR(Length(radial), r * std::abs(2 * si.uv.y - 1), 0.02 * r);
                for (int j = 0; j < 8; ++j) {
                    const Vec3f w = Vec3f(RandomDirD(rng));
                    if (accel.Occluded(si.SpawnRayTo(si.p + w * float(dist)))) ++self;
                    SurfaceInteraction again;
                    if (accel.Intersect(si.SpawnRay(w), &again)) ++self;
                }
            }
            EXPECT_GT(hits, 600);
            EXPECT_EQ(self, 0) << "width " << width << " placement " << placement;
        }
    }
}

// Curves in an instance and moving curves go through the same Interaction.
TEST(Curves, InstancedAndMoving) {
    auto proto = std::make_shared<Accel>();
    proto->AddCurves(Straight(CurveType::Cylinder, 0.2f));
    proto->Commit();
    Accel accel;
    accel.AddInstance(proto, Translate(Vec3d(0, 0, -1)));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0.2f, 0, 5}, {0, 0, -1}, Infinity}, &si));
    EXPECT_NEAR(si.t, 5.9f, 1e-3f);
    EXPECT_NEAR(si.n.z, 1.f, 1e-3f);
    EXPECT_NEAR(si.uv.x, 0.6f, 1e-3f);

    auto moving = Straight(CurveType::Cylinder, 0.2f);
    moving->SetMotionSteps({Translate(Vec3d(0, 1, 0))});
    Accel m;
    m.AddCurves(std::move(moving));
    m.Commit();
    Ray r{{0.2f, 0.5f, 5}, {0, 0, -1}, Infinity, 0, 0.5f};
    ASSERT_TRUE(m.Intersect(r, &si));
    EXPECT_NEAR(si.t, 4.9f, 1e-3f);
    EXPECT_NEAR(si.p.y, 0.5f, 1e-3f);
    EXPECT_NEAR(si.n.z, 1.f, 1e-3f);
    r.time = 0;
    EXPECT_FALSE(m.Intersect(r, &si));
}

}  // namespace
}  // namespace prism
