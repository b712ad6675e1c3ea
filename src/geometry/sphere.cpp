#include "geometry/sphere.h"

#include <algorithm>
#include <cmath>

#include "geometry/quadric_util.h"

namespace prism {

Sphere::Sphere(const Transform &worldFromObject, bool reverseOrientation, double radius,
               double zMin, double zMax, double phiMaxDeg)
    : AnalyticShapeT(worldFromObject, reverseOrientation),
      radius_(radius),
      zMin_(Clamp(std::min(zMin, zMax), -radius, radius)),
      zMax_(Clamp(std::max(zMin, zMax), -radius, radius)),
      thetaZMin_(std::acos(Clamp(std::min(zMin, zMax) / radius, -1.0, 1.0))),
      thetaZMax_(std::acos(Clamp(std::max(zMin, zMax) / radius, -1.0, 1.0))),
      phiMax_(Radians(Clamp(phiMaxDeg, 0.0, 360.0))) {
    partial_ = zMin_ > -radius_ || zMax_ < radius_ || phiMax_ < 2 * Pi;
}

Bounds3d Sphere::ObjectBounds() const {
    return Bounds3d(Vec3d(-radius_, -radius_, zMin_), Vec3d(radius_, radius_, zMax_));
}

template <typename Real>
bool Sphere::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                        ObjectHit *hit) const {
    const Real r = Real(radius_);
    Real a = Dot(d, d);
    if (!(a > 0)) return false;
    Real b = 2 * Dot(d, o);
    Real c = Dot(o, o) - r * r;
    // Cancellation-free discriminant (Haines et al., Ray Tracing Gems ch. 7; pbrt-v4):
    // b^2 - 4ac = 4a (r^2 - |o - (b/2a) d|^2).
    Vec3<Real> v = o - d * (b / (2 * a));
    Real len = Length(v);
    Real discrim = 4 * a * (r + len) * (r - len);
    Real t0, t1, q;
    if (!SolveQuadratic(a, b, c, discrim, &t0, &t1, &q)) return false;

    // Conservative bound on the roots' rounding error: c/q carries the error of |o|^2 - r^2,
    // q/a a few ulps of itself, and the object-space origin the error of its transform.
    Real oo = Dot(o, o);
    Real tErr = Gamma<Real>(8) * ((oo + r * r) / std::max(std::abs(q), std::numeric_limits<Real>::min()) +
                                  std::abs(t0) + std::abs(t1)) +
                Gamma<Real>(4) * std::sqrt(oo / a) + tSlack;
    Real lo = std::max(tMin, tErr);
    for (Real t : {t0, t1}) {
        if (!(t > lo)) continue;
        if (!(t < tMax)) break;
        Vec3<Real> pr = o + d * t;
        // Re-project onto the surface, in double regardless of Real.
        Vec3d p(pr);
        p *= radius_ / Length(p);
        if (p.x == 0 && p.y == 0) p.x = 1e-5 * radius_;
        double phi = Azimuth(p.x, p.y);
        if (partial_ && ((zMin_ > -radius_ && p.z < zMin_) || (zMax_ < radius_ && p.z > zMax_) ||
                         phi > phiMax_))
            continue;
        hit->t = double(t);
        hit->p = p;
        hit->pError = Abs(p) * double(Gamma<Real>(5));
        hit->phi = phi;
        return true;
    }
    return false;
}

template bool Sphere::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Sphere::IntersectT<double>(Vec3d, Vec3d, double, double, double,
                                         ObjectHit *) const;

LocalGeometry Sphere::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double u = hit.phi / phiMax_;
    double cosTheta = Clamp(p.z / radius_, -1.0, 1.0);
    double theta = std::acos(cosTheta);
    double v = (theta - thetaZMin_) / (thetaZMax_ - thetaZMin_);
    g.uv = {u, v};
    double zRadius = std::sqrt(p.x * p.x + p.y * p.y);
    double cosPhi = p.x / zRadius, sinPhi = p.y / zRadius;
    double sinTheta = SafeSqrt(1 - cosTheta * cosTheta);
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    g.dpdv = Vec3d(p.z * cosPhi, p.z * sinPhi, -radius_ * sinTheta) * (thetaZMax_ - thetaZMin_);
    // cross(dpdu, dpdv) points along +p; use p itself, which stays defined at the poles.
    g.n = p;
    return g;
}

}  // namespace prism
