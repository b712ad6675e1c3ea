// Property tests of the sphere intersector (docs/SHAPES.md S1–S3 style; pbrt's
// Reintersect/Normal patterns).
#include "geometry/sphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"

namespace prism {
namespace {

Vec3f RandomDir(PCG32 &rng) {
    double z = 1 - 2 * rng.UniformDouble(), phi = 2 * Pi * rng.UniformDouble();
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3f(Vec3d(r * std::cos(phi), r * std::sin(phi), z));
}

Transform RandomTransform(PCG32 &rng) {
    double s = std::pow(10.0, 4 * rng.UniformDouble() - 2);
    Vec3d axis(RandomDir(rng));
    Vec3d t(100 * (rng.UniformDouble() - 0.5), 100 * (rng.UniformDouble() - 0.5),
            100 * (rng.UniformDouble() - 0.5));
    return Translate(t) * Rotate(360 * rng.UniformDouble(), axis) * Scale(s, s, s);
}

// Spawns from a hit point: the robust offset must keep outward rays off the surface and let
// inward rays find the far side exactly once.
void CheckReintersect(const Sphere &sphere, Precision prec, uint64_t seed, int nRays) {
    PCG32 rng(seed);
    Bounds3d wb = sphere.RenderFromObject().Bounds(sphere.ObjectBounds());
    int checked = 0;
    for (int i = 0; i < nRays; ++i) {
        // A ray from outside aimed at a random point of the bounds.
        Vec3d target = Vec3d(Lerp(rng.UniformDouble(), wb.pMin.x, wb.pMax.x),
                             Lerp(rng.UniformDouble(), wb.pMin.y, wb.pMax.y),
                             Lerp(rng.UniformDouble(), wb.pMin.z, wb.pMax.z));
        Vec3d dir(RandomDir(rng));
        double extent = Length(wb.Diagonal());
        Vec3f o(target - dir * (2 * extent)), d(dir);
        ObjectHit hit;
        if (!sphere.Intersect(o, d, 0, Infinity, prec, &hit)) continue;
        SurfaceInteraction si = sphere.Interaction(hit, d);
        ASSERT_FALSE(si.n.HasNaN());
        for (int k = 0; k < 8; ++k) {
            Vec3f w = RandomDir(rng);
            Ray r = si.SpawnRay(w);
            ObjectHit h2;
            bool again = sphere.Intersect(r.o, r.d, 0, Infinity, prec, &h2);
            bool outward = Dot(w, si.n) > 0;
            if (!sphere.IsPartial()) {
                if (outward) {
                    EXPECT_FALSE(again)
                        << "self-hit at t=" << h2.t << " seed " << seed << " i " << i;
                } else {
                    // Inward: exactly one hit, on the far side, not at the origin.
                    ASSERT_TRUE(again) << "inward ray missed the far side, seed " << seed;
                    Vec3d pFar = Vec3d(r.o) + Vec3d(r.d) * h2.t;
                    EXPECT_GT(Distance(pFar, Vec3d(si.p)), 1e-4 * extent);
                }
            } else if (outward && again) {
                // A partial sphere can be hit again from outside only through its opening,
                // far from the origin point.
                Vec3d p2 = Vec3d(r.o) + Vec3d(r.d) * h2.t;
                EXPECT_GT(Distance(p2, Vec3d(si.p)), 1e-5 * extent);
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, nRays);  // most rays hit
}

TEST(Sphere, HitsLieOnSurfaceWithinBound) {
    PCG32 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        Transform xf = RandomTransform(rng);
        double r = std::pow(10.0, 4 * rng.UniformDouble() - 2);
        Sphere s(xf, false, r, -r, r, 360);
        for (int i = 0; i < 50; ++i) {
            Vec3d target = xf.Point(Vec3d(RandomDir(rng)) * (r * 0.9 * rng.UniformDouble()));
            Vec3d dir(RandomDir(rng));
            Vec3f o(target - dir * (10 * r)), d(dir);
            ObjectHit hit;
            ASSERT_TRUE(s.Intersect(o, d, 0, Infinity, Precision::Double, &hit));
            // Object-space residual within the stated error bound (plus a float of slack for
            // re-projection rounding).
            double resid = std::abs(Length(hit.p) - r);
            EXPECT_LE(resid, Length(hit.pError) + 4 * r * MachineEpsilon<double>());
            // World-space: the float hit point lies within its error bound of the surface.
            SurfaceInteraction si = s.Interaction(hit, d);
            Vec3d pObj = xf.Inverse().Point(Vec3d(si.p));
            double worldResid = std::abs(Length(pObj) - r) * Length(xf.Vector(Vec3d(1, 0, 0)));
            EXPECT_LE(worldResid, 2 * Length(Vec3d(si.pError)) + 1e-12) << "trial " << trial;
        }
    }
}

TEST(Sphere, NormalParallelToPosition) {
    PCG32 rng(11);
    for (int i = 0; i < 2000; ++i) {
        double zmin = -1 + 2 * rng.UniformDouble(), zmax = -1 + 2 * rng.UniformDouble();
        double phimax = 360 * rng.UniformDouble() + 1;
        Sphere s(Transform(), false, 1, zmin, zmax, phimax);
        Vec3f o(RandomDir(rng) * 4.f);
        Vec3f d = Normalize(Vec3f(Vec3d(RandomDir(rng)) * 0.5) - o);
        ObjectHit hit;
        if (!s.Intersect(o, d, 0, Infinity, Precision::Double, &hit)) continue;
        SurfaceInteraction si = s.Interaction(hit, d);
        EXPECT_NEAR(Dot(Normalize(Vec3d(si.n)), Normalize(Vec3d(si.p))), 1.0, 1e-6);
        EXPECT_GE(hit.p.z, std::min(zmin, zmax) - 1e-12);
        EXPECT_LE(hit.p.z, std::max(zmin, zmax) + 1e-12);
        EXPECT_LE(hit.phi, Radians(phimax) + 1e-12);
    }
}

TEST(Sphere, ReintersectFullSphereDouble) {
    PCG32 rng(3);
    for (int trial = 0; trial < 40; ++trial) {
        Transform xf = RandomTransform(rng);
        Sphere s(xf, false, 1, -1, 1, 360);
        CheckReintersect(s, Precision::Double, 1000 + trial, 320);
    }
}

TEST(Sphere, ReintersectFullSphereFloat) {
    PCG32 rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        Transform xf = RandomTransform(rng);
        Sphere s(xf, false, 1, -1, 1, 360);
        CheckReintersect(s, Precision::Float, 2000 + trial, 300);
    }
}

TEST(Sphere, ReintersectPartialSphere) {
    PCG32 rng(9);
    for (int trial = 0; trial < 20; ++trial) {
        Transform xf = RandomTransform(rng);
        Sphere s(xf, false, 2, -1.2, 0.7, 250);
        CheckReintersect(s, Precision::Double, 3000 + trial, 300);
    }
}

TEST(Sphere, PartialSphereShowsItsInside) {
    // Hemisphere z >= 0 seen from above: the ray passes the cut and hits the inside
    // (second root); the outward normal then faces away from the viewer.
    Sphere s(Transform(), false, 1, 0, 1, 360);
    Vec3f o(0, 0, -5), d(0, 0, 1);
    ObjectHit hit;
    ASSERT_TRUE(s.Intersect(o, d, 0, Infinity, Precision::Double, &hit));
    EXPECT_NEAR(hit.t, 6.0, 1e-6);  // the top of the dome, from inside
    SurfaceInteraction si = s.Interaction(hit, d);
    EXPECT_GT(Dot(si.n, d), 0.f);  // outward normal points along the ray: we see the inside
    // phimax clips: a ray through the removed wedge sees the far inside wall.
    Sphere wedge(Transform(), false, 1, -1, 1, 270);
    Vec3f o2(3, -3, 0), d2 = Normalize(Vec3f(-1, 1, 0));  // enters through phi = 315 degrees
    ASSERT_TRUE(wedge.Intersect(o2, d2, 0, Infinity, Precision::Double, &hit));
    EXPECT_NEAR(hit.phi, Radians(135), 1e-6);
}

TEST(Sphere, S1_TinyFarSphereClassification) {
    // S1: r = 1e-3 at distance 1e4; rays aimed over a disk of radius 2r. Hit/miss must match
    // the exact answer away from a thin band around the silhouette.
    for (Precision prec : {Precision::Double, Precision::Float}) {
        double r = 1e-3, dist = 1e4;
        Sphere s(Translate(Vec3d(0, 0, dist)), false, r, -r, r, 360);
        PCG32 rng(13);
        int wrong = 0, hits = 0;
        for (int i = 0; i < 20000; ++i) {
            double a = 2 * Pi * rng.UniformDouble(), rad = 2 * r * std::sqrt(rng.UniformDouble());
            Vec3f o(0, 0, 0);
            Vec3f d(Vec3d(rad * std::cos(a), rad * std::sin(a), dist));
            // Exact perpendicular distance of the (float-rounded) ray to the centre.
            long double dx = d.x, dy = d.y, dz = d.z;
            long double len = std::sqrt(dx * dx + dy * dy + dz * dz);
            long double t = dz * (long double)dist / (len * len);
            long double px = dx * t, py = dy * t, pz = dz * t - dist;
            long double perp = std::sqrt(px * px + py * py + pz * pz);
            ObjectHit hit;
            bool got = s.Intersect(o, d, 0, Infinity, prec, &hit);
            bool want = perp < r;
            // Classification must be exact outside a band of 1e-4 r around the silhouette.
            if (std::abs(double(perp) - r) > 1e-4 * r && got != want) ++wrong;
            hits += got;
        }
        EXPECT_EQ(wrong, 0) << (prec == Precision::Float ? "float" : "double");
        EXPECT_GT(hits, 4000);
    }
}

TEST(Sphere, S4_HugeFloorSphere) {
    // S4: Whitted's floor, r = 1e5 centred at (0, -1e5, 0); the eye 1 unit above. Rays from
    // 0.1 degrees below the true horizon down to 11.5 degrees.
    double R = 1e5;
    Sphere s(Translate(Vec3d(0, -R, 0)), false, R, -R, R, 360);
    double dip = std::acos(R / (R + 1));  // angle of the horizon below the horizontal
    PCG32 rng(17);
    int falseResults = 0;
    for (int i = 0; i < 20000; ++i) {
        double angle = dip + Radians(0.1 + 11.4 * rng.UniformDouble());
        double az = 2 * Pi * rng.UniformDouble();
        Vec3f o(0, 1, 0);
        Vec3f d(Vec3d(std::cos(angle) * std::cos(az), -std::sin(angle),
                      std::cos(angle) * std::sin(az)));
        ObjectHit hit;
        if (!s.Intersect(o, d, 0, Infinity, Precision::Double, &hit)) {
            ++falseResults;
            continue;
        }
        SurfaceInteraction si = s.Interaction(hit, d);
        Vec3d pc = Vec3d(si.p) - Vec3d(0, -R, 0);
        EXPECT_LE(std::abs(Length(pc) - R),
                  std::max(1e-6, 4 * double(std::nextafter(1e5f, 2e5f) - 1e5f)));
        // Shadow ray to a light at height 10 must not be blocked by the floor itself.
        Vec3f light(si.p.x, 10.f, si.p.z);
        Ray shadow = si.SpawnRayTo(light);
        ObjectHit h2;
        EXPECT_FALSE(s.Intersect(shadow.o, shadow.d, 0, shadow.tMax, Precision::Double, &h2))
            << "acne";
    }
    EXPECT_EQ(falseResults, 0);
    // Rays 0.1 degrees *above* the true horizon miss.
    for (int i = 0; i < 2000; ++i) {
        double angle = dip - Radians(0.1 + 0.1 * rng.UniformDouble());
        Vec3f d(Vec3d(std::cos(angle), -std::sin(angle), 0));
        ObjectHit hit;
        EXPECT_FALSE(s.Intersect(Vec3f(0, 1, 0), d, 0, Infinity, Precision::Double, &hit));
    }
}

TEST(Sphere, S2_RayOriginOnTheSurface) {
    struct Case {
        double r;
        Vec3d centre;
    };
    for (const Case &c : {Case{1, {0, 0, 0}}, Case{1e4, {0, 0, 0}}, Case{1, {1e4, 1e4, 1e4}}}) {
        SCOPED_TRACE("r " + std::to_string(c.r) + " centre " + ToString(c.centre));
        Sphere s(Translate(c.centre), false, c.r, -c.r, c.r, 360);
        PCG32 rng(41);
        int rawSelfHits = 0, selfHits = 0, farMisses = 0, n = 0;
        for (int i = 0; i < 4000; ++i) {
            Vec3d dirToSurface(RandomDir(rng));
            Vec3f o(c.centre + dirToSurface * (3 * c.r)), d(-dirToSurface);
            ObjectHit hit;
            ASSERT_TRUE(s.Intersect(o, d, 0, Infinity, Precision::Double, &hit));
            SurfaceInteraction si = s.Interaction(hit, d);
            Vec3f w = RandomDir(rng);
            bool outward = Dot(w, si.n) > 0;
            ObjectHit h2;
            // (a) Without an offset, from the rounded hit point itself: the acne metric.
            if (outward && s.Intersect(si.p, w, 0, Infinity, Precision::Double, &h2)) ++rawSelfHits;
            // (b) With the error-bound offset.
            Ray r = si.SpawnRay(w);
            double offset = Length(Vec3d(r.o) - Vec3d(si.p));
            EXPECT_LE(offset, 1e-6 * std::max(Length(Vec3d(si.p)), c.r));
            bool again = s.Intersect(r.o, r.d, 0, Infinity, Precision::Double, &h2);
            if (outward) {
                selfHits += again;
            } else {
                // Exactly one hit, on the far side, at t = 2 r cos(theta).
                if (!again) {
                    ++farMisses;
                    continue;
                }
                // The far root of the spawned ray, in long double. (At the origin this is
                // 2 r cos(theta); far from it the float hit point sits up to ulp(|p|) off the
                // surface, which moves grazing chords, so compare with the exact root.)
                long double ox = (long double)r.o.x - c.centre.x,
                            oy = (long double)r.o.y - c.centre.y,
                            oz = (long double)r.o.z - c.centre.z;
                long double a = (long double)r.d.x * r.d.x + (long double)r.d.y * r.d.y +
                                (long double)r.d.z * r.d.z;
                long double b = 2 * (ox * r.d.x + oy * r.d.y + oz * r.d.z);
                long double cc = ox * ox + oy * oy + oz * oz - (long double)c.r * c.r;
                long double tFar = (-b + std::sqrt(std::max(0.0L, b * b - 4 * a * cc))) / (2 * a);
                EXPECT_NEAR(h2.t, double(tFar), 1e-9 * (c.r + Length(c.centre)));
                double cosTheta = -Dot(Vec3d(w), Vec3d(si.n)) / Length(Vec3d(w));
                if (Length(c.centre) == 0 && cosTheta > 0.1)  // the offset moves grazing chords
                    EXPECT_NEAR(h2.t, 2 * c.r * cosTheta, 1e-5 * c.r);
                ObjectHit h3;
                Ray r2 = s.Interaction(h2, r.d).SpawnRay(r.d);
                EXPECT_FALSE(s.Intersect(r2.o, r2.d, 0, Infinity, Precision::Double, &h3));
            }
            ++n;
        }
        EXPECT_EQ(selfHits, 0);
        EXPECT_EQ(farMisses, 0);
        RecordProperty("raw_self_hits_r" + std::to_string(int(c.r)), rawSelfHits);
    }
    // Two concentric spheres r and r (1 + 1e-5): a ray leaving the inner one outward must
    // still hit the outer one, so the offset skips no real geometry.
    Sphere inner(Transform(), false, 1, -1, 1, 360),
        outer(Transform(), false, 1 + 1e-5, -2, 2, 360);
    PCG32 rng(43);
    for (int i = 0; i < 2000; ++i) {
        Vec3d n(RandomDir(rng));
        Vec3f o(n * 3.0), d(-n);
        ObjectHit hit;
        ASSERT_TRUE(inner.Intersect(o, d, 0, Infinity, Precision::Double, &hit));
        SurfaceInteraction si = inner.Interaction(hit, d);
        Vec3f w = FaceForward(RandomDir(rng), si.n);
        Ray r = si.SpawnRay(w);
        ObjectHit h2;
        EXPECT_TRUE(outer.Intersect(r.o, r.d, 0, Infinity, Precision::Double, &h2)) << i;
    }
}

TEST(Sphere, DegenerateRaysNeverNaN) {
    Sphere s(Transform(), false, 1, -1, 1, 360);
    ObjectHit hit;
    EXPECT_FALSE(s.Intersect(Vec3f(0, 0, 0), Vec3f(0, 0, 0), 0, Infinity, Precision::Double, &hit));
    // A ray along the axis through the poles: the azimuth guard keeps uv finite.
    ASSERT_TRUE(s.Intersect(Vec3f(0, 0, -3), Vec3f(0, 0, 1), 0, Infinity, Precision::Double, &hit));
    SurfaceInteraction si = s.Interaction(hit, Vec3f(0, 0, 1));
    EXPECT_FALSE(si.n.HasNaN());
    EXPECT_FALSE(std::isnan(si.uv.x) || std::isnan(si.uv.y));
    EXPECT_NEAR(si.n.z, -1.f, 1e-5f);
}

// Interaction without uv/dpdu (NeedNone) gives the same point, error bound and normals as the
// full one: the spawn offsets do not depend on what the material reads.
TEST(Sphere, InteractionWithoutSurfaceDataKeepsPointAndNormal) {
    Transform m = Translate(Vec3d(0.3, -1.2, 4.0)) * Scale(2, 2, 2);
    for (bool partial : {false, true}) {
        Sphere s(m, false, 1.5, partial ? -1.0 : -1.5, 1.5, partial ? 300 : 360);
        PCG32 rng(7);
        int hits = 0;
        for (int i = 0; i < 200; ++i) {
            Vec3f o(0, 0, 0);
            Vec3f d = Normalize(
                Vec3f(0.3f, -1.2f, 4.0f) +
                Vec3f(rng.Uniform() - 0.5f, rng.Uniform() - 0.5f, rng.Uniform() - 0.5f) * 6.f);
            ObjectHit hit;
            if (!s.Intersect(o, d, 0, Infinity, Precision::Double, &hit)) continue;
            ++hits;
            SurfaceInteraction full = s.Interaction(hit, d), lean = s.Interaction(hit, d, NeedNone);
            EXPECT_EQ(full.p, lean.p);
            EXPECT_EQ(full.pError, lean.pError);
            EXPECT_EQ(full.n, lean.n);
            EXPECT_EQ(full.ns, lean.ns);
            EXPECT_EQ(lean.uv, Vec2f(0, 0));
            EXPECT_GE(full.uv.x, 0.f);
            EXPECT_LE(full.uv.x, 1.f);
        }
        EXPECT_GT(hits, 50);
    }
}

}  // namespace
}  // namespace prism

