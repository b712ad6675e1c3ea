// The robust root routine shared by the rotational quadrics without a stable closed-form
// discriminant (cone, paraboloid, hyperboloid), and the residual-based error bound that
// the torus uses too. Included only by the shapes' .cpp files.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/quadric_util.h"
#include "geometry/shape.h"

namespace prism {

// F(p) = A (x^2 + y^2) + B (z - z0)^2 + C (z - z0) + D; z0 keeps the cone's apex term
// unexpanded. FAbs sums the magnitudes of F's terms, which bounds F's rounding error.
struct RotationalQuadric {
    double A = 0, B = 0, C = 0, D = 0, z0 = 0;
    double F(const Vec3d &p) const {
        double z = p.z - z0;
        return A * (p.x * p.x + p.y * p.y) + B * z * z + C * z + D;
    }
    double FAbs(const Vec3d &p) const {
        double z = p.z - z0;
        return std::abs(A) * (p.x * p.x + p.y * p.y) + std::abs(B) * z * z + std::abs(C * z) +
               std::abs(D);
    }
    Vec3d Grad(const Vec3d &p) const { return {2 * A * p.x, 2 * A * p.y, 2 * B * (p.z - z0) + C}; }
    // Grad's derivative along dp (F's Hessian times dp: Grad is linear in p).
    Vec3d GradDerivative(const Vec3d &dp) const {
        return {2 * A * dp.x, 2 * A * dp.y, 2 * B * dp.z};
    }
};

// b*b' - c*d with one FMA-recovered rounding error (Kahan): a 1.5-ulp discriminant.
template <typename Real>
inline Real DifferenceOfProducts(Real a, Real b, Real c, Real d) {
    Real cd = c * d;
    Real err = std::fma(-c, d, cd);
    Real dop = std::fma(a, b, -cd);
    return dop + err;
}

// Parameter interval of the ray inside box (slab test in double). The box is padded by a
// relative 1e-9 of its size so a hit on its boundary is never culled by rounding.
inline bool BoxInterval(const Bounds3d &box, const Vec3d &o, const Vec3d &d, double *tIn,
                        double *tOut) {
    double size = MaxComponent(box.Diagonal()) +
                  std::max(MaxComponent(Abs(box.pMin)), MaxComponent(Abs(box.pMax)));
    double pad = 1e-9 * size;
    double t0 = -std::numeric_limits<double>::infinity();
    double t1 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        double lo = box.pMin[i] - pad, hi = box.pMax[i] + pad;
        if (d[i] == 0) {
            if (o[i] < lo || o[i] > hi) return false;
            continue;
        }
        double a = (lo - o[i]) / d[i], b = (hi - o[i]) / d[i];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    // Widen by a few ulps for the divisions' rounding.
    t0 -= Gamma<double>(4) * std::abs(t0);
    t1 += Gamma<double>(4) * std::abs(t1);
    *tIn = t0;
    *tOut = t1;
    return t0 <= t1;
}

// Uncertainty of a root of f(t) = F(o + t d) when F's value there is uncertain by fErr (from
// the origin's position error times |grad F|, or from rounding), using the local model
// f ~ f1 dt + f2 dt^2 / 2: about fErr / f1 for a transversal root, sqrt(2 fErr / f2) for a
// tangent one. Never divides by zero; +inf only when both derivatives vanish.
inline double RootError(double fErr, double f1, double f2) {
    f1 = std::abs(f1);
    f2 = std::abs(f2);
    double den = f1 + std::sqrt(f1 * f1 + 2 * f2 * fErr);
    return den > 0 ? 2 * fErr / den : (fErr > 0 ? std::numeric_limits<double>::infinity() : 0);
}

// Moves p onto the implicit surface with one Newton step along the gradient (in double) and
// returns a conservative per-component bound on p's distance from the surface: the residual
// |F(p)| plus F's own rounding error, over |grad F|, plus a few ulps of p.
template <typename Surface>
inline void ProjectToSurface(const Surface &s, Vec3d *p, Vec3d *pError) {
    Vec3d g = s.Grad(*p);
    double g2 = Dot(g, g);
    if (g2 > 0 && std::isfinite(g2)) {
        Vec3d q = *p - g * (s.F(*p) / g2);
        if (std::abs(s.F(q)) <= std::abs(s.F(*p))) *p = q;
    }
    g = s.Grad(*p);
    double gl = Length(g);
    double fErr = std::abs(s.F(*p)) + Gamma<double>(8) * s.FAbs(*p);
    double dist = fErr / gl;
    // Where the gradient vanishes (a cone's apex) F is quadratic in the distance.
    if (!(gl > 0) || !std::isfinite(dist)) dist = std::sqrt(fErr);
    *pError = Abs(*p) * Gamma<double>(4) + Vec3d(dist, dist, dist);
}

// Nearest root of the rotational quadric q with t in (tMin, tMax) that passes clip(p, &phi).
// The origin is first moved to the entry of the object bounds (in double, then rounded once
// to Real), so the coefficients are formed from shape-sized numbers; the shift is added back
// to t. A root within its own error bound of 0 is rejected (pbrt's conservative test).
template <typename Real, typename Clip>
bool IntersectRotationalQuadric(const RotationalQuadric &q, const Bounds3d &box, Vec3<Real> o,
                                Vec3<Real> d, Real tMin, Real tMax, Real tSlack, const Clip &clip,
                                ObjectHit *hit) {
    Vec3d od(o), dd(d);
    double tIn, tOut;
    if (!BoxInterval(box, od, dd, &tIn, &tOut) || !(tOut > double(tMin))) return false;
    double ts = std::max(tIn, 0.0);
    Vec3<Real> os(od + dd * ts);
    const Real A = Real(q.A), B = Real(q.B), C = Real(q.C), D = Real(q.D);
    Real zs = os.z - Real(q.z0);
    Real a = A * (d.x * d.x + d.y * d.y) + B * d.z * d.z;
    Real b = 2 * (A * (d.x * os.x + d.y * os.y) + B * d.z * zs) + C * d.z;
    Real c = A * (os.x * os.x + os.y * os.y) + B * zs * zs + C * zs + D;
    Real cAbs = std::abs(A) * (os.x * os.x + os.y * os.y) + std::abs(B) * zs * zs +
                std::abs(C * zs) + std::abs(D);
    Real roots[2], qq;
    int nRoots = 2;
    if (a == 0) {
        // A ray parallel to an asymptotic direction: F is linear along it.
        if (b == 0) return false;
        roots[0] = -c / b;
        qq = b;
        nRoots = 1;
    } else {
        Real discrim = DifferenceOfProducts(b, b, 4 * a, c);
        if (!SolveQuadratic(a, b, c, discrim, &roots[0], &roots[1], &qq)) return false;
    }
    // Rounding of the coefficients and the root formula (pbrt-style, in Real)...
    Real tErr = Gamma<Real>(8) * (cAbs / std::max(std::abs(qq), std::numeric_limits<Real>::min()) +
                                  std::abs(roots[0]) + std::abs(roots[nRoots - 1]));
    // ...plus the origin's position error (its transform, tSlack |d|, and the rounding of the
    // shifted origin), which moves a root by |grad F| |dp| / |f'|: large for grazing rays.
    double posErr = double(tSlack) * Length(dd) + double(Gamma<Real>(2)) * Length(Vec3d(os));
    for (int i = 0; i < nRoots; ++i) {
        double t = ts + double(roots[i]);
        if (!(t < double(tMax))) break;
        Vec3d p = Vec3d(os) + Vec3d(d) * double(roots[i]);
        double f1 = Dot(q.Grad(p), dd), f2 = 2 * double(a);
        double err =
            double(tErr) + Gamma<double>(2) * ts + RootError(Length(q.Grad(p)) * posErr, f1, f2);
        if (!(t > std::max(double(tMin), err))) continue;
        Vec3d pError;
        ProjectToSurface(q, &p, &pError);
        double phi;
        if (!clip(p, &phi)) continue;
        hit->t = t;
        hit->p = p;
        hit->pError = pError;
        hit->phi = phi;
        return true;
    }
    return false;
}

}  // namespace prism
