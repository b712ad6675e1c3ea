// Property tests run on every analytic shape (pbrt's Reintersect/Normal patterns): hit
// residuals within pError, normals along the gradient and cross(dpdu, dpdv), spawned rays
// free of self-hits, and Embree's intersect/occluded paths in agreement.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/accel.h"
#include "shape_test_util.h"

namespace prism {
namespace {

using namespace testing_util;

const char *PrecName(Precision p) { return p == Precision::Float ? "float" : "double"; }

// A ray from outside the world bounds toward a random point of them.
bool ShootAtBounds(const AnalyticShape &s, PCG32 &rng, Precision prec, Vec3f *o, Vec3f *d,
                   ObjectHit *hit) {
    Bounds3d wb = s.RenderFromObject().Bounds(s.ObjectBounds());
    Vec3d target(Lerp(rng.UniformDouble(), wb.pMin.x, wb.pMax.x),
                 Lerp(rng.UniformDouble(), wb.pMin.y, wb.pMax.y),
                 Lerp(rng.UniformDouble(), wb.pMin.z, wb.pMax.z));
    Vec3d dir = RandomDirD(rng);
    *o = Vec3f(target - dir * (2 * Length(wb.Diagonal())));
    *d = Vec3f(dir);
    return s.Intersect(*o, *d, 0, Infinity, prec, hit);
}

TEST(AnalyticShapes, HitsLieOnSurfaceWithinBound) {
    for (Kind k : AllKinds)
        for (Precision prec : {Precision::Double, Precision::Float}) {
            PCG32 rng(100 + int(k));
            int hits = 0;
            for (int trial = 0; trial < 40; ++trial) {
                Transform xf = RandomTransform(rng);
                auto s = MakeShape(k, xf, trial % 2 == 1, rng);
                Transform objFromWorld = xf.Inverse();
                for (int i = 0; i < 50; ++i) {
                    Vec3f o, d;
                    ObjectHit hit;
                    if (!ShootAtBounds(*s, rng, prec, &o, &d, &hit)) continue;
                    ++hits;
                    // Object space: the reported point is within its own error bound of the
                    // surface (a ulp of slack for evaluating the residual itself).
                    double resid = Residual(*s, hit.p);
                    EXPECT_LE(resid, Length(hit.pError) + 1e-15 * Length(hit.p))
                        << KindName(k) << " " << PrecName(prec) << " trial " << trial;
                    // The reported point lies on the ray (within the float ray's precision).
                    Vec3d pRay = objFromWorld.Point(Vec3d(o) + Vec3d(d) * hit.t);
                    // (object-space scale of the world-space magnitudes involved)
                    double scale = Length(objFromWorld.Vector(Vec3d(1, 0, 0))) *
                                   (Length(Vec3d(o)) + hit.t + Length(xf.Point(Vec3d(0, 0, 0))));
                    double rel = prec == Precision::Double ? 1e-12 : 1e-5;
                    EXPECT_LE(Distance(pRay, hit.p), rel * scale) << KindName(k);
                    // World space: the float point is within its world error bound.
                    SurfaceInteraction si = s->Interaction(hit, d);
                    Vec3d pw = objFromWorld.Point(Vec3d(si.p));
                    double worldScale = Length(xf.Vector(Vec3d(1, 0, 0)));
                    EXPECT_LE(Residual(*s, pw) * worldScale, 2 * Length(Vec3d(si.pError)) + 1e-30)
                        << KindName(k) << " " << PrecName(prec);
                }
            }
            EXPECT_GT(hits, 400) << KindName(k);
        }
}

TEST(AnalyticShapes, NormalAlongGradientAndCrossProduct) {
    for (Kind k : AllKinds) {
        PCG32 rng(200 + int(k));
        int crossChecked = 0;
        for (int trial = 0; trial < 400; ++trial) {
            auto s = MakeShape(k, Transform(), trial % 2 == 1, rng);
            Vec3f o, d;
            ObjectHit hit;
            if (!ShootAtBounds(*s, rng, Precision::Double, &o, &d, &hit)) continue;
            LocalGeometry g = s->Geometry(hit);
            ASSERT_FALSE(g.n.HasNaN() || g.dpdu.HasNaN() || g.dpdv.HasNaN()) << KindName(k);
            ASSERT_TRUE(std::isfinite(g.uv.x) && std::isfinite(g.uv.y)) << KindName(k);
            EXPECT_GE(g.uv.x, -1e-9);
            EXPECT_LE(g.uv.x, 1 + 1e-9);
            Vec3d grad = s->ImplicitGradient(hit.p);
            double c = Dot(Normalize(g.n), Normalize(grad));
            if (k == Kind::Hyperboloid) c = std::abs(c);  // oriented by p1 -> p2, not F
            EXPECT_NEAR(c, 1.0, 1e-9) << KindName(k) << " trial " << trial;
            // pbrt's orientation: n points along cross(dpdu, dpdv).
            Vec3d cr = Cross(g.dpdu, g.dpdv);
            if (Length(cr) > 1e-9 * Length(g.dpdu) * Length(g.dpdv)) {
                EXPECT_GT(Dot(Normalize(cr), Normalize(g.n)), 0.999999) << KindName(k);
                ++crossChecked;
            }
            // The world normal is the transformed one (here identity), unit length.
            SurfaceInteraction si = s->Interaction(hit, d);
            EXPECT_NEAR(Length(Vec3d(si.n)), 1.0, 1e-6);
        }
        EXPECT_GT(crossChecked, 100) << KindName(k);
    }
}

TEST(AnalyticShapes, ClosedShapesOutwardGradient) {
    // Closed shapes: F < 0 just inside along -n, > 0 just outside along +n.
    for (Kind k : {Kind::Sphere, Kind::Torus}) {
        PCG32 rng(300);
        auto s = MakeShape(k, Transform(), false, rng);
        for (int i = 0; i < 200; ++i) {
            Vec3f o, d;
            ObjectHit hit;
            if (!ShootAtBounds(*s, rng, Precision::Double, &o, &d, &hit)) continue;
            Vec3d n = Normalize(s->Geometry(hit).n);
            EXPECT_GT(s->Implicit(hit.p + n * 1e-3), 0) << KindName(k);
            EXPECT_LT(s->Implicit(hit.p - n * 1e-3), 0) << KindName(k);
        }
    }
}

// Spawns 8 rays from each hit (pbrt-v3 OffsetRayOrigin). Convex-solid shapes: an outward ray
// never hits again. The disk: no ray ever hits the plane again. Full sphere and torus: an
// inward ray always finds the far wall. Everything else: any second hit is far from the
// origin (a self-hit would sit within the point's error bound).
void CheckReintersect(Kind k, bool partial, Precision prec, uint64_t seed, int nSpawn) {
    PCG32 rng(seed);
    int spawned = 0, trial = 0, inward = 0, inwardMisses = 0;
    while (spawned < nSpawn) {
        Transform xf = RandomTransform(rng);
        auto s = MakeShape(k, xf, partial, rng);
        Bounds3d wb = xf.Bounds(s->ObjectBounds());
        double extent = Length(wb.Diagonal());
        double near = (prec == Precision::Double ? 1e-9 : 1e-5) * extent;
        ++trial;
        for (int i = 0; i < 20; ++i) {
            Vec3f o, d;
            ObjectHit hit;
            if (!ShootAtBounds(*s, rng, prec, &o, &d, &hit)) continue;
            SurfaceInteraction si = s->Interaction(hit, d);
            ASSERT_FALSE(si.n.HasNaN());
            for (int j = 0; j < 8; ++j, ++spawned) {
                Vec3f w = RandomDirF(rng);
                Ray r = si.SpawnRay(w);
                ObjectHit h2;
                bool again = s->Intersect(r.o, r.d, 0, Infinity, prec, &h2);
                bool outward = Dot(w, si.n) > 0;
                Vec3d p2 = Vec3d(r.o) + Vec3d(r.d) * h2.t;
                std::string where = std::string(KindName(k)) + " " + PrecName(prec) + " trial " +
                                    std::to_string(trial);
                if (k == Kind::Disk || (outward && ConvexSolid(k))) {
                    EXPECT_FALSE(again) << "self-hit, t=" << h2.t << " " << where;
                } else if (!outward && !partial && (k == Kind::Sphere || k == Kind::Torus)) {
                    // In float, a far wall closer than the object-space origin's transform error
                    // divided by the grazing cosine cannot be told from a self-hit and is
                    // conservatively rejected (docs/SHAPES.md); double must always find it.
                    ++inward;
                    if (!again) {
                        ++inwardMisses;
                        ASSERT_EQ(prec, Precision::Float)
                            << "inward ray missed the far wall, " << where;
                        continue;
                    }
                    EXPECT_GT(Distance(p2, Vec3d(si.p)), near) << where;
                } else if (again) {
                    EXPECT_GT(Distance(p2, Vec3d(si.p)), near) << where;
                }
            }
        }
    }
    EXPECT_LE(inwardMisses, inward / 200) << KindName(k) << " " << PrecName(prec);
}

TEST(AnalyticShapes, ReintersectDouble) {
    for (Kind k : AllKinds) {
        CheckReintersect(k, false, Precision::Double, 400 + int(k), 10000);
        CheckReintersect(k, true, Precision::Double, 500 + int(k), 4000);
    }
}

TEST(AnalyticShapes, ReintersectFloat) {
    for (Kind k : AllKinds) CheckReintersect(k, false, Precision::Float, 600 + int(k), 10000);
}

TEST(AnalyticShapes, IntersectAndOccludedAgreeThroughAccel) {
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        PCG32 rng(31);
        for (int i = 0; i < 28; ++i) {
            Kind k = AllKinds[i % 7];
            Vec3d c(10 * rng.UniformDouble(), 10 * rng.UniformDouble(), 10 * rng.UniformDouble());
            Transform xf = Translate(c) * Rotate(360 * rng.UniformDouble(), RandomDirD(rng));
            accel.AddAnalytic(MakeShape(k, xf, i % 2 == 1, rng, rng.Uniform() < 0.5f));
        }
        accel.Commit();
        int hits = 0;
        for (int i = 0; i < 20000; ++i) {
            Vec3f o(float(20 * rng.UniformDouble() - 5), float(20 * rng.UniformDouble() - 5), -10);
            Vec3f d = Normalize(
                Vec3f(float(rng.UniformDouble() - 0.5), float(rng.UniformDouble() - 0.5), 1));
            float tMax = float(40 * rng.UniformDouble());
            SurfaceInteraction si;
            bool hit = accel.Intersect(Ray{o, d, tMax}, &si);
            ASSERT_EQ(hit, accel.Occluded(Ray{o, d, tMax})) << i << " " << PrecName(prec);
            if (hit) {
                ++hits;
                EXPECT_LT(si.t, tMax);
                EXPECT_FALSE(si.n.HasNaN());
                // The closest hit agrees with the shape's own routine.
                ObjectHit oh;
                ASSERT_TRUE(accel.Analytic(si.shape)->Intersect(o, d, 0, tMax, prec, &oh));
                EXPECT_NEAR(oh.t, si.t, 1e-5 * (1 + si.t));
            }
        }
        EXPECT_GT(hits, 1000);
    }
}

TEST(AnalyticShapes, InvalidParametersThrow) {
    Transform I;
    EXPECT_THROW(Cylinder(I, false, 0, -1, 1, 360), std::invalid_argument);
    EXPECT_THROW(Cylinder(I, false, 1, 1, 1, 360), std::invalid_argument);
    EXPECT_THROW(Cylinder(I, false, 1, -1, 1, 0), std::invalid_argument);
    EXPECT_THROW(Disk(I, false, 0, -1, 0, 360), std::invalid_argument);
    EXPECT_THROW(Disk(I, false, 0, 1, 1, 360), std::invalid_argument);
    EXPECT_THROW(Cone(I, false, 1, 0, 360), std::invalid_argument);
    EXPECT_THROW(Cone(I, false, -1, 1, 360), std::invalid_argument);
    EXPECT_THROW(Paraboloid(I, false, 1, 0, 0, 360), std::invalid_argument);
    EXPECT_THROW(Paraboloid(I, false, 1, -1, -0.5, 360), std::invalid_argument);
    // pbrt-v3's default hyperboloid (p1 at the origin) sweeps a cone: its fit never converges.
    EXPECT_THROW(Hyperboloid(I, false, Vec3d(0, 0, 0), Vec3d(1, 1, 1), 360), std::invalid_argument);
    EXPECT_THROW(Hyperboloid(I, false, Vec3d(1, 0, 0), Vec3d(0, 1, 0), 360), std::invalid_argument);
    EXPECT_THROW(Hyperboloid(I, false, Vec3d(1, 0, 1), Vec3d(1, 0, 1), 360), std::invalid_argument);
    EXPECT_THROW(Torus(I, false, 0.5, 1, 360), std::invalid_argument);
    EXPECT_THROW(Torus(I, false, 1, 1, 360), std::invalid_argument);
    EXPECT_THROW(Torus(I, false, 0, 0.1, 360), std::invalid_argument);
    EXPECT_THROW(Torus(I, false, 1, 0, 360), std::invalid_argument);
    try {
        Torus(I, false, 0.5, 1, 360);
    } catch (const std::invalid_argument &e) {
        EXPECT_STREQ(e.what(), "torus minorradius must be smaller than majorradius");
    }
}

TEST(AnalyticShapes, ObjectBoundsContainHits) {
    for (Kind k : AllKinds) {
        PCG32 rng(700 + int(k));
        for (int trial = 0; trial < 300; ++trial) {
            auto s = MakeShape(k, Transform(), trial % 2 == 1, rng);
            Bounds3d b = s->ObjectBounds();
            Vec3f o, d;
            ObjectHit hit;
            if (!ShootAtBounds(*s, rng, Precision::Double, &o, &d, &hit)) continue;
            for (int i = 0; i < 3; ++i) {
                double tol = 1e-12 * (1 + std::abs(hit.p[i]));
                EXPECT_GE(hit.p[i], b.pMin[i] - tol) << KindName(k);
                EXPECT_LE(hit.p[i], b.pMax[i] + tol) << KindName(k);
            }
        }
    }
}

}  // namespace
}  // namespace prism
