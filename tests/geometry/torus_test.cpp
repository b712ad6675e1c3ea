// The torus hard cases of docs/SHAPES.md S8 (a-e), against long-double references.
#include "geometry/torus.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/accel.h"
#include "shape_test_util.h"

namespace prism {
namespace {

using namespace testing_util;
using LD = long double;

constexpr double Eps = 0x1p-52;  // double machine epsilon (2.2e-16)

double UlpF(double x) {  // ulp of a double value
    return std::nextafter(std::abs(x), 1e300) - std::abs(x);
}

TEST(Torus, S8a_AxisRayThroughHoleMisses) {
    Torus t(Transform(), false, 1, 0.25, 360);
    Torus::Root roots[4];
    for (Precision prec : {Precision::Double, Precision::Float}) {
        ObjectHit hit;
        EXPECT_FALSE(t.Intersect(Vec3f(0, 0, -5), Vec3f(0, 0, 1), 0, Infinity, prec, &hit));
        EXPECT_FALSE(t.Intersect(Vec3f(0, 0, 5), Vec3f(0, 0, -1), 0, Infinity, prec, &hit));
        // Parallel rays anywhere inside the hole (rho < R - r) miss as well.
        PCG32 rng(1);
        for (int i = 0; i < 2000; ++i) {
            double rho = 0.7499 * std::sqrt(rng.UniformDouble()), a = 2 * Pi * rng.UniformDouble();
            Vec3f o(float(rho * std::cos(a)), float(rho * std::sin(a)), -3.f);
            EXPECT_FALSE(t.Intersect(o, Vec3f(0, 0, 1), 0, Infinity, prec, &hit)) << rho;
        }
    }
    EXPECT_EQ(t.Roots(Vec3d(0, 0, -5), Vec3d(0, 0, 1), 0, 1e30, 0, roots), 0);
}

TEST(Torus, S8b_EquatorialRayFindsFourRoots) {
    // Through the centre in the equatorial plane, at several azimuths and direction scales:
    // roots at D -+ (R + r) and D -+ (R - r).
    const double R = 1, r = 0.25;
    Torus t(Transform(), false, R, r, 360);
    for (double az : {0.0, 0.3, 1.0, 2.5, 4.0}) {
        for (double scale : {1.0, 3.0, 0.125}) {
            for (double D : {5.0, 1e3}) {
                Vec3d dir(std::cos(az), std::sin(az), 0);
                Vec3d o = -dir * D;
                Torus::Root roots[4];
                ASSERT_EQ(t.Roots(o, dir * scale, 0, 1e30, 0, roots), 4) << az;
                double want[4] = {D - R - r, D - R + r, D + R - r, D + R + r};
                for (int i = 0; i < 4; ++i) {
                    double tw = want[i] / scale;
                    // The origin itself is rounded (cos/sin of az), so allow its ulps too.
                    EXPECT_LE(std::abs(roots[i].t - tw), 4 * UlpF(tw) + 4 * UlpF(D) / scale)
                        << "root " << i << " az " << az << " D " << D;
                }
            }
        }
    }
    // The nearest is what Intersect reports (float ray exactly representable).
    for (Precision prec : {Precision::Double, Precision::Float}) {
        ObjectHit hit;
        ASSERT_TRUE(t.Intersect(Vec3f(-5, 0, 0), Vec3f(1, 0, 0), 0, Infinity, prec, &hit));
        EXPECT_LE(std::abs(hit.t - 3.75), 4 * UlpF(3.75));
        // tMin past the first root exposes the next one.
        ASSERT_TRUE(t.Intersect(Vec3f(-5, 0, 0), Vec3f(1, 0, 0), 4.0f, Infinity, prec, &hit));
        EXPECT_LE(std::abs(hit.t - 4.25), 4 * UlpF(4.25));
    }
}

TEST(Torus, S8c_TangentToTopCircle) {
    // Horizontal rays at height z0 = r (1 + delta): the plane z = z0 cuts the torus in the
    // annulus R -+ s, s = sqrt(r^2 - z0^2), so the exact answer is: hit iff |z0| < r and the
    // line passes within R + s of the axis. Rays tangent to the top circle are double roots.
    const double R = 1, r = 0.25;
    Torus t(Transform(), false, R, r, 360);
    PCG32 rng(3);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        int wrong = 0, hits = 0, checked = 0, transversal = 0;
        for (int i = 0; i < 20000; ++i) {
            double delta =
                (rng.Uniform() < 0.5f ? -1 : 1) * std::pow(10.0, -8 + 6 * rng.UniformDouble());
            float z0 = float(r * (1 + delta));
            float y0 = float(1.6 * rng.UniformDouble() - 0.8);
            Vec3f o(-5.f, y0, z0), d(1, 0, 0);
            ObjectHit hit;
            bool got = t.Intersect(o, d, 0, Infinity, prec, &hit);
            LD s2 = LD(r) * r - LD(z0) * z0;
            bool want = s2 > 0 && LD(y0) * y0 < (R + std::sqrt(s2)) * (R + std::sqrt(s2));
            if (std::abs(double(z0) - r) > 1e-6 * R) {
                ++checked;
                if (got != want) ++wrong;
            }
            if (got) {
                ++hits;
                ASSERT_TRUE(std::isfinite(hit.t));
                // The nearest crossing, from the outside circle of the annulus. These rays are
                // all transversal: a float z0 != r is at least an ulp from the top circle, so
                // the incidence cosine is at least ~3e-4 (tangent rays: below).
                if (want) {
                    LD s = std::sqrt(std::max(s2, LD(0)));
                    LD w = std::sqrt((R + s) * (R + s) - LD(y0) * y0);
                    LD tRef = 5 - w;
                    // |n . d| at the hit: the tube angle's cosine s / r times the azimuth's.
                    double cosInc = double(w / (R + s) * (s / r));
                    double err = std::abs(double(hit.t - tRef));
                    // docs/SHAPES.md, transversal roots: sqrt(eps) * scale, and the first
                    // order error eps * scale / |cos| of the root model (scale 5: the origin).
                    EXPECT_LE(err, std::sqrt(Eps) * 5) << "z0 " << z0 << " y0 " << y0;
                    EXPECT_LE(err, Eps * 5 / cosInc) << "z0 " << z0 << " y0 " << y0;
                    ++transversal;
                }
            }
        }
        EXPECT_EQ(wrong, 0) << (prec == Precision::Float ? "float" : "double");
        EXPECT_GT(checked, 10000);
        EXPECT_GT(hits, 2000);
        EXPECT_GT(transversal, 2000);
    }
}

TEST(Torus, S8c_TangentRaysGrazeTheTopCircle) {
    // z0 = r exactly: the plane z = r touches the torus only along the top circle, so every
    // such ray is tangent, with double roots at x = -+sqrt(R^2 - y0^2). A computed double root
    // may or may not be reported (docs/SHAPES.md); if one is, it is one of the two tangent
    // points within the tangent bound sqrt(2 eps scale / kappa) of the root model, kappa the
    // normal curvature along the ray: (1 / r) cos^2 of the angle to the meridian plane.
    const double R = 1, r = 0.25;
    Torus t(Transform(), false, R, r, 360);
    PCG32 rng(5);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        int hits = 0;
        for (int i = 0; i < 4000; ++i) {
            float y0 = float(1.6 * rng.UniformDouble() - 0.8);
            ObjectHit hit;
            if (!t.Intersect(Vec3f(-5.f, y0, float(r)), Vec3f(1, 0, 0), 0, Infinity, prec, &hit))
                continue;
            ++hits;
            LD w = std::sqrt(LD(R) * R - LD(y0) * y0);
            double err =
                std::min(std::abs(double(hit.t - (5 - w))), std::abs(double(hit.t - (5 + w))));
            double kappa = (1 / r) * (1 - double(y0) * y0 / (R * R));
            EXPECT_LE(err, std::sqrt(2 * Eps * 5 / kappa)) << "y0 " << y0;
        }
        EXPECT_GT(hits, 1000);  // most are reported, so the bound is exercised
    }
}