namespace prism {

// A hit point's error bound covers the rounding of its double world-space position to float.
// GCC 12's SLP vectorizer folded that rounding away in the loop this bound was computed in
// before (core/vecmath.h OpaqueFloat): on this sphere the bound missed up to half a float ulp
// in y and z, which this test would have caught.
TEST(Sphere, HitErrorCoversTheRoundingToFloat) {
    const Transform rfo = Translate({0.1, 2.0000001, 13.146825427662719});
    Sphere sphere(rfo, false, 1, -1, 1, 360);
    for (const Vec3d &p : {Vec3d(0, 0, 1), Vec3d(0.6, 0, 0.8), Vec3d(0, -0.28, 0.96)}) {
        ObjectHit hit;
        hit.t = 1;
        hit.p = p;
        const SurfaceInteraction si = sphere.Interaction(hit, Vec3f(0, 0, -1), NeedNone);
        const Vec3d pW = rfo.Point(p);
        for (int i = 0; i < 3; ++i) {
            const double rounding = std::abs(double(si.p[i]) - pW[i]);
            EXPECT_GE(double(si.pError[i]), rounding) << "component " << i;
        }
        // The case of the bug: y and z of the world point are not floats.
        EXPECT_NE(double(si.p.y), pW.y);
    }
}

}  // namespace prism
