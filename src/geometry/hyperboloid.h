// pbrt-v3's hyperboloid: the surface a (x^2 + y^2) - c z^2 = 1 fitted to the segment p1 p2
// rotated about z (pbrt-v3's a_h, c_h fit), z between the points' heights, phi <= phimax.
// Solved in the shifted-origin form of quadric_solve.h.
#pragma once

#include "geometry/shape.h"

namespace prism {

class Hyperboloid final : public AnalyticShapeT<Hyperboloid> {
  public:
    // Throws std::invalid_argument when p1, p2 define no hyperboloid (equal points, equal
    // heights, a segment whose line meets the axis so the fit never converges, a <= 0) or
    // phimax is outside (0, 360].
    Hyperboloid(const Transform &renderFromObject, bool reverseOrientation, const Vec3d &p1,
                const Vec3d &p2, double phiMaxDeg);

    const char *Name() const override { return "hyperboloid"; }
    Bounds3d ObjectBounds() const override;
    double Implicit(const Vec3d &p) const override;  // a rho^2 - c z^2 - 1, positive outside
    Vec3d ImplicitGradient(const Vec3d &p) const override;
    // Curvature: the field is the quadric's gradient (the default NormalField), linear in p.
    Vec3d NormalFieldDerivative(const Vec3d &p, const Vec3d &dp) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    bool Revolution(RevolutionProfile *profile) const override;  // [validate hook]

    template <typename Real>
    bool IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                    ObjectHit *hit) const;

    double Ah() const { return ah_; }
    double Ch() const { return ch_; }

  private:
    double Phi(const Vec3d &p) const;  // azimuth relative to the rotated profile point

    Vec3d p1_, p2_;
    double zMin_, zMax_, rMax_, phiMax_, ah_ = 0, ch_ = 0;
};

}  // namespace prism
