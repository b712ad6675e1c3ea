#include "geometry/disk.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/quadric_util.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

Disk::Disk(const Transform &renderFromObject, bool reverseOrientation, double height, double radius,
           double innerRadius, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      height_(height),
      radius_(radius),
      innerRadius_(innerRadius),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw std::invalid_argument("disk radius must be positive");
    if (!(innerRadius >= 0) || !(innerRadius < radius))
        throw std::invalid_argument("disk innerradius must be in [0, radius)");
    if (!std::isfinite(height)) throw std::invalid_argument("disk height must be finite");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("disk phimax must be positive");
}

Bounds3d Disk::ObjectBounds() const {
    return Bounds3d(Vec3d(-radius_, -radius_, height_), Vec3d(radius_, radius_, height_));
}

template <typename Real>
bool Disk::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                      ObjectHit *hit) const {
    // A ray in the plane's direction (edge-on) never crosses it: a miss, not a NaN.
    if (d.z == 0) return false;
    const Real h = Real(height_);
    Real t = (h - o.z) / d.z;
    // The sign of h - oz is exact; its magnitude is uncertain by the rounding of h and oz
    // and by the origin's transform error (tSlack |d|), divided by |dz|.
    Real tErr =
        (Gamma<Real>(3) * (std::abs(h) + std::abs(o.z)) + tSlack * Length(d)) / std::abs(d.z);
    if (!(t > std::max(tMin, tErr)) || !(t < tMax)) return false;
    Vec3d p(o + d * t);
    p.z = height_;
    double dist2 = p.x * p.x + p.y * p.y;
    if (dist2 > radius_ * radius_ || dist2 < innerRadius_ * innerRadius_) return false;
    // The azimuth (an atan2) only where it can clip; Geometry computes it for uv.
    double phi = phiMax_ < 2 * Pi ? Azimuth(p.x, p.y) : 0;
    if (phi > phiMax_) return false;
    hit->t = double(t);
    hit->p = p;
    // z is exact (set to the plane); x and y only carry tangential rounding.
    hit->pError = Vec3d(std::abs(p.x), std::abs(p.y), 0) * double(Gamma<Real>(3));
    hit->phi = phi;
    return true;
}

template bool Disk::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Disk::IntersectT<double>(Vec3d, Vec3d, double, double, double, ObjectHit *) const;

LocalGeometry Disk::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double dist = std::hypot(p.x, p.y);
    double phi = phiMax_ < 2 * Pi ? hit.phi : Azimuth(p.x, p.y);
    g.uv = {phi / phiMax_, (radius_ - dist) / (radius_ - innerRadius_)};
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    // At the centre the radial direction is undefined; use phi = 0's.
    Vec3d radial = dist > 0 ? Vec3d(p.x / dist, p.y / dist, 0) : Vec3d(1, 0, 0);
    g.dpdv = radial * (innerRadius_ - radius_);
    // cross(dpdu, dpdv) = phiMax rho (radius - innerradius) (0, 0, 1).
    g.n = Vec3d(0, 0, 1);
    return g;
}

bool Disk::SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const {
    // Uniform by area over the annulus sector: r^2 uniform in [ri^2, r^2], phi uniform.
    double r2 = Lerp(double(u.x), innerRadius_ * innerRadius_, radius_ * radius_);
    double r = std::sqrt(r2), phi = double(u.y) * phiMax_;
    *p = Vec3d(r * std::cos(phi), r * std::sin(phi), height_);
    *n = Vec3d(0, 0, 1);
    double area = 0.5 * phiMax_ * (radius_ * radius_ - innerRadius_ * innerRadius_);
    *pdfArea = area > 0 ? 1 / area : 0;
    return area > 0;
}

// The profile swept about z (tessellation and `prism validate`).
bool Disk::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Disk;
    pr->phiMax = phiMax_;
    pr->a = radius_;  // v = 0 on the outer rim, as the shape's uv.v
    pr->b = innerRadius_;
    pr->c = height_;
    pr->poleV1 = innerRadius_ == 0;
    return true;
}

// Shape "disk" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the error
// points at the offending parameter). Parameters:
//   height       float  0     its z
//   radius       float  1     > 0
//   innerradius  float  0     in [0, radius): an annulus
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Disk>(const ShapeParams &params,
                                                 const Transform &renderFromObject,
                                                 bool reverseOrientation) {
    float height = params.FiniteFloat("height", 0.f);
    float radius = params.PositiveFloat("radius", 1.f);
    float inner = params.Float("innerradius", 0.f);
    if (!(inner >= 0) || !(inner < radius))
        throw SceneError(params.Loc("innerradius"), "disk innerradius must be in [0, radius)");
    float phimax = params.PhiMax();
    return params.Construct("radius", [&] {
        return std::make_unique<Disk>(renderFromObject, reverseOrientation, height, radius, inner,
                                      phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Disk>(const Transform &renderFromObject) {
    return std::make_unique<Disk>(renderFromObject, false, 0, 1, 0.3, 300);
}

PRISM_USER_GEOMETRY(Disk)

}  // namespace prism
