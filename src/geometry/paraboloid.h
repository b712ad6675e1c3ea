// pbrt-v3's paraboloid k (x^2 + y^2) = z with k = zmax / r^2, clipped to z in [zmin, zmax]
// and phi <= phimax. Solved in the shifted-origin form of quadric_solve.h.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Paraboloid final : public AnalyticShapeT<Paraboloid> {
  public:
    // Throws std::invalid_argument for radius <= 0, max(zmin, zmax) <= 0, zmin == zmax or
    // phimax outside (0, 360].
    Paraboloid(const Transform &renderFromObject, bool reverseOrientation, double radius,
               double zMin, double zMax, double phiMaxDeg);

    const char *Name() const override { return "paraboloid"; }
    Bounds3d ObjectBounds() const override;
    double Implicit(const Vec3d &p) const override;  // k (x^2 + y^2) - z, positive outside
    Vec3d ImplicitGradient(const Vec3d &p) const override;
    // Curvature: the field is the quadric's gradient (the default NormalField), linear in p.
    Vec3d NormalFieldDerivative(const Vec3d &p, const Vec3d &dp) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    Vec3d GeometricNormal(const ObjectHit &hit) const override {
        return {2 * k_ * hit.p.x, 2 * k_ * hit.p.y, -1};
    }
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

  private:
    double radius_, zMin_, zMax_, phiMax_, k_;
};

}  // namespace prism
