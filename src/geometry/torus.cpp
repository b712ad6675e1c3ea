#include "geometry/torus.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/polynomial.h"
#include "geometry/quadric_solve.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

namespace {

// The quartic F, used for the root-rejection error bound (it is what the polynomial solves).
struct TorusQuartic {
    double R, r;
    double F(const Vec3d &p) const {
        double g = Dot(p, p) + R * R - r * r;
        return g * g - 4 * R * R * (p.x * p.x + p.y * p.y);
    }
    double FAbs(const Vec3d &p) const {
        double g = Dot(p, p) + R * R + r * r;
        return g * g + 4 * R * R * (p.x * p.x + p.y * p.y);
    }
    Vec3d Grad(const Vec3d &p) const {
        double g = Dot(p, p) + R * R - r * r;
        return Vec3d(p.x * (g - 2 * R * R), p.y * (g - 2 * R * R), p.z * g) * 4.0;
    }
};

// The signed distance to the torus, sqrt((rho - R)^2 + z^2) - r: the same surface as the
// quartic, but evaluated without the quartic's cancellation (which grows like R/r for thin
// tori). Used to polish roots and to project hits, in the form ProjectToSurface expects.
struct TorusDistance {
    double R, r;
    double F(const Vec3d &p) const {
        double rho = std::hypot(p.x, p.y);
        return std::hypot(rho - R, p.z) - r;
    }
    // Rounding of hypot, rho - R and the final subtraction: a few ulps of these magnitudes.
    double FAbs(const Vec3d &p) const { return std::hypot(p.x, p.y) + R + std::abs(p.z) + r; }
    Vec3d Grad(const Vec3d &p) const {
        double rho = std::hypot(p.x, p.y);
        // On the axis (never on the surface, since r < R) any horizontal direction will do.
        Vec3d radial = rho > 0 ? Vec3d(p.x / rho, p.y / rho, 0) : Vec3d(1, 0, 0);
        Vec3d v = radial * (rho - R) + Vec3d(0, 0, p.z);
        double l = Length(v);
        return l > 0 ? v / l : Vec3d(0, 0, 1);
    }
};

// [t0, t1] ∩ [lo, hi] (in place); false if empty.
bool Clip(double lo, double hi, double *t0, double *t1) {
    *t0 = std::max(*t0, lo);
    *t1 = std::min(*t1, hi);
    return *t0 <= *t1;
}

// Parameter interval (unit direction d) where the ray is inside both the bounding sphere
// (radius R + r, closest-approach form) and the slab |z| <= r, widened by a relative slack.
bool BoundingInterval(const Vec3d &o, const Vec3d &d, double R, double r, double slack,
                      double *tau0, double *tau1) {
    double rb = (R + r) * (1 + slack);
    double b = Dot(o, d);
    double len = Length(o - d * b);
    if (len > rb) return false;
    double h = std::sqrt((rb + len) * (rb - len));
    double pad = slack * (std::abs(b) + h);
    *tau0 = -b - h - pad;
    *tau1 = -b + h + pad;
    double rz = r * (1 + slack);
    if (d.z == 0) return std::abs(o.z) <= rz;
    double s0 = (-rz - o.z) / d.z, s1 = (rz - o.z) / d.z;
    if (s0 > s1) std::swap(s0, s1);
    return Clip(s0 - slack * std::abs(s0), s1 + slack * std::abs(s1), tau0, tau1);
}

}  // namespace

Torus::Torus(const Transform &renderFromObject, bool reverseOrientation, double majorRadius,
             double minorRadius, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      R_(majorRadius),
      r_(minorRadius),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    if (!(majorRadius > 0) || !std::isfinite(majorRadius))
        throw std::invalid_argument("torus majorradius must be positive");
    if (!(minorRadius > 0) || !std::isfinite(minorRadius))
        throw std::invalid_argument("torus minorradius must be positive");
    if (!(minorRadius < majorRadius))
        throw std::invalid_argument("torus minorradius must be smaller than majorradius");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("torus phimax must be positive");
}

Bounds3d Torus::ObjectBounds() const {
    double e = R_ + r_;
    return Bounds3d(Vec3d(-e, -e, -r_), Vec3d(e, e, r_));
}

double Torus::Implicit(const Vec3d &p) const { return TorusDistance{R_, r_}.F(p); }
Vec3d Torus::ImplicitGradient(const Vec3d &p) const { return TorusDistance{R_, r_}.Grad(p); }

