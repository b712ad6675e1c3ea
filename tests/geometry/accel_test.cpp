#include "geometry/accel.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/transform.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace prism {
namespace {

TEST(Accel, MeshAndSphereClosestHit) {
    Accel accel;
    // A unit quad at z = 5 and a sphere of radius 1 at z = 2.
    std::vector<Vec3f> P = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
    int mesh = accel.AddMesh(std::make_unique<TriangleMesh>(
        Transform(), false, P, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    int sphere = accel.AddAnalytic(
        std::make_unique<Sphere>(Translate(Vec3d(0, 0, 2)), false, 1, -1, 1, 360));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0, 0, 0}, {0, 0, 1}, Infinity}, &si));
    EXPECT_EQ(si.shape, sphere);
    EXPECT_NEAR(si.t, 1.0f, 1e-6f);
    EXPECT_NEAR(si.n.z, -1.f, 1e-6f);
    ASSERT_TRUE(accel.Intersect(Ray{{0.9f, 0.9f, 0}, {0, 0, 1}, Infinity}, &si));
    EXPECT_EQ(si.shape, mesh);
    EXPECT_NEAR(si.t, 5.0f, 1e-6f);
    // Triangle geometric normal: (p1-p0) x (p2-p0) = +z for this winding.
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);
    EXPECT_FALSE(accel.Intersect(Ray{{5, 5, 0}, {0, 0, 1}, Infinity}, &si));
    // tMax limits the query.
    EXPECT_FALSE(accel.Occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0.5f}));
    EXPECT_TRUE(accel.Occluded(Ray{{0, 0, 0}, {0, 0, 1}, 1.5f}));
}

// Rays Embree cannot trace (it asserts on components beyond its FLT_LARGE, 1.844e18) are
// misses and unoccluded in every query, single and packet, instead of an abort.
TEST(Accel, UntraceableRaysAreMissesNotAborts) {
    Accel accel;
    accel.AddAnalytic(std::make_unique<Sphere>(Transform(), false, 1, -1, 1, 360));
    accel.Commit();
    const Ray far{{1e30f, 0, 0}, {-1, 0, 0}, Infinity}, huge{{0, 0, -5}, {0, 0, 3e38f}, Infinity};
    const Ray nan{{0, 0, -5}, {0, 0, std::nanf("")}, Infinity}, ok{{0, 0, -5}, {0, 0, 1}, Infinity};
    for (const Ray &r : {far, huge, nan}) {
        EXPECT_FALSE(TraceableRay(r));
        RawHit h;
        EXPECT_FALSE(accel.IntersectRaw(r, &h));
        EXPECT_FALSE(accel.Occluded(r));
    }
    EXPECT_TRUE(TraceableRay(ok));
    const Ray packet[4] = {far, ok, huge, nan};
    RawHit hits[4];
    bool occluded[4];
    accel.IntersectPacket(packet, 4, hits, occluded);
    EXPECT_EQ(hits[0].shape, -1);
    EXPECT_EQ(hits[1].shape, 0);
    EXPECT_EQ(hits[2].shape, -1);
    EXPECT_EQ(hits[3].shape, -1);
    EXPECT_FALSE(occluded[0]);
    EXPECT_TRUE(occluded[1]);
}

TEST(Accel, IntersectAndOccludedAgree) {
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        PCG32 rng(21);
        for (int i = 0; i < 20; ++i) {
            Vec3d c(10 * rng.UniformDouble(), 10 * rng.UniformDouble(), 10 * rng.UniformDouble());
            accel.AddAnalytic(std::make_unique<Sphere>(Translate(c), rng.Uniform() < 0.5f,
                                                       0.2 + rng.UniformDouble(), -0.5, 1, 300));
        }
        accel.Commit();
        for (int i = 0; i < 20000; ++i) {
            Vec3f o(float(20 * rng.UniformDouble() - 5), float(20 * rng.UniformDouble() - 5), -10);
            Vec3f d = Normalize(
                Vec3f(float(rng.UniformDouble() - 0.5), float(rng.UniformDouble() - 0.5), 1));
            float tMax = float(40 * rng.UniformDouble());
            SurfaceInteraction si;
            bool hit = accel.Intersect(Ray{o, d, tMax}, &si);
            EXPECT_EQ(hit, accel.Occluded(Ray{o, d, tMax})) << i;
            if (hit) {
                EXPECT_LT(si.t, tMax);
            }
        }
    }
}

