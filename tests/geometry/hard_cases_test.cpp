// Named hard cases from docs/SHAPES.md that are not sphere-only: S3 (grazing band, sphere and
// cylinder), S6 (thin and degenerate quadrics), S7 (partial-shape boundaries). Each compares
// against a long-double evaluation of the same float ray.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "geometry/accel.h"
#include "shape_test_util.h"

namespace prism {
namespace {

using namespace testing_util;
using LD = long double;

const char *PrecName(Precision p) { return p == Precision::Float ? "float" : "double"; }

bool AllFinite(const Vec3d &v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Everything a hit reports is finite (S6's "never NaN" criterion).
void ExpectFiniteHit(const AnalyticShape &s, const ObjectHit &hit, const Vec3f &d,
                     const std::string &what) {
    ASSERT_TRUE(std::isfinite(hit.t)) << what;
    ASSERT_TRUE(AllFinite(hit.p) && AllFinite(hit.pError)) << what;
    LocalGeometry g = s.Geometry(hit);
    ASSERT_TRUE(AllFinite(g.n) && AllFinite(g.dpdu) && AllFinite(g.dpdv)) << what;
    ASSERT_TRUE(std::isfinite(g.uv.x) && std::isfinite(g.uv.y)) << what;
    ASSERT_GT(Length(g.n), 0) << what;
    SurfaceInteraction si = s.Interaction(hit, d);
    ASSERT_FALSE(si.n.HasNaN() || si.p.HasNaN() || si.pError.HasNaN()) << what;
}

// ---------------------------------------------------------------------------------------
// S3: rays at perpendicular distance r (1 +- k 2^-23), k = 1..1024, from 10 r and 1e4 r.

struct GrazingRay {
    Vec3f o, d;
    LD perp;  // exact perpendicular distance (3-D for the sphere, in xy for the cylinder)
    LD tRef;  // exact nearest crossing (if perp < r)
};

// Reference for the float-rounded ray: sphere (centre 0) or infinite cylinder (axis z).
GrazingRay MakeGrazing(const Vec3f &o, const Vec3f &d, bool cylinder, double r) {
    GrazingRay g{o, d, 0, 0};
    LD ox = o.x, oy = o.y, oz = cylinder ? 0 : o.z, dx = d.x, dy = d.y, dz = cylinder ? 0 : d.z;
    LD dd = dx * dx + dy * dy + dz * dz;
    LD proj = -(ox * dx + oy * dy + oz * dz) / std::sqrt(dd);  // along the unit direction
    LD oo = ox * ox + oy * oy + oz * oz;
    g.perp = std::sqrt(std::max(LD(0), oo - proj * proj));
    LD half = std::sqrt(std::max(LD(0), LD(r) * r - g.perp * g.perp));
    g.tRef = (proj - half) / std::sqrt(dd);
    return g;
}

void CheckGrazing(bool cylinder, double D, Precision prec, bool randomDirections) {
    const double r = 1;
    std::unique_ptr<AnalyticShape> shape;
    if (cylinder)
        shape = std::make_unique<Cylinder>(Transform(), false, r, -2 * D, 2 * D, 360);
    else
        shape = std::make_unique<Sphere>(Transform(), false, r, -r, r, 360);
    const AnalyticShape *s = shape.get();
    AccelOptions opts;
    opts.precision = prec;
    Accel accel(opts);
    accel.AddAnalytic(std::move(shape));
    accel.Commit();

    PCG32 rng(uint64_t(D) + cylinder);
    int checked = 0, wrong = 0, inBand = 0;
    for (int k = 1; k <= 1024; k *= 2)
        for (int sign : {-1, 1})
            for (int j = 0; j < 60; ++j) {
                double rho = r * (1 + sign * k * 0x1p-23);
                Vec3f o, d;
                if (!randomDirections) {
                    // Near-axis-aligned slopes (multiples of 2^-20) keep the float origin
                    // exact to far below 2^-23 r, so the band is probed at the ulp level.
                    double ty = double(int(rng.Uniform() * 17) - 8) * 0x1p-20;
                    double tz = cylinder ? 0 : double(int(rng.Uniform() * 17) - 8) * 0x1p-20;
                    double a = 2 * Pi * rng.UniformDouble();
                    d = Vec3f(1.f, float(ty), float(tz));
                    o = Vec3f(float(-D), float(rho * std::cos(a) - D * ty),
                              cylinder ? float(0.5 * rng.UniformDouble())
                                       : float(rho * std::sin(a) - D * tz));
                    if (cylinder)
                        o.y = float((rng.Uniform() < 0.5f ? -1 : 1) * rho * std::sqrt(1 + ty * ty) -
                                    D * ty);
                } else {
                    Vec3d dir = RandomDirD(rng);
                    if (cylinder) dir = Normalize(Vec3d(dir.x, dir.y, 0));
                    Vec3d e = Normalize(Cross(dir, cylinder ? Vec3d(0, 0, 1) : RandomDirD(rng)));
                    d = Vec3f(dir);
                    o = Vec3f(e * rho - dir * D);
                }
                GrazingRay g = MakeGrazing(o, d, cylinder, r);
                SurfaceInteraction si;
                bool got = accel.Intersect(Ray{o, d, Infinity}, &si);
                ASSERT_EQ(got, accel.Occluded(Ray{o, d, Infinity}))
                    << "intersect/occluded disagree, k " << k;
                bool want = g.perp < r;
                LD dev = std::abs(g.perp - r) / r;
                if (dev >= 8 * 0x1p-23) {
                    ++checked;
                    if (dev < 1025 * 0x1p-23) ++inBand;
                    if (got != want) ++wrong;
                }
                if (got) {
                    ASSERT_FALSE(si.n.HasNaN());
                    ObjectHit hit;
                    ASSERT_TRUE(s->Intersect(o, d, 0, Infinity, prec, &hit));
                    ExpectFiniteHit(*s, hit, d, "grazing");
                    // t is continuous across the band: no jump beyond 1e-3 r.
                    if (want) EXPECT_LE(std::abs(double(LD(hit.t) - g.tRef)), 1e-3 * r) << k;
                }
            }
    std::string what = std::string(cylinder ? "cylinder" : "sphere") + " D " + std::to_string(D) +
                       " " + PrecName(prec);
    EXPECT_EQ(wrong, 0) << what;
    EXPECT_GT(checked, 600) << what;
    if (!randomDirections || D < 100) EXPECT_GT(inBand, 300) << what;
}

TEST(HardCases, S3_GrazingBandSphereAndCylinder) {
    for (bool cylinder : {false, true})
        for (double D : {10.0, 1e4}) {
            CheckGrazing(cylinder, D, Precision::Double, false);
            CheckGrazing(cylinder, D, Precision::Float, false);
            CheckGrazing(cylinder, D, Precision::Double, true);
        }
}

// ---------------------------------------------------------------------------------------
// S6: thin and degenerate quadrics. Reference: the quadratic of F(o + t d) = 0 in long
// double, clipped to the shape's z range (full phi).

struct QuadricRef {
    LD A, B, C, D, z0, zMin, zMax;
};

// Returns 1 (hit), 0 (miss) or -1 (inside the ambiguity band: nearly tangent, or a root
// within 1e-7 of a clip boundary).
int ReferenceHit(const QuadricRef &q, const Vec3f &of, const Vec3f &df) {
    LD ox = of.x, oy = of.y, oz = LD(of.z) - q.z0, dx = df.x, dy = df.y, dz = df.z;
    LD a = q.A * (dx * dx + dy * dy) + q.B * dz * dz;
    LD b = 2 * (q.A * (ox * dx + oy * dy) + q.B * oz * dz) + q.C * dz;
    LD c = q.A * (ox * ox + oy * oy) + q.B * oz * oz + q.C * oz + q.D;
    LD disc = b * b - 4 * a * c;
    LD scale = b * b + std::abs(4 * a * c);
    if (std::abs(disc) <= 1e-9L * scale) return -1;
    if (disc < 0) return 0;
    LD sq = std::sqrt(disc), roots[2];
    int n = 0;
    if (a == 0) {
        roots[n++] = -c / b;
    } else {
        LD qq = b < 0 ? -(b - sq) / 2 : -(b + sq) / 2;
        roots[n++] = qq / a;
        roots[n++] = c / qq;
    }
    bool any = false;
    LD zScale = std::max(std::abs(q.zMin), std::abs(q.zMax)) + (q.zMax - q.zMin);
    for (int i = 0; i < n; ++i) {
        if (!(roots[i] > 0)) continue;
        LD z = LD(of.z) + roots[i] * dz;
        if (std::abs(z - q.zMin) < 1e-7L * zScale || std::abs(z - q.zMax) < 1e-7L * zScale)
            return -1;
        if (z >= q.zMin && z <= q.zMax) any = true;
    }
    return any ? 1 : 0;
}

// Random rays at the shape's bounds: no NaN anywhere, hits within 1e-5 (relative) of the
// implicit surface and within their own pError, and the hit/miss classification of the
// long-double reference outside its ambiguity band.
void CheckDegenerate(const AnalyticShape &s, const QuadricRef &ref, const char *name,
                     uint64_t seed) {
    PCG32 rng(seed);
    Bounds3d b = s.ObjectBounds();
    double extent = Length(b.Diagonal());
    for (Precision prec : {Precision::Double, Precision::Float}) {
        int hits = 0, wrong = 0;
        for (int i = 0; i < 4000; ++i) {
            Vec3d target(Lerp(rng.UniformDouble(), b.pMin.x, b.pMax.x),
                         Lerp(rng.UniformDouble(), b.pMin.y, b.pMax.y),
                         Lerp(rng.UniformDouble(), b.pMin.z, b.pMax.z));
            Vec3d dir = RandomDirD(rng);
            Vec3f o(target - dir * (3 * extent)), d(dir);
            ObjectHit hit;
            bool got = s.Intersect(o, d, 0, Infinity, prec, &hit);
            int want = ReferenceHit(ref, o, d);
            if (want >= 0 && got != bool(want)) ++wrong;
            if (!got) continue;
            ++hits;
            ExpectFiniteHit(s, hit, d, name);
            double resid = Residual(s, hit.p);
            EXPECT_LE(resid, 1e-5 * extent) << name;
            EXPECT_LE(resid, Length(hit.pError) + 1e-15 * extent) << name;
        }
        EXPECT_EQ(wrong, 0) << name << " " << PrecName(prec);
        EXPECT_GT(hits, 200) << name << " " << PrecName(prec);
    }
}

TEST(HardCases, S6_ThinNearCylinderHyperboloid) {
    // p1 = (1, 0, 0), p2 = (1, 0.001, 1): nearly a cylinder, the fit is ill-conditioned.
    Hyperboloid h(Transform(), false, Vec3d(1, 0, 0), Vec3d(1, 0.001, 1), 360);
    EXPECT_TRUE(std::isfinite(h.Ah()) && std::isfinite(h.Ch()));
    EXPECT_NEAR(h.Ah(), 1, 1e-5);
    EXPECT_NEAR(h.Ch(), 1e-6, 1e-7);
    CheckDegenerate(h, {LD(h.Ah()), -LD(h.Ch()), 0, -1, 0, 0, 1}, "thin hyperboloid", 61);
}

TEST(HardCases, S6_EqualRadiusHyperboloidFitTerminates) {
    // Both points at radius 1: pbrt-v3's loop must (and here does) terminate.
    Hyperboloid h(Transform(), false, Vec3d(1, 0, -1), Vec3d(0, 1, 1), 360);
    EXPECT_NEAR(h.Ah(), 2, 1e-12);
    EXPECT_NEAR(h.Ch(), 1, 1e-12);
    CheckDegenerate(h, {2, -1, 0, -1, 0, -1, 1}, "equal-radius hyperboloid", 62);
    // Same radius, vertical segment: the fit is the cylinder rho = 1 (c = 0).
    Hyperboloid cyl(Transform(), false, Vec3d(1, 0, 0), Vec3d(1, 0, 1), 360);
    EXPECT_NEAR(cyl.Ah(), 1, 1e-12);
    EXPECT_NEAR(cyl.Ch(), 0, 1e-12);
    CheckDegenerate(cyl, {1, 0, 0, -1, 0, 0, 1}, "cylindrical hyperboloid", 63);
    // p2 at z = 0 is swapped with p1, as in pbrt-v3.
    Hyperboloid swapped(Transform(), false, Vec3d(1, -1, -1), Vec3d(1, 0, 0), 360);
    EXPECT_NEAR(swapped.Ah(), 1, 1e-12);
    EXPECT_NEAR(swapped.Ch(), 1, 1e-12);
}

TEST(HardCases, S6_FlatCone) {
    Cone c(Transform(), false, 1, 1e-4, 360);
    double k = 1 / (1e-4 * 1e-4);
    CheckDegenerate(c, {1, -LD(k), 0, 0, 1e-4L, 0, 1e-4L}, "flat cone", 64);
}

TEST(HardCases, S6_SteepParaboloid) {
    // zmax / r^2 = 1e6.
    Paraboloid p(Transform(), false, 1e-3, 0, 1, 360);
    CheckDegenerate(p, {1e6L, 0, -1, 0, 0, 0, 1}, "steep paraboloid", 65);
}

TEST(HardCases, S6_CylinderHitAlongItsAxis) {
    Cylinder c(Transform(), false, 1, -1, 1, 360);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        ObjectHit hit;
        // a = 0: no quadratic; a miss, not a NaN.
        EXPECT_FALSE(c.Intersect(Vec3f(0, 0, -5), Vec3f(0, 0, 1), 0, Infinity, prec, &hit));
        EXPECT_FALSE(c.Intersect(Vec3f(0.5f, 0.2f, 0), Vec3f(0, 0, -1), 0, Infinity, prec, &hit));
        EXPECT_FALSE(c.Intersect(Vec3f(1, 0, -5), Vec3f(0, 0, 1), 0, Infinity, prec, &hit));
        // Nearly parallel: either a miss or a finite hit on the wall.
        for (float e : {1e-30f, 1e-20f, 1e-12f, 1e-7f}) {
            Vec3f d(e, 0, 1);
            if (c.Intersect(Vec3f(0, 0, -1), d, 0, Infinity, prec, &hit))
                ExpectFiniteHit(c, hit, d, "near-axis cylinder ray");
        }
    }
}

TEST(HardCases, S6_DiskHitEdgeOn) {
    Disk disk(Transform(), false, 0.5, 1, 0.2, 360);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        ObjectHit hit;
        EXPECT_FALSE(disk.Intersect(Vec3f(-5, 0, 0.5f), Vec3f(1, 0, 0), 0, Infinity, prec, &hit));
        EXPECT_FALSE(
            disk.Intersect(Vec3f(-5, 0.5f, 0.5f), Vec3f(1, 0, 0), 0, Infinity, prec, &hit));
        for (float e : {1e-30f, 1e-20f, 1e-7f}) {
            Vec3f d(1, 0, -e);
            if (disk.Intersect(Vec3f(-0.5f, 0.1f, 0.5f), d, 0, Infinity, prec, &hit)) {
                ExpectFiniteHit(disk, hit, d, "near-edge-on disk ray");
                EXPECT_EQ(hit.p.z, 0.5);
            }
        }
        // A ray through the hole (rho < innerradius) misses; the annulus is hit with
        // pError 0 along the normal.
        EXPECT_FALSE(disk.Intersect(Vec3f(0.1f, 0, 3), Vec3f(0, 0, -1), 0, Infinity, prec, &hit));
        ASSERT_TRUE(disk.Intersect(Vec3f(0.5f, 0, 3), Vec3f(0, 0, -1), 0, Infinity, prec, &hit));
        EXPECT_EQ(hit.pError.z, 0);
        EXPECT_NEAR(hit.t, 2.5, 1e-6);
    }
}

// ---------------------------------------------------------------------------------------
// S7: partial shapes.

std::vector<std::unique_ptr<AnalyticShape>> PartialShapes() {
    std::vector<std::unique_ptr<AnalyticShape>> v;
    Transform I;
    v.push_back(std::make_unique<Sphere>(I, false, 1, -0.5, 0.3, 270));
    v.push_back(std::make_unique<Cylinder>(I, false, 1, -0.5, 0.3, 270));
    v.push_back(std::make_unique<Cone>(I, false, 1, 1.5, 270));
    v.push_back(std::make_unique<Paraboloid>(I, false, 1, 0.2, 1.2, 270));
    v.push_back(
        std::make_unique<Hyperboloid>(I, false, Vec3d(1, -0.8, -0.8), Vec3d(1, 0.6, 0.6), 270));
    v.push_back(std::make_unique<Torus>(I, false, 1, 0.3, 270));
    v.push_back(std::make_unique<Disk>(I, false, 0.1, 1, 0.3, 270));
    return v;
}

TEST(HardCases, S7_PartialShapesShowTheirInside) {
    // From outside the bounds, a convex full shape is only ever seen from outside; a clipped
    // one shows its inside (the second root) through the cut. Every shape here must produce
    // inside views, with normals facing away from the viewer, and every hit must lie in the
    // clip range to within 2 ulp.
    PCG32 rng(71);
    for (auto &s : PartialShapes()) {
        Bounds3d b = s->ObjectBounds();
        double extent = Length(b.Diagonal());
        int inside = 0, hits = 0;
        for (int i = 0; i < 4000; ++i) {
            Vec3d target(Lerp(rng.UniformDouble(), b.pMin.x, b.pMax.x),
                         Lerp(rng.UniformDouble(), b.pMin.y, b.pMax.y),
                         Lerp(rng.UniformDouble(), b.pMin.z, b.pMax.z));
            Vec3d dir = RandomDirD(rng);
            Vec3f o(target - dir * (3 * extent)), d(dir);
            ObjectHit hit;
            if (!s->Intersect(o, d, 0, Infinity, Precision::Double, &hit)) continue;
            ++hits;
            SurfaceInteraction si = s->Interaction(hit, d);
            if (Dot(si.n, d) > 0) ++inside;
            double ulp2 = 2 * 0x1p-52 * (1 + std::abs(hit.p.z));
            EXPECT_LE(hit.phi, Radians(270) + 2 * 0x1p-52 * 8) << s->Name();
            EXPECT_GE(hit.p.z, b.pMin.z - ulp2) << s->Name();
            EXPECT_LE(hit.p.z, b.pMax.z + ulp2) << s->Name();
        }
        EXPECT_GT(hits, 500) << s->Name();
        if (std::string(s->Name()) != "disk") EXPECT_GT(inside, 50) << s->Name();
    }
    // Named rays through the cut of a phimax = 270 cylinder and the top of a zmax-clipped
    // sphere: they hit the far inside wall.
    Cylinder cyl(Transform(), false, 1, -1, 1, 270);
    ObjectHit hit;
    Vec3f d = Normalize(Vec3f(-1, 1, 0));
    ASSERT_TRUE(cyl.Intersect(Vec3f(3, -3, 0), d, 0, Infinity, Precision::Double, &hit));
    EXPECT_NEAR(hit.t, 3 * std::sqrt(2.0) + 1, 1e-6);
    EXPECT_NEAR(hit.phi, Radians(135), 1e-6);
    EXPECT_GT(Dot(cyl.Interaction(hit, d).n, d), 0.f);
    // The same ray through the removed wedge of a cone, paraboloid and hyperboloid (the
    // generic quadric routine's second root).
    Cone cone(Transform(), false, 1, 1.5, 270);
    Paraboloid para(Transform(), false, 1, 0.2, 1.2, 270);
    Hyperboloid hyp(Transform(), false, Vec3d(1, -0.8, -0.8), Vec3d(1, 0.6, 0.6), 270);
    struct Case {
        const AnalyticShape *s;
        float z;
        double rho;
    } cases[] = {{&cone, 0.5f, 1.0 / 1.5}, {&para, 0.6f, std::sqrt(0.5)}, {&hyp, 0.f, 1.0}};
    for (const Case &c : cases) {
        for (Precision prec : {Precision::Double, Precision::Float}) {
            ASSERT_TRUE(c.s->Intersect(Vec3f(3, -3, c.z), d, 0, Infinity, prec, &hit))
                << c.s->Name();
            EXPECT_NEAR(hit.t, 3 * std::sqrt(2.0) + c.rho, 1e-5) << c.s->Name();
            EXPECT_NEAR(hit.phi, Radians(135), 1e-5) << c.s->Name();
            EXPECT_GT(Dot(c.s->Interaction(hit, d).n, d), 0.f) << c.s->Name();
        }
    }
    Sphere sph(Transform(), false, 1, -0.5, 0.3, 270);
    Vec3f d2 = Normalize(Vec3f(float(std::sqrt(0.5)), float(std::sqrt(0.5)), -5));
    ASSERT_TRUE(sph.Intersect(Vec3f(0, 0, 5), d2, 0, Infinity, Precision::Double, &hit));
    EXPECT_NEAR(hit.p.z, 0, 1e-6);
    EXPECT_GT(Dot(sph.Interaction(hit, d2).n, d2), 0.f);
}

TEST(HardCases, S7_RaysAtClipBoundaries) {
    // Rays aimed exactly at phi = phimax and at z = zmax: if reported, the hit is in range
    // within 2 ulp; a ray just inside the boundary is hit, one just outside is not.
    for (Precision prec : {Precision::Double, Precision::Float}) {
        Cylinder c(Transform(), false, 1, -0.5, 0.3, 270);
        ObjectHit hit;
        for (double dz : {-1e-4, 0.0, 1e-4}) {
            Vec3f o(-5, 0, float(0.3 + dz)), d(1, 0, 0);  // hits phi = 180 at height 0.3 + dz
            bool got = c.Intersect(o, d, 0, Infinity, prec, &hit);
            if (dz < 0) EXPECT_TRUE(got);
            if (dz > 0) EXPECT_FALSE(got);
            if (got) EXPECT_LE(hit.p.z, 0.3 + 2 * 0x1p-23);
        }
        // phimax = 270: the boundary is the -y axis. Vertical rays next to it.
        for (double dx : {-1e-4, 0.0, 1e-4}) {
            Vec3f o(float(dx), -5, 0), d(0, 1, 0);
            bool got = c.Intersect(o, d, 0, Infinity, prec, &hit);
            ASSERT_TRUE(got);                         // the far wall at phi ~ 90 is always there
            if (dx < 0) EXPECT_NEAR(hit.t, 4, 1e-3);  // phi < 270: the near wall
            if (dx > 0) EXPECT_NEAR(hit.t, 6, 1e-3);  // phi > 270: clipped, far wall
            EXPECT_LE(hit.phi, Radians(270) + 1e-15);
        }
    }
}

TEST(HardCases, S7_SymmetricUnderPhiRotation) {
    // Rotating the shape about z and the rays with it changes nothing, away from the clip
    // boundaries (where the rotation's rounding may flip the answer).
    PCG32 rng(73);
    for (double angle : {90.0, 37.0}) {
        Transform rot = RotateZ(angle);
        auto a = PartialShapes();
        std::vector<std::unique_ptr<AnalyticShape>> b;
        for (auto &s : a) {
            // Rebuild each shape under the rotation.
            std::string n = s->Name();
            if (n == "sphere") b.push_back(std::make_unique<Sphere>(rot, false, 1, -0.5, 0.3, 270));
            if (n == "cylinder")
                b.push_back(std::make_unique<Cylinder>(rot, false, 1, -0.5, 0.3, 270));
            if (n == "cone") b.push_back(std::make_unique<Cone>(rot, false, 1, 1.5, 270));
            if (n == "paraboloid")
                b.push_back(std::make_unique<Paraboloid>(rot, false, 1, 0.2, 1.2, 270));
            if (n == "hyperboloid")
                b.push_back(std::make_unique<Hyperboloid>(rot, false, Vec3d(1, -0.8, -0.8),
                                                          Vec3d(1, 0.6, 0.6), 270));
            if (n == "torus") b.push_back(std::make_unique<Torus>(rot, false, 1, 0.3, 270));
            if (n == "disk") b.push_back(std::make_unique<Disk>(rot, false, 0.1, 1, 0.3, 270));
        }
        ASSERT_EQ(a.size(), b.size());
        for (size_t si = 0; si < a.size(); ++si) {
            int compared = 0;
            for (int i = 0; i < 2000; ++i) {
                Vec3d target(2 * rng.UniformDouble() - 1, 2 * rng.UniformDouble() - 1,
                             2 * rng.UniformDouble() - 1);
                Vec3d dir = RandomDirD(rng);
                Vec3d o = target - dir * 6;
                ObjectHit ha, hb;
                bool ga =
                    a[si]->Intersect(Vec3f(o), Vec3f(dir), 0, Infinity, Precision::Double, &ha);
                Vec3f ob(rot.Point(o)), db(rot.Vector(dir));
                bool gb = b[si]->Intersect(ob, db, 0, Infinity, Precision::Double, &hb);
                // Skip rays whose hit (either) is near a clip edge or grazing.
                auto nearEdge = [&](const ObjectHit &h) {
                    return std::abs(h.phi - Radians(270)) < 1e-5 || h.phi < 1e-5 ||
                           std::abs(h.p.z - 0.3) < 1e-5 || std::abs(h.p.z + 0.5) < 1e-5 ||
                           std::abs(h.p.z - 0.2) < 1e-5 || std::abs(h.p.z - 1.2) < 1e-5 ||
                           std::abs(h.p.z - 0.6) < 1e-5 || std::abs(h.p.z + 0.8) < 1e-5 ||
                           std::abs(h.p.z) < 1e-5 || std::abs(h.p.z - 1.5) < 1e-5;
                };
                if ((ga && nearEdge(ha)) || (gb && nearEdge(hb))) continue;
                // Rounding of the rotated float ray: compare away from silhouettes too.
                if (ga != gb) {
                    ADD_FAILURE() << a[si]->Name() << " angle " << angle << " ray " << i;
                    continue;
                }
                if (ga) {
                    EXPECT_NEAR(ha.t, hb.t, 1e-4 * ha.t) << a[si]->Name();
                    ++compared;
                }
            }
            EXPECT_GT(compared, 100) << a[si]->Name();
        }
    }
}

}  // namespace
}  // namespace prism
