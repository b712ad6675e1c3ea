#include "geometry/paraboloid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/quadric_solve.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

namespace {
RotationalQuadric ParaboloidQuadric(double k) {
    RotationalQuadric q;
    q.A = k;
    q.C = -1;
    return q;
}
}  // namespace

Paraboloid::Paraboloid(const Transform &renderFromObject, bool reverseOrientation, double radius,
                       double zMin, double zMax, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      radius_(radius),
      zMin_(std::min(zMin, zMax)),
      zMax_(std::max(zMin, zMax)),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw std::invalid_argument("paraboloid radius must be positive");
    if (!(zMax_ > 0) || !std::isfinite(zMax_) || !std::isfinite(zMin_))
        throw std::invalid_argument("paraboloid zmax must be positive");
    if (!(zMin_ < zMax_)) throw std::invalid_argument("paraboloid zmin and zmax must differ");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("paraboloid phimax must be positive");
    k_ = zMax_ / (radius * radius);
    if (!(k_ > 0) || !std::isfinite(k_))
        throw std::invalid_argument("paraboloid zmax / radius^2 is out of range");
}

Bounds3d Paraboloid::ObjectBounds() const {
    // The surface does not exist below z = 0; a negative zmin still sets v as in pbrt.
    return Bounds3d(Vec3d(-radius_, -radius_, std::max(zMin_, 0.0)),
                    Vec3d(radius_, radius_, zMax_));
}

double Paraboloid::Implicit(const Vec3d &p) const { return ParaboloidQuadric(k_).F(p); }
Vec3d Paraboloid::ImplicitGradient(const Vec3d &p) const { return ParaboloidQuadric(k_).Grad(p); }
Vec3d Paraboloid::NormalFieldDerivative(const Vec3d &, const Vec3d &dp) const {
    return ParaboloidQuadric(k_).GradDerivative(dp);
}

template <typename Real>
bool Paraboloid::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                            ObjectHit *hit) const {
    auto clip = [this](const Vec3d &p, double *phi) {
        *phi = Azimuth(p.x, p.y);
        return p.z >= zMin_ && p.z <= zMax_ && *phi <= phiMax_;
    };
    return IntersectRotationalQuadric(ParaboloidQuadric(k_), ObjectBounds(), o, d, tMin, tMax,
                                      tSlack, clip, hit);
}

template bool Paraboloid::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Paraboloid::IntersectT<double>(Vec3d, Vec3d, double, double, double,
                                             ObjectHit *) const;

LocalGeometry Paraboloid::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    g.uv = {hit.phi / phiMax_, (p.z - zMin_) / (zMax_ - zMin_)};
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    // pbrt: (zmax - zmin) (x / 2z, y / 2z, 1); x / 2z = cos(phi) / (2 k rho) diverges at the
    // vertex, where only the z part is kept.
    double dz = zMax_ - zMin_;
    g.dpdv = p.z > 0 ? Vec3d(p.x / (2 * p.z), p.y / (2 * p.z), 1) * dz : Vec3d(0, 0, dz);
    // cross(dpdu, dpdv) = phiMax dz (x, y, -1/(2k)): along grad F = (2kx, 2ky, -1).
    g.n = Vec3d(2 * k_ * p.x, 2 * k_ * p.y, -1);
    return g;
}

// The profile swept about z (tessellation and `prism validate`).
bool Paraboloid::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Paraboloid;
    pr->phiMax = phiMax_;
    pr->a = k_;
    // Uniform in rho rather than z: rho = sqrt(z / k) has an infinite slope at the vertex, so
    // uniform z steps would make the first ring's chord error O(1/n) instead of O(1/n^2).
    double zLo = std::max(zMin_, 0.0);
    pr->b = std::sqrt(zLo / k_);
    pr->c = std::sqrt(zMax_ / k_);
    pr->poleV0 = zLo == 0;
    return pr->c > pr->b;
}

// Shape "paraboloid" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the
// error points at the offending parameter). Parameters:
//   radius       float  1     at zmax, > 0
//   zmin, zmax   float  0, 1  its extent along z; zmax > 0, and they must differ
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Paraboloid>(const ShapeParams &params,
                                                       const Transform &renderFromObject,
                                                       bool reverseOrientation) {
    float radius = params.PositiveFloat("radius", 1.f);
    float zmin = params.FiniteFloat("zmin", 0.f), zmax = params.FiniteFloat("zmax", 1.f);
    float phimax = params.PhiMax();
    if (!(std::max(zmin, zmax) > 0))
        throw SceneError(params.Loc("zmax"), "paraboloid zmax must be positive");
    if (zmin == zmax) throw SceneError(params.Loc("zmax"), "paraboloid zmin and zmax must differ");
    return params.Construct("zmax", [&] {
        return std::make_unique<Paraboloid>(renderFromObject, reverseOrientation, radius, zmin,
                                            zmax, phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Paraboloid>(const Transform &renderFromObject) {
    return std::make_unique<Paraboloid>(renderFromObject, false, 1, 0, 1.5, 360);
}

PRISM_USER_GEOMETRY(Paraboloid)

}  // namespace prism