TEST(Accel, PacketQueriesMatchSingleRays) {
    // rtcIntersect16 reaches the N-wide user-geometry callbacks with valid masks; every
    // lane must agree with the single-ray query, hit for hit.
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        PCG32 rng(33);
        for (int i = 0; i < 12; ++i) {
            Vec3d c(6 * rng.UniformDouble(), 6 * rng.UniformDouble(), 6 * rng.UniformDouble());
            accel.AddAnalytic(std::make_unique<Sphere>(Translate(c), false,
                                                       0.3 + rng.UniformDouble(), -1, 0.8, 320));
        }
        std::vector<Vec3f> P = {{-10, -10, 7}, {10, -10, 7}, {10, 10, 7}, {-10, 10, 7}};
        accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P,
                                                     std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        accel.Commit();
        for (int batch = 0; batch < 500; ++batch) {
            int n = 1 + batch % 16;
            Ray rays[16];
            for (int i = 0; i < n; ++i) {
                rays[i].o = Vec3f(float(8 * rng.UniformDouble() - 1),
                                  float(8 * rng.UniformDouble() - 1), -5);
                rays[i].d = Normalize(
                    Vec3f(float(rng.UniformDouble() - 0.5), float(rng.UniformDouble() - 0.5), 1));
                rays[i].tMax = float(5 + 15 * rng.UniformDouble());
            }
            RawHit hits[16];
            bool occ[16];
            accel.IntersectPacket(rays, n, hits, occ);
            for (int i = 0; i < n; ++i) {
                RawHit single;
                bool hit = accel.IntersectRaw(rays[i], &single);
                ASSERT_EQ(hit, hits[i].shape >= 0) << "batch " << batch << " lane " << i;
                EXPECT_EQ(occ[i], hit);
                if (hit) {
                    EXPECT_EQ(single.shape, hits[i].shape);
                    EXPECT_EQ(single.t, hits[i].t);
                }
            }
        }
    }
}

// The object-space hit the Embree callback records (RawHit::object) is exactly what the root
// routine gives when Interaction runs it again, for single rays and for packets.
TEST(Accel, RecordedObjectHitMatchesResolve) {
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        PCG32 rng(7);
        for (int i = 0; i < 12; ++i) {
            Vec3d c(6 * rng.UniformDouble(), 6 * rng.UniformDouble(), 6 * rng.UniformDouble());
            accel.AddAnalytic(std::make_unique<Sphere>(Translate(c), false,
                                                       0.3 + rng.UniformDouble(), -0.7, 1, 300));
        }
        accel.Commit();
        int recorded = 0;
        for (int batch = 0; batch < 300; ++batch) {
            Ray rays[16];
            for (int i = 0; i < 16; ++i) {
                rays[i].o = Vec3f(float(8 * rng.UniformDouble() - 1),
                                  float(8 * rng.UniformDouble() - 1), -5);
                rays[i].d = Normalize(
                    Vec3f(float(rng.UniformDouble() - 0.5), float(rng.UniformDouble() - 0.5), 1));
                rays[i].tMax = float(5 + 15 * rng.UniformDouble());
            }
            RawHit hits[16];
            accel.IntersectPacket(rays, 16, hits);
            for (int i = 0; i < 16; ++i) {
                RawHit single;
                if (!accel.IntersectRaw(rays[i], &single)) continue;
                ASSERT_TRUE(single.hasObject);
                ASSERT_TRUE(hits[i].hasObject);
                ++recorded;
                ObjectHit again;
                ASSERT_TRUE(accel.Analytic(single.shape)
                                ->Intersect(rays[i].o, rays[i].d, rays[i].tMin, rays[i].tMax, prec,
                                            &again));
                for (const ObjectHit *oh : {&single.object, &hits[i].object}) {
                    EXPECT_EQ(oh->t, again.t);
                    EXPECT_EQ(oh->p, again.p);
                    EXPECT_EQ(oh->pError, again.pError);
                    EXPECT_EQ(oh->phi, again.phi);
                }
                RawHit forced = single;
                forced.hasObject = false;
                SurfaceInteraction a = accel.Interaction(rays[i], single),
                                   b = accel.Interaction(rays[i], forced);
                EXPECT_EQ(a.p, b.p);
                EXPECT_EQ(a.pError, b.pError);
                EXPECT_EQ(a.n, b.n);
            }
        }
        EXPECT_GT(recorded, 100);
    }
}

TEST(Accel, ReverseOrientationFlipsNormals) {
    Accel accel;
    accel.AddAnalytic(std::make_unique<Sphere>(Transform(), true, 1, -1, 1, 360));
    accel.AddAnalytic(std::make_unique<Sphere>(Translate(Vec3d(5, 0, 0)) * Scale(-1, 1, 1), false,
                                               1, -1, 1, 360));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0, 0, -5}, {0, 0, 1}, Infinity}, &si));
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);  // flipped: points inward
    ASSERT_TRUE(accel.Intersect(Ray{{5, 0, -5}, {0, 0, 1}, Infinity}, &si));
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);  // handedness swap flips too
}