Vec3d Torus::NormalField(const Vec3d &p) const {
    const double rho = std::hypot(p.x, p.y);
    const Vec3d radial = rho > 0 ? Vec3d(p.x / rho, p.y / rho, 0) : Vec3d(1, 0, 0);
    return p - radial * R_;
}

Vec3d Torus::NormalFieldDerivative(const Vec3d &p, const Vec3d &dp) const {
    // d(radial) = (dq - radial (radial . dq)) / rho with dq = (dx, dy, 0).
    const double rho = std::hypot(p.x, p.y);
    if (!(rho > 0)) return dp;  // on the axis: never on the surface (r < R)
    const Vec3d radial(p.x / rho, p.y / rho, 0), dq(dp.x, dp.y, 0);
    return dp - (dq - radial * Dot(radial, dq)) * (R_ / rho);
}

int Torus::Roots(const Vec3d &o, const Vec3d &dIn, double tMin, double tMax, double tSlack,
                 Root roots[4]) const {
    // Unit direction: the quartic is then monic; tau = t |d|.
    double dLen = Length(dIn);
    if (!(dLen > 0) || !std::isfinite(dLen)) return 0;
    Vec3d d = dIn / dLen;
    const double R = R_, r = r_;
    const double slack = Gamma<double>(16);
    double tau0, tau1;
    if (!BoundingInterval(o, d, R, r, slack, &tau0, &tau1)) return 0;
    double lo = tau0, hi = tau1;
    if (!Clip(tMin * dLen, tMax * dLen, &lo, &hi)) return 0;

    // Shift the origin to the bounding-sphere entry so the coefficients are shape-sized.
    // A ray starting inside (e.g. spawned from the surface) keeps its origin: its roots near
    // tau = 0 are then resolved to the ulps of the origin itself.
    double ts = std::max(tau0, 0.0);
    Vec3d os = o + d * ts;

    // F(os + tau d) = tau^4 + 4 b tau^3 + (2k + 4 b^2 + 4 R^2 dz^2) tau^2
    //                + (4 b k + 8 R^2 oz dz) tau + k^2 - 4 R^2 (r^2 - oz^2),  k = |os|^2 - R^2 -
    //                r^2.
    double bs = Dot(os, d);
    double k = Dot(os, os) - R * R - r * r;
    double coef[5] = {k * k - 4 * R * R * (r * r - os.z * os.z),
                      4 * bs * k + 8 * R * R * os.z * d.z,
                      2 * k + 4 * bs * bs + 4 * R * R * d.z * d.z, 4 * bs, 1};
    double tauRoots[4];
    double isoPad = slack * (R + r + std::abs(hi - ts));
    int n = PolynomialRoots(coef, 4, lo - ts - isoPad, hi - ts + isoPad, tauRoots);

    TorusQuartic f{R, r};
    TorusDistance dist{R, r};
    // Position uncertainty of os: its rounding plus the caller's origin error.
    double posErr = Gamma<double>(4) * (Length(o) + ts) + tSlack * dLen;
    double d2coef[3] = {2 * coef[2], 6 * coef[3], 12 * coef[4]};
    int count = 0;
    // Points on the caller's ray with one rounding per component (fma): the polished t is
    // then limited by F's conditioning, not by |o| (the shift and the normalization of d
    // each cost an ulp of |o|, which is far more than an ulp of |p| for a distant eye).
    auto at = [&](double t) {
        return Vec3d(std::fma(t, dIn.x, o.x), std::fma(t, dIn.y, o.y), std::fma(t, dIn.z, o.z));
    };
    for (int i = 0; i < n; ++i) {
        double tau = tauRoots[i];
        // The root's own error: the interval around it where |F| is below F's evaluation
        // error, from a second-order model (covers tangent double roots, where F' -> 0).
        Vec3d p = os + d * tau;
        Vec3d grad = f.Grad(p);
        double fErr = Gamma<double>(12) * f.FAbs(p) + Length(grad) * posErr;
        double tauErr = RootError(fErr, Dot(grad, d), EvalPolynomial(d2coef, 2, tau));
        double tauTotal = ts + tau;
        if (!(tauTotal > tauErr + Gamma<double>(2) * ts)) continue;
        // Polish on F itself along the original ray, which is better conditioned than the
        // expanded quartic; a step is kept only if it reduces |F| and stays nearer to this
        // root than to its neighbours (a near-double pair must not collapse into one).
        double t = tauTotal / dLen;
        double maxStep = std::numeric_limits<double>::infinity();
        if (i > 0) maxStep = std::min(maxStep, 0.5 * (tau - tauRoots[i - 1]) / dLen);
        if (i + 1 < n) maxStep = std::min(maxStep, 0.5 * (tauRoots[i + 1] - tau) / dLen);
        double t0 = t;
        double fv = dist.F(at(t));
        for (int it = 0; it < 2 && fv != 0; ++it) {
            double df = Dot(dist.Grad(at(t)), dIn);
            if (!(df != 0)) break;
            double tn = t - fv / df;
            if (!(std::abs(tn - t0) <= maxStep)) break;
            double fn = dist.F(at(tn));
            if (!(std::abs(fn) < std::abs(fv))) break;
            t = tn;
            fv = fn;
        }
        if (!(t > tMin) || !(t < tMax)) continue;
        Root &out = roots[count++];
        out.t = t;
        out.p = at(t);
        ProjectToSurface(dist, &out.p, &out.pError);
    }
    // Polishing can reorder two roots of a near-double pair.
    std::sort(roots, roots + count, [](const Root &a, const Root &b) { return a.t < b.t; });
    return count;
}