// Distance from a ray to the torus core circle (long double; dense sampling in phi, then
// golden-section refinement): the ray meets the solid torus iff this is below r.
LD CoreDistance(const Vec3f &o, const Vec3f &d, double R) {
    LD ox = o.x, oy = o.y, oz = o.z, dx = d.x, dy = d.y, dz = d.z;
    LD dd = dx * dx + dy * dy + dz * dz;
    auto dist2 = [&](LD phi) {
        LD cx = R * std::cos(phi), cy = R * std::sin(phi);
        LD wx = cx - ox, wy = cy - oy, wz = -oz;
        LD t = std::max(LD(0), (wx * dx + wy * dy + wz * dz) / dd);
        LD px = wx - t * dx, py = wy - t * dy, pz = wz - t * dz;
        return px * px + py * py + pz * pz;
    };
    const int n = 1024;
    int best = 0;
    LD bestV = dist2(0);
    for (int i = 1; i < n; ++i) {
        LD v = dist2(2 * LD(Pi) * i / n);
        if (v < bestV) bestV = v, best = i;
    }
    LD a = 2 * LD(Pi) * (best - 1) / n, b = 2 * LD(Pi) * (best + 1) / n;
    const LD g = (std::sqrt(LD(5)) - 1) / 2;
    for (int it = 0; it < 80; ++it) {
        LD c = b - g * (b - a), e = a + g * (b - a);
        if (dist2(c) < dist2(e))
            b = e;
        else
            a = c;
    }
    return std::sqrt(std::min(bestV, dist2((a + b) / 2)));
}

