// pbrt-v3's cone: apex (0, 0, h), base radius r at z = 0, x^2 + y^2 = (r/h)^2 (z - h)^2 for
// z in [0, h], phi <= phimax. Solved in the shifted-origin form of quadric_solve.h.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Cone final : public AnalyticShapeT<Cone> {
  public:
    // Throws std::invalid_argument for radius <= 0, height <= 0 or phimax outside (0, 360].
    Cone(const Transform &renderFromObject, bool reverseOrientation, double radius, double height,
         double phiMaxDeg);

    const char *Name() const override { return "cone"; }
    Bounds3d ObjectBounds() const override;
    // Positive outside (farther from the axis than the surface).
    double Implicit(const Vec3d &p) const override;
    Vec3d ImplicitGradient(const Vec3d &p) const override;
    // Curvature: the field is the quadric's gradient (the default NormalField), linear in p.
    Vec3d NormalFieldDerivative(const Vec3d &p, const Vec3d &dp) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

  private:
    double radius_, height_, phiMax_;
};

}  // namespace prism