// The triangle normal: float where the edges' angle keeps it within a few tens of ulps of the
// double result, double for slivers; Interaction without uv/dpdu keeps p, pError and n.
TEST(TriangleMesh, NormalAndLeanInteraction) {
    std::vector<Vec3f> P = {{0, 0, 0}, {1, 0, 0},    {0.3f, 1, 0.2f},          // well shaped
                            {0, 0, 0}, {1000, 0, 0}, {500, 0.001f, 0.0003f}};  // sliver
    std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5};
    TriangleMesh mesh(Transform(), false, P, idx, {},
                      {{0, 0}, {1, 0}, {0, 1}, {0, 0}, {1, 0}, {0, 1}});
    for (size_t prim : {size_t(0), size_t(1)}) {
        const uint32_t *v = mesh.Triangle(prim);
        Vec3d e1 = Vec3d(P[v[1]] - P[v[0]]), e2 = Vec3d(P[v[2]] - P[v[0]]);
        Vec3d exact = Normalize(Cross(e1, e2));
        Vec3f n = mesh.GeometricNormal(prim);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(n[i], exact[i], 4e-6) << prim;
        Vec3f d = Normalize(Vec3f(0.1f, 0.2f, -1));
        SurfaceInteraction full = mesh.Interaction(prim, 0.25f, 0.5f, 3, d);
        SurfaceInteraction lean = mesh.Interaction(prim, 0.25f, 0.5f, 3, d, NeedNone);
        EXPECT_EQ(full.p, lean.p);
        EXPECT_EQ(full.pError, lean.pError);
        EXPECT_EQ(full.n, lean.n);
        EXPECT_EQ(full.ns, lean.ns);
        EXPECT_EQ(lean.uv, Vec2f(0, 0));
        EXPECT_EQ(lean.dpdu, Vec3f(0, 0, 0));
        EXPECT_NE(full.dpdu, Vec3f(0, 0, 0));
    }
}

}  // namespace
}  // namespace prism

namespace prism {

// The BVH is built with HIGH quality once the render will trace at least
// HighQualitySamplesPerTriangle camera samples per triangle; the hits do not change.
TEST(Accel, BuildQualityFollowsTheExpectedWork) {
    std::vector<Vec3f> P = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
    for (uint64_t samples :
         {uint64_t(0), 2 * HighQualitySamplesPerTriangle - 1, 2 * HighQualitySamplesPerTriangle}) {
        AccelOptions ao;
        ao.expectedSamples = samples;
        Accel accel(ao);
        accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P,
                                                     std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        accel.Commit();
        EXPECT_EQ(accel.BuiltWithHighQuality(), samples >= 2 * HighQualitySamplesPerTriangle)
            << samples;
        EXPECT_EQ(accel.BuildQuality(),
                  accel.BuiltWithHighQuality() ? BvhQuality::High : BvhQuality::Medium);
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(Ray{{0.5f, 0.5f, 0}, {0, 0, 1}, Infinity}, &si));
        EXPECT_NEAR(si.t, 5.0f, 1e-6f);
    }
}

}  // namespace prism

namespace prism {

// An explicit BvhQuality is what Embree builds with, whatever the expected work; ROBUST is
// set on the Embree scene when asked for. The hits do not change.
TEST(Accel, ExplicitBuildQualityAndRobustFlag) {
    std::vector<Vec3f> P = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
    for (BvhQuality q : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High}) {
        for (bool robust : {false, true}) {
            AccelOptions ao;
            ao.quality = q;
            ao.robust = robust;
            ao.expectedSamples = q == BvhQuality::Low ? 1000000 : 0;  // Auto would pick HIGH
            Accel accel(ao);
            accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P,
                                                         std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
            accel.Commit();
            EXPECT_EQ(accel.BuildQuality(), q);
            EXPECT_EQ(accel.BuiltWithHighQuality(), q == BvhQuality::High);
            EXPECT_EQ(accel.Robust(), robust);
            SurfaceInteraction si;
            ASSERT_TRUE(accel.Intersect(Ray{{0.5f, 0.5f, 0}, {0, 0, 1}, Infinity}, &si));
            EXPECT_NEAR(si.t, 5.0f, 1e-6f);
        }
    }
}

}  // namespace prism

