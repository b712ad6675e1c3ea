#include "geometry/cylinder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/quadric_solve.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

Cylinder::Cylinder(const Transform &renderFromObject, bool reverseOrientation, double radius,
                   double zMin, double zMax, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      radius_(radius),
      zMin_(std::min(zMin, zMax)),
      zMax_(std::max(zMin, zMax)),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw std::invalid_argument("cylinder radius must be positive");
    if (!(zMin_ < zMax_) || !std::isfinite(zMin_) || !std::isfinite(zMax_))
        throw std::invalid_argument("cylinder zmin and zmax must differ");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("cylinder phimax must be positive");
}

Bounds3d Cylinder::ObjectBounds() const {
    return Bounds3d(Vec3d(-radius_, -radius_, zMin_), Vec3d(radius_, radius_, zMax_));
}

Vec3d Cylinder::ImplicitGradient(const Vec3d &p) const {
    double l = std::hypot(p.x, p.y);
    return l > 0 ? Vec3d(p.x / l, p.y / l, 0) : Vec3d(1, 0, 0);
}

template <typename Real>
bool Cylinder::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                          ObjectHit *hit) const {
    const Real r = Real(radius_);
    Real a = d.x * d.x + d.y * d.y;
    // A ray parallel to the axis never crosses the (open) wall transversally: a miss.
    if (!(a > 0)) return false;
    Real b = 2 * (d.x * o.x + d.y * o.y);
    Real oo = o.x * o.x + o.y * o.y;
    Real c = oo - r * r;
    // pbrt-v4 / Ray Tracing Gems ch. 7 in 2-D: b^2 - 4ac = 4a (r^2 - |v|^2) with v the
    // closest approach of the projected ray to the axis.
    Real f = b / (2 * a);
    Real vx = o.x - f * d.x, vy = o.y - f * d.y;
    Real len = std::sqrt(vx * vx + vy * vy);
    Real discrim = 4 * a * (r + len) * (r - len);
    Real t0, t1, q;
    if (!SolveQuadratic(a, b, c, discrim, &t0, &t1, &q)) return false;

    Real tErr =
        Gamma<Real>(8) * ((oo + r * r) / std::max(std::abs(q), std::numeric_limits<Real>::min()) +
                          std::abs(t0) + std::abs(t1)) +
        Gamma<Real>(4) * std::sqrt(oo / a);
    // The origin's transform error (tSlack |d|) moves a root by |grad F| |dp| / |f'(t)|,
    // which grows for rays grazing the wall.
    double posErr = double(tSlack) * double(Length(d));
    for (Real t : {t0, t1}) {
        if (!(t < tMax)) break;
        Vec3d p(o + d * t);
        double f1 = 2 * (p.x * double(d.x) + p.y * double(d.y));
        double err = double(tErr) + RootError(2 * radius_ * posErr, f1, 2 * double(a));
        if (!(double(t) > std::max(double(tMin), err))) continue;
        // Re-project (x, y) onto the circle, in double regardless of Real.
        double l = std::hypot(p.x, p.y);
        if (!(l > 0)) continue;
        p.x *= radius_ / l;
        p.y *= radius_ / l;
        // The azimuth (an atan2) only where it can clip; Geometry computes it for uv.
        double phi = phiMax_ < 2 * Pi ? Azimuth(p.x, p.y) : 0;
        if (p.z < zMin_ || p.z > zMax_ || phi > phiMax_) continue;
        hit->t = double(t);
        hit->p = p;
        hit->pError = Vec3d(std::abs(p.x), std::abs(p.y), 0) * double(Gamma<Real>(3));
        hit->phi = phi;
        return true;
    }
    return false;
}

template bool Cylinder::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Cylinder::IntersectT<double>(Vec3d, Vec3d, double, double, double, ObjectHit *) const;

LocalGeometry Cylinder::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double phi = phiMax_ < 2 * Pi ? hit.phi : Azimuth(p.x, p.y);
    g.uv = {phi / phiMax_, (p.z - zMin_) / (zMax_ - zMin_)};
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    g.dpdv = Vec3d(0, 0, zMax_ - zMin_);
    // cross(dpdu, dpdv) = phiMax (zmax - zmin) (x, y, 0): outward.
    g.n = Vec3d(p.x, p.y, 0);
    return g;
}

bool Cylinder::SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const {
    double z = Lerp(double(u.x), zMin_, zMax_), phi = double(u.y) * phiMax_;
    *p = Vec3d(radius_ * std::cos(phi), radius_ * std::sin(phi), z);
    *n = Vec3d(p->x, p->y, 0);  // outward, as cross(dpdu, dpdv)
    double area = (zMax_ - zMin_) * radius_ * phiMax_;
    *pdfArea = area > 0 ? 1 / area : 0;
    return area > 0;
}

// The profile swept about z (tessellation and `prism validate`).
bool Cylinder::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Cylinder;
    pr->phiMax = phiMax_;
    pr->a = radius_;
    pr->b = zMin_;
    pr->c = zMax_;
    return true;
}

// Shape "cylinder" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the
// error points at the offending parameter). Parameters:
//   radius       float  1      > 0
//   zmin, zmax   float  -1, 1  its extent along z; they must differ
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Cylinder>(const ShapeParams &params,
                                                     const Transform &renderFromObject,
                                                     bool reverseOrientation) {
    float radius = params.PositiveFloat("radius", 1.f);
    float zmin = params.FiniteFloat("zmin", -1.f), zmax = params.FiniteFloat("zmax", 1.f);
    float phimax = params.PhiMax();
    if (zmin == zmax) throw SceneError(params.Loc("zmax"), "cylinder zmin and zmax must differ");
    return params.Construct("zmax", [&] {
        return std::make_unique<Cylinder>(renderFromObject, reverseOrientation, radius, zmin, zmax,
                                          phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Cylinder>(const Transform &renderFromObject) {
    return std::make_unique<Cylinder>(renderFromObject, false, 1, -1, 1, 360);
}

PRISM_USER_GEOMETRY(Cylinder)

}  // namespace prism
