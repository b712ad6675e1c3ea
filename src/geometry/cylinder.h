// pbrt's open cylinder x^2 + y^2 = r^2, z in [zmin, zmax], phi <= phimax, with pbrt-v4's
// cancellation-free 2-D discriminant.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Cylinder final : public AnalyticShapeT<Cylinder> {
  public:
    // Throws std::invalid_argument for radius <= 0, zmin == zmax or phimax outside (0, 360].
    Cylinder(const Transform &renderFromObject, bool reverseOrientation, double radius, double zMin,
             double zMax, double phiMaxDeg);

    const char *Name() const override { return "cylinder"; }
    Bounds3d ObjectBounds() const override;
    double Implicit(const Vec3d &p) const override { return std::hypot(p.x, p.y) - radius_; }
    Vec3d ImplicitGradient(const Vec3d &p) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    Vec3d GeometricNormal(const ObjectHit &hit) const override { return {hit.p.x, hit.p.y, 0}; }
    // Curvature: the field (x, y, 0), linear in p.
    Vec3d NormalField(const Vec3d &p) const override { return {p.x, p.y, 0}; }
    Vec3d NormalFieldDerivative(const Vec3d &, const Vec3d &dp) const override {
        return {dp.x, dp.y, 0};
    }
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

    bool IsPartial() const { return phiMax_ < 2 * Pi; }

    bool SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const override;

  private:
    double radius_, zMin_, zMax_, phiMax_;
};

}  // namespace prism
