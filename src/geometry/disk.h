// pbrt's disk: the annulus innerradius <= rho <= radius, phi <= phimax, in the plane z = h.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Disk final : public AnalyticShapeT<Disk> {
  public:
    // Throws std::invalid_argument for radius <= 0, innerradius outside [0, radius) or
    // phimax outside (0, 360].
    Disk(const Transform &renderFromObject, bool reverseOrientation, double height, double radius,
         double innerRadius, double phiMaxDeg);

    const char *Name() const override { return "disk"; }
    Bounds3d ObjectBounds() const override;
    // Signed distance to the plane (a disk has no inside; +z is the side its normal faces).
    double Implicit(const Vec3d &p) const override { return p.z - height_; }
    Vec3d ImplicitGradient(const Vec3d &) const override { return {0, 0, 1}; }
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    Vec3d GeometricNormal(const ObjectHit &) const override { return {0, 0, 1}; }
    // A plane: the normal does not change.
    Vec3d NormalFieldDerivative(const Vec3d &, const Vec3d &) const override { return {}; }
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

    bool SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const override;

  private:
    double height_, radius_, innerRadius_, phiMax_;
};

}  // namespace prism
