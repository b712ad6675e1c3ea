// pbrt's sphere (radius, zmin, zmax, phimax) with a robust double-precision root routine.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Sphere final : public AnalyticShapeT<Sphere> {
  public:
    Sphere(const Transform &renderFromObject, bool reverseOrientation, double radius, double zMin,
           double zMax, double phiMaxDeg);

    const char *Name() const override { return "sphere"; }
    Bounds3d ObjectBounds() const override;
    double Implicit(const Vec3d &p) const override { return Length(p) - radius_; }
    Vec3d ImplicitGradient(const Vec3d &p) const override { return Normalize(p); }
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    Vec3d GeometricNormal(const ObjectHit &hit) const override { return hit.p; }
    // Curvature: the field p (radial), whose derivative along dp is dp.
    Vec3d NormalField(const Vec3d &p) const override { return p; }
    Vec3d NormalFieldDerivative(const Vec3d &, const Vec3d &dp) const override { return dp; }
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]
    bool SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const override;
    // Full spheres under similarity transforms sample the cone they subtend (pbrt-v3
    // Sphere::Sample), which wastes no samples on the far side; others sample by area.
    bool Sample(const Vec3f &ref, Vec2f u, ShapeSample *ss) const override;
    float Pdf(const Vec3f &ref, const Vec3f &p, const Vec3f &n) const override;

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

    double Radius() const { return radius_; }
    bool IsPartial() const { return partial_; }

  private:
    double radius_, zMin_, zMax_, thetaZMin_, thetaZMax_, phiMax_;
    bool partial_;
    bool similarity_;  // transform is rotation + uniform scale + translation
};

}  // namespace prism
