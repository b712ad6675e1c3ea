// Prism's torus (not a pbrt-v3 shape): axis z, major radius R, minor radius r < R, the surface
// (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2), clipped to phi <= phimax. The quartic is solved
// in double after culling and an origin shift; all real roots are isolated by derivative
// bracketing (polynomial.h) and polished by Newton steps on the tube's distance function.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Torus final : public AnalyticShapeT<Torus> {
  public:
    // Throws std::invalid_argument for R <= 0, r <= 0, r >= R (spindle/horn tori) or phimax
    // outside (0, 360].
    Torus(const Transform &renderFromObject, bool reverseOrientation, double majorRadius,
          double minorRadius, double phiMaxDeg);

    const char *Name() const override { return "torus"; }
    Bounds3d ObjectBounds() const override;
    // The signed distance sqrt((rho - R)^2 + z^2) - r: zero on the quartic's surface,
    // positive outside, and free of the quartic's R/r cancellation.
    double Implicit(const Vec3d &p) const override;
    Vec3d ImplicitGradient(const Vec3d &p) const override;
    // Curvature: the field p - R radial(p) (from the tube's centre circle to p).
    Vec3d NormalField(const Vec3d &p) const override;
    Vec3d NormalFieldDerivative(const Vec3d &p, const Vec3d &dp) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

    // Every surface crossing of the object-space ray o + t d with t in (tMin, tMax), phi
    // clipping ignored, ascending; roots within their own error bound of t = 0 are dropped.
    // tSlack is the uncertainty of t from the origin's rounding. Returns the count (<= 4).
    struct Root {
        double t;
        Vec3d p, pError;
    };
    int Roots(const Vec3d &o, const Vec3d &d, double tMin, double tMax, double tSlack,
              Root roots[4]) const;

    double MajorRadius() const { return R_; }
    double MinorRadius() const { return r_; }
    bool IsPartial() const { return phiMax_ < 2 * Pi; }

  private:
    double R_, r_, phiMax_;
};

}  // namespace prism