TEST(Torus, S8d_ThinTorusFromFar) {
    // r / R = 1e-3, eye at 1e3 R; rays aimed near the core circle.
    const double R = 1, r = 1e-3;
    Torus t(Transform(), false, R, r, 360);
    PCG32 rng(4);
    int wrong[2] = {0, 0}, hits[2] = {0, 0};
    for (int i = 0; i < 1500; ++i) {
        Vec3d eye = RandomDirD(rng) * (1e3 * R);
        double a = 2 * Pi * rng.UniformDouble();
        Vec3d target = Vec3d(R * std::cos(a), R * std::sin(a), 0) +
                       RandomDirD(rng) * (2 * r * rng.UniformDouble());
        Vec3f o(eye), d(Normalize(target - eye));
        LD dist = CoreDistance(o, d, R);
        bool want = dist < r;
        for (Precision prec : {Precision::Double, Precision::Float}) {
            int pi = prec == Precision::Float;
            ObjectHit hit;
            bool got = t.Intersect(o, d, 0, Infinity, prec, &hit);
            if (std::abs(double(dist) - r) > 1e-6 * R && got != want) ++wrong[pi];
            if (got) {
                ++hits[pi];
                EXPECT_LE(Residual(t, hit.p), Length(hit.pError));
                // For transversal hits, t is the exact crossing of this float ray to 4 ulp
                // (reference: long-double Newton on F along the ray).
                Vec3d n = Normalize(t.ImplicitGradient(hit.p));
                if (std::abs(Dot(n, Vec3d(d))) > 0.3) {
                    LD tr = hit.t;
                    for (int it = 0; it < 6; ++it) {
                        LD px = LD(o.x) + tr * d.x, py = LD(o.y) + tr * d.y,
                           pz = LD(o.z) + tr * d.z;
                        LD g = px * px + py * py + pz * pz + LD(R) * R - LD(r) * r;
                        LD f = g * g - 4 * LD(R) * R * (px * px + py * py);
                        LD fx = 4 * px * (g - 2 * LD(R) * R), fy = 4 * py * (g - 2 * LD(R) * R),
                           fz = 4 * pz * g;
                        tr -= f / (fx * d.x + fy * d.y + fz * d.z);
                    }
                    EXPECT_LE(std::abs(double(LD(hit.t) - tr)), 4 * UlpF(hit.t))
                        << (pi ? "float" : "double") << " ray " << i;
                }
                // The hit is the near side: the ray just before it is still outside.
                Vec3d before = Vec3d(o) + Vec3d(d) * (hit.t - 1e-2 * r);
                EXPECT_GT(t.Implicit(before), 0);
            }
        }
    }
    for (int pi = 0; pi < 2; ++pi) {
        EXPECT_EQ(wrong[pi], 0) << (pi ? "float" : "double");
        EXPECT_GT(hits[pi], 300);
    }
}