template <typename Real>
bool Torus::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                       ObjectHit *hit) const {
    // The quartic is always solved in double: a float quartic loses the thin-torus and
    // grazing cases entirely. Real only sets the precision of the incoming ray.
    Root roots[4];
    int n = Roots(Vec3d(o), Vec3d(d), double(tMin), double(tMax), double(tSlack), roots);
    for (int i = 0; i < n; ++i) {
        double phi = Azimuth(roots[i].p.x, roots[i].p.y);
        // A clipped torus can need any of its four roots.
        if (phi > phiMax_) continue;
        hit->t = roots[i].t;
        hit->p = roots[i].p;
        hit->pError = roots[i].pError;
        hit->phi = phi;
        return true;
    }
    return false;
}

template bool Torus::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Torus::IntersectT<double>(Vec3d, Vec3d, double, double, double, ObjectHit *) const;

LocalGeometry Torus::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double rho = std::hypot(p.x, p.y);
    double cosPhi = std::cos(hit.phi), sinPhi = std::sin(hit.phi);
    // theta: angle around the tube, 0 at the outer equator, pi/2 at the top.
    double theta = std::atan2(p.z, rho - R_);
    if (theta < 0) theta += 2 * Pi;
    g.uv = {hit.phi / phiMax_, theta / (2 * Pi)};
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    g.dpdv = Vec3d(-p.z * cosPhi, -p.z * sinPhi, rho - R_) * (2 * Pi);
    // p - R (cos phi, sin phi, 0): the outward tube normal, along grad F and along
    // cross(dpdu, dpdv) = 2 pi phiMax rho (cos theta cos phi, cos theta sin phi, sin theta) r.
    g.n = Vec3d((rho - R_) * cosPhi, (rho - R_) * sinPhi, p.z);
    return g;
}

// The profile swept about z (tessellation and `prism validate`).
bool Torus::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Torus;
    pr->phiMax = phiMax_;
    pr->a = R_;
    pr->b = r_;
    pr->closedV = true;
    return true;
}

// Shape "torus" (shape_list.inc; a Prism extension, each value checked so the error points at
// the offending parameter). Parameters:
//   majorradius  float  1     the centre circle's, > 0
//   minorradius  float  0.25  the tube's, > 0
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Torus>(const ShapeParams &params,
                                                  const Transform &renderFromObject,
                                                  bool reverseOrientation) {
    float major = params.PositiveFloat("majorradius", 1.f);
    float minor = params.PositiveFloat("minorradius", 0.25f);
    float phimax = params.PhiMax();
    if (!(minor < major))
        throw SceneError(params.Loc("minorradius"),
                         "torus minorradius must be smaller than majorradius");
    return params.Construct("minorradius", [&] {
        return std::make_unique<Torus>(renderFromObject, reverseOrientation, major, minor, phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Torus>(const Transform &renderFromObject) {
    return std::make_unique<Torus>(renderFromObject, false, 1, 0.3, 360);
}

PRISM_USER_GEOMETRY(Torus)

}  // namespace prism