namespace prism {

// The three ways a spawned ray leaves a surface (RayOffset): error bounds are exactly
// OffsetRayOrigin (the default), a fixed epsilon moves along n to the side of the direction,
// and no offset keeps the point.
TEST(Accel, SpawnOffsetModes) {
    SurfaceInteraction si;
    si.p = Vec3f(1, 2, 3);
    si.pError = Vec3f(1e-3f, 1e-3f, 1e-3f);
    si.n = Vec3f(0, 1, 0);
    Vec3f up(0.6f, 0.8f, 0), down(0.6f, -0.8f, 0), light(1, 10, 3);
    for (const Vec3f &w : {up, down}) {
        EXPECT_EQ(si.SpawnRay(w, RayOffset{}).o, si.SpawnRay(w).o);
        EXPECT_EQ(si.SpawnRay(w, RayOffset{}).d, w);
        Ray e = si.SpawnRay(w, RayOffset{OffsetMode::FixedEpsilon, 0.25f});
        EXPECT_EQ(e.o, Vec3f(1, w.y > 0 ? 2.25f : 1.75f, 3));
        EXPECT_EQ(si.SpawnRay(w, RayOffset{OffsetMode::None, 0.25f}).o, si.p);
    }
    Ray s = si.SpawnRayTo(light), s0 = si.SpawnRayTo(light, RayOffset{});
    EXPECT_EQ(s.o, s0.o);
    EXPECT_EQ(s.d, s0.d);
    EXPECT_EQ(s.tMax, s0.tMax);
    Ray se = si.SpawnRayTo(light, RayOffset{OffsetMode::FixedEpsilon, 0.5f});
    EXPECT_EQ(se.o, Vec3f(1, 2.5f, 3));
    EXPECT_EQ(se.o + se.d, light);
    EXPECT_EQ(si.SpawnRayTo(light, RayOffset{OffsetMode::None, 0.5f}).o, si.p);
}

}  // namespace prism

namespace prism {
namespace {

// HARD_CASES.md S9: rays spawned from large, thin, tilted triangles hit neither their own
// triangle nor its nearly coplanar neighbours again. Here the pole of a tessellated huge sphere
// (the floor of Whitted's scene under --tessellate 64): a fan of 64 triangles `size` long with
// a slope of 1/20, tilted, hit within a unit of the pole. The error bound of pbrt's
// interpolated hit point is per component; across a tilted plane whose vertices lie far from
// the hit it is much smaller than the error of Embree's own float triangle test, and shadow
// rays re-hit the fan (acne). TriangleMesh::Interaction adds that test's error to the offset.
TEST(Accel, SpawnedRaysLeaveLargeTiltedTriangles) {
    for (bool robust : {false, true}) {
        for (float size : {1.f, 1e2f, 1e4f}) {
            AccelOptions opts;
            opts.robust = robust;
            Accel accel(opts);
            Transform tilt = RotateX(23) * RotateZ(37);
            std::vector<Vec3f> P = {Vec3f(0, 0, 0)};
            std::vector<uint32_t> idx;
            const int fan = 64;
            for (int k = 0; k < fan; ++k) {
                double phi = 2 * Pi * k / fan;
                Vec3d ring(std::cos(phi), -0.05, std::sin(phi));
                P.push_back(Vec3f(tilt.Point(ring * double(size))));
                idx.insert(idx.end(), {0u, uint32_t(1 + (k + 1) % fan), uint32_t(1 + k)});
            }
            accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P, idx));
            accel.Commit();
            Vec3f up = Normalize(Vec3f(tilt.Normal(Vec3d(0, 1, 0))));
            PCG32 rng(size_t(size) + (robust ? 7 : 0));
            int selfHits = 0, hits = 0;
            for (int i = 0; i < 4000; ++i) {
                // Aim at a point within 0.6 of the pole from above, at any angle.
                Vec3f target(float(rng.UniformDouble() * 1.2 - 0.6), 0,
                             float(rng.UniformDouble() * 1.2 - 0.6));
                target = Vec3f(tilt.Point(Vec3d(target)));
                Vec3f from = target + Normalize(up + Vec3f(float(rng.UniformDouble() - 0.5),
                                                           float(rng.UniformDouble() - 0.5),
                                                           float(rng.UniformDouble() - 0.5)) *
                                                         0.8f) *
                                          3.f;
                SurfaceInteraction si;
                if (!accel.Intersect(Ray{from, target - from, Infinity}, &si)) continue;
                ++hits;
                // Leave on the side the ray came from, down to 1e-3 radians above the plane.
                Vec3f n = Dot(si.n, from - si.p) > 0 ? si.n : -si.n;
                Vec3f a, b;
                CoordinateSystem(n, &a, &b);
                float phi = float(2 * Pi * rng.UniformDouble());
                float elev = float(std::pow(10.0, -3 + 3 * rng.UniformDouble()));
                Vec3f d = Normalize(n * std::sin(elev) +
                                    (a * std::cos(phi) + b * std::sin(phi)) * std::cos(elev));
                if (accel.Occluded(si.SpawnRay(d))) ++selfHits;
                if (accel.Occluded(si.SpawnRayTo(si.p + d * (10 * size)))) ++selfHits;
            }
            EXPECT_GT(hits, 3000);
            EXPECT_EQ(selfHits, 0) << "size " << size << (robust ? " robust" : "");
        }
    }
}

}  // namespace
}  // namespace prism
