#include "geometry/cone.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/quadric_solve.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

namespace {
RotationalQuadric ConeQuadric(double radius, double height) {
    RotationalQuadric q;
    q.A = 1;
    q.B = -(radius / height) * (radius / height);
    q.z0 = height;
    return q;
}
}  // namespace

Cone::Cone(const Transform &renderFromObject, bool reverseOrientation, double radius, double height,
           double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      radius_(radius),
      height_(height),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw std::invalid_argument("cone radius must be positive");
    if (!(height > 0) || !std::isfinite(height))
        throw std::invalid_argument("cone height must be positive");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("cone phimax must be positive");
}

Bounds3d Cone::ObjectBounds() const {
    return Bounds3d(Vec3d(-radius_, -radius_, 0), Vec3d(radius_, radius_, height_));
}

double Cone::Implicit(const Vec3d &p) const { return ConeQuadric(radius_, height_).F(p); }
Vec3d Cone::ImplicitGradient(const Vec3d &p) const { return ConeQuadric(radius_, height_).Grad(p); }
Vec3d Cone::NormalFieldDerivative(const Vec3d &, const Vec3d &dp) const {
    return ConeQuadric(radius_, height_).GradDerivative(dp);
}

template <typename Real>
bool Cone::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                      ObjectHit *hit) const {
    auto clip = [this](const Vec3d &p, double *phi) {
        *phi = Azimuth(p.x, p.y);
        return p.z >= 0 && p.z <= height_ && *phi <= phiMax_;
    };
    return IntersectRotationalQuadric(ConeQuadric(radius_, height_), ObjectBounds(), o, d, tMin,
                                      tMax, tSlack, clip, hit);
}

template bool Cone::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Cone::IntersectT<double>(Vec3d, Vec3d, double, double, double, ObjectHit *) const;

LocalGeometry Cone::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double cosPhi = std::cos(hit.phi), sinPhi = std::sin(hit.phi);
    g.uv = {hit.phi / phiMax_, p.z / height_};
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    // pbrt's (-x/(1-v), -y/(1-v), h), written without the division so the apex is defined.
    g.dpdv = Vec3d(-radius_ * cosPhi, -radius_ * sinPhi, height_);
    // cross(dpdu, dpdv) = phiMax rho (h cos phi, h sin phi, r): outward and up, along grad F.
    g.n = Vec3d(height_ * cosPhi, height_ * sinPhi, radius_);
    return g;
}

// The profile swept about z (tessellation and `prism validate`).
bool Cone::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Cone;
    pr->phiMax = phiMax_;
    pr->a = radius_;
    pr->b = height_;
    pr->poleV1 = true;  // the apex
    return true;
}

// Shape "cone" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the error
// points at the offending parameter). Parameters:
//   radius       float  1     the base's, > 0
//   height       float  1     the apex's z, > 0
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Cone>(const ShapeParams &params,
                                                 const Transform &renderFromObject,
                                                 bool reverseOrientation) {
    float radius = params.PositiveFloat("radius", 1.f);
    float height = params.PositiveFloat("height", 1.f);
    float phimax = params.PhiMax();
    return params.Construct("height", [&] {
        return std::make_unique<Cone>(renderFromObject, reverseOrientation, radius, height, phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Cone>(const Transform &renderFromObject) {
    return std::make_unique<Cone>(renderFromObject, false, 1, 1.5, 360);
}

PRISM_USER_GEOMETRY(Cone)

}  // namespace prism