TEST(Torus, S8e_SpawnedFromSurfaceFindsFarWall) {
    PCG32 rng(5);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        for (int trial = 0; trial < 20; ++trial) {
            Transform xf = RandomTransform(rng);
            double r = 0.05 + 0.5 * rng.UniformDouble();
            Torus t(xf, false, 1, r, 360);
            Bounds3d wb = xf.Bounds(t.ObjectBounds());
            double extent = Length(wb.Diagonal());
            double scale = Length(xf.Vector(Vec3d(1, 0, 0)));
            for (int i = 0; i < 50; ++i) {
                Vec3d target = xf.Point(Vec3d(std::cos(i), std::sin(i), 0));
                Vec3d dir = RandomDirD(rng);
                Vec3f o(target - dir * (2 * extent)), d(dir);
                ObjectHit hit;
                if (!t.Intersect(o, d, 0, Infinity, prec, &hit)) continue;
                SurfaceInteraction si = t.Interaction(hit, d);
                // A refracted ray into the tube (slightly bent toward -n).
                Vec3f w = Normalize(d * 0.5f - si.n * 0.5f);
                Ray ray = si.SpawnRay(w);
                ObjectHit h2;
                ASSERT_TRUE(t.Intersect(ray.o, ray.d, 0, Infinity, prec, &h2)) << "trial " << trial;
                Vec3d pFar = Vec3d(ray.o) + Vec3d(ray.d) * h2.t;
                // Not a self-hit: the far wall is a macroscopic distance away, and on the
                // surface within its error bound.
                EXPECT_GT(Distance(pFar, Vec3d(si.p)), 1e-3 * r * scale) << "trial " << trial;
                EXPECT_LE(Residual(t, h2.p), Length(h2.pError));
                // The far wall is an exit: the outward normal points along the ray.
                SurfaceInteraction s2 = t.Interaction(h2, ray.d);
                EXPECT_GT(Dot(s2.n, ray.d), 0.f);
                // Reflection (outward) never re-hits right at the origin.
                Ray refl = si.SpawnRay(d - si.n * (2 * Dot(d, si.n)));
                if (t.Intersect(refl.o, refl.d, 0, Infinity, prec, &h2)) {
                    Vec3d p3 = Vec3d(refl.o) + Vec3d(refl.d) * h2.t;
                    EXPECT_GT(Distance(p3, Vec3d(si.p)), 1e-6 * extent);
                }
            }
        }
    }
}

TEST(Torus, ClippedTorusUsesFourthRoot) {
    // phimax = 186 degrees: along y = -0.1 the first three crossings are at phi ~ 355, 352
    // and 187.7 degrees (clipped); the fourth, at ~184.6, is visible from inside the tube.
    Torus t(Transform(), false, 1, 0.25, 186);
    for (Precision prec : {Precision::Double, Precision::Float}) {
        ObjectHit hit;
        Vec3f o(5, -0.1f, 0), d(-1, 0, 0);
        ASSERT_TRUE(t.Intersect(o, d, 0, Infinity, prec, &hit));
        double y = double(-0.1f);
        EXPECT_NEAR(hit.t, 5 + std::sqrt(1.25 * 1.25 - y * y), 1e-12);
        SurfaceInteraction si = t.Interaction(hit, d);
        EXPECT_GT(Dot(si.n, d), 0.f);  // we see the inside
        // The full torus reports the first crossing.
        Torus full(Transform(), false, 1, 0.25, 360);
        ASSERT_TRUE(full.Intersect(o, d, 0, Infinity, prec, &hit));
        EXPECT_NEAR(hit.t, 5 - std::sqrt(1.25 * 1.25 - y * y), 1e-12);
    }
}

TEST(Torus, IntersectAndOccludedAgreeNearSilhouettes) {
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        accel.AddAnalytic(std::make_unique<Torus>(Transform(), false, 1, 0.25, 360));
        accel.AddAnalytic(
            std::make_unique<Torus>(Translate(Vec3d(3, 0, 0)) * RotateX(90), false, 1, 1e-3, 300));
        accel.Commit();
        PCG32 rng(6);
        for (int i = 0; i < 20000; ++i) {
            // Rays grazing the top circle and the thin torus.
            Vec3f o(-5, float(2 * rng.UniformDouble() - 1),
                    float(0.25 * (1 + 1e-4 * (rng.UniformDouble() - 0.5))));
            Vec3f d = Normalize(Vec3f(1, float(0.01 * (rng.UniformDouble() - 0.5)), 0));
            float tMax = float(12 * rng.UniformDouble());
            SurfaceInteraction si;
            bool hit = accel.Intersect(Ray{o, d, tMax}, &si);
            ASSERT_EQ(hit, accel.Occluded(Ray{o, d, tMax})) << i;
            if (hit) EXPECT_FALSE(si.n.HasNaN());
        }
    }
}

}  // namespace
}  // namespace prism
