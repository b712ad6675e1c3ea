#include "geometry/sphere.h"

#include <algorithm>
#include <cmath>

#include "geometry/quadric_util.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

Sphere::Sphere(const Transform &renderFromObject, bool reverseOrientation, double radius,
               double zMin, double zMax, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      radius_(radius),
      zMin_(Clamp(std::min(zMin, zMax), -radius, radius)),
      zMax_(Clamp(std::max(zMin, zMax), -radius, radius)),
      thetaZMin_(std::acos(Clamp(std::min(zMin, zMax) / radius, -1.0, 1.0))),
      thetaZMax_(std::acos(Clamp(std::max(zMin, zMax) / radius, -1.0, 1.0))),
      phiMax_(Radians(Clamp(phiMaxDeg, 0.0, 360.0))) {
    partial_ = zMin_ > -radius_ || zMax_ < radius_ || phiMax_ < 2 * Pi;
    Vec3d ex = renderFromObject.Vector(Vec3d(1, 0, 0)),
          ey = renderFromObject.Vector(Vec3d(0, 1, 0)),
          ez = renderFromObject.Vector(Vec3d(0, 0, 1));
    double lx = Length(ex), ly = Length(ey), lz = Length(ez);
    similarity_ = std::abs(lx - ly) <= 1e-9 * lx && std::abs(lx - lz) <= 1e-9 * lx &&
                  std::abs(Dot(ex, ey)) <= 1e-9 * lx * ly &&
                  std::abs(Dot(ex, ez)) <= 1e-9 * lx * lz &&
                  std::abs(Dot(ey, ez)) <= 1e-9 * ly * lz;
}

bool Sphere::SampleObjectArea(Vec2f u, Vec3d *p, Vec3d *n, double *pdfArea) const {
    // Uniform in z (Archimedes) and phi over the clipped band.
    double z = Lerp(double(u.x), zMin_, zMax_);
    double phi = double(u.y) * phiMax_;
    double rxy = SafeSqrt(radius_ * radius_ - z * z);
    *p = Vec3d(rxy * std::cos(phi), rxy * std::sin(phi), z);
    *n = *p;
    double area = phiMax_ * radius_ * (zMax_ - zMin_);
    *pdfArea = area > 0 ? 1 / area : 0;
    return area > 0;
}

bool Sphere::Sample(const Vec3f &ref, Vec2f u, ShapeSample *ss) const {
    if (partial_ || !similarity_) return AnalyticShape::Sample(ref, u, ss);
    Vec3d c = renderFromObject_.Point(Vec3d(0, 0, 0));
    double rW = radius_ * Length(renderFromObject_.Vector(Vec3d(1, 0, 0)));
    Vec3d wc = c - Vec3d(ref);
    double dc2 = LengthSquared(wc);
    if (dc2 <= rW * rW * (1 + 1e-6)) return AnalyticShape::Sample(ref, u, ss);  // inside
    double dc = std::sqrt(dc2);
    wc = wc / dc;
    Vec3d wcX, wcY;
    CoordinateSystem(wc, &wcX, &wcY);
    double sinThetaMax2 = rW * rW / dc2;
    double cosThetaMax = SafeSqrt(1 - sinThetaMax2);
    // Uniform direction in the cone; 1 - cos computed without cancellation for tiny cones.
    double oneMinusCosMax = sinThetaMax2 / (1 + cosThetaMax);
    double oneMinusCos = double(u.x) * oneMinusCosMax;
    double cosTheta = 1 - oneMinusCos;
    double sinTheta = SafeSqrt(oneMinusCos * (2 - oneMinusCos));
    double phi = double(u.y) * 2 * Pi;
    // The point on the sphere where that direction first meets it.
    double dsq = dc * cosTheta - SafeSqrt(rW * rW - dc2 * sinTheta * sinTheta);
    Vec3d dir = wcX * (sinTheta * std::cos(phi)) + wcY * (sinTheta * std::sin(phi)) + wc * cosTheta;
    Vec3d pW = Vec3d(ref) + dir * dsq;
    Vec3d nW = Normalize(pW - c);
    pW = c + nW * rW;  // re-project onto the surface
    if (flipNormals_) nW = -nW;
    ss->p = Vec3f(pW);
    ss->n = Vec3f(nW);
    ss->pdf = float(1 / (2 * Pi * oneMinusCosMax));
    return std::isfinite(ss->pdf) && ss->pdf > 0;
}

float Sphere::Pdf(const Vec3f &ref, const Vec3f &p, const Vec3f &n) const {
    if (partial_ || !similarity_) return AnalyticShape::Pdf(ref, p, n);
    Vec3d c = renderFromObject_.Point(Vec3d(0, 0, 0));
    double rW = radius_ * Length(renderFromObject_.Vector(Vec3d(1, 0, 0)));
    double dc2 = LengthSquared(c - Vec3d(ref));
    if (dc2 <= rW * rW * (1 + 1e-6)) return AnalyticShape::Pdf(ref, p, n);  // inside
    // Sample's uniform cone: the density is the same for every direction inside it.
    double sinThetaMax2 = rW * rW / dc2;
    double oneMinusCosMax = sinThetaMax2 / (1 + SafeSqrt(1 - sinThetaMax2));
    return float(1 / (2 * Pi * oneMinusCosMax));
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
    Real tErr =
        Gamma<Real>(8) * ((oo + r * r) / std::max(std::abs(q), std::numeric_limits<Real>::min()) +
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
        // The azimuth (an atan2) only where it can clip; Geometry computes it for uv.
        double phi = 0;
        if (partial_) {
            phi = Azimuth(p.x, p.y);
            if ((zMin_ > -radius_ && p.z < zMin_) || (zMax_ < radius_ && p.z > zMax_) ||
                phi > phiMax_)
                continue;
        }
        hit->t = double(t);
        hit->p = p;
        hit->pError = Abs(p) * double(Gamma<Real>(5));
        hit->phi = phi;
        return true;
    }
    return false;
}

template bool Sphere::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Sphere::IntersectT<double>(Vec3d, Vec3d, double, double, double, ObjectHit *) const;

LocalGeometry Sphere::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double u = (partial_ ? hit.phi : Azimuth(p.x, p.y)) / phiMax_;
    double cosTheta = Clamp(p.z / radius_, -1.0, 1.0);
    double theta = std::acos(cosTheta);
    double v = (theta - thetaZMin_) / (thetaZMax_ - thetaZMin_);
    g.uv = {u, v};
    double zRadius = std::sqrt(p.x * p.x + p.y * p.y);
    // At the poles the azimuth is undefined; any unit (cos, sin) keeps dpdv finite.
    double cosPhi = zRadius > 0 ? p.x / zRadius : 1, sinPhi = zRadius > 0 ? p.y / zRadius : 0;
    double sinTheta = SafeSqrt(1 - cosTheta * cosTheta);
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    g.dpdv = Vec3d(p.z * cosPhi, p.z * sinPhi, -radius_ * sinTheta) * (thetaZMax_ - thetaZMin_);
    // cross(dpdu, dpdv) points along +p; use p itself, which stays defined at the poles.
    g.n = p;
    return g;
}

// The profile swept about z (tessellation and `prism validate`).
bool Sphere::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Sphere;
    pr->phiMax = phiMax_;
    pr->a = radius_;
    pr->b = thetaZMin_;  // v = 0 at zmin, as the shape's uv.v
    pr->c = thetaZMax_;
    pr->poleV0 = zMin_ <= -radius_;
    pr->poleV1 = zMax_ >= radius_;
    return thetaZMin_ > thetaZMax_;
}

// Shape "sphere" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the
// error points at the offending parameter). Parameters:
//   radius       float  1        > 0
//   zmin, zmax   float  -radius, radius  the cut-off heights
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Sphere>(const ShapeParams &params,
                                                   const Transform &renderFromObject,
                                                   bool reverseOrientation) {
    float radius = params.PositiveFloat("radius", 1.f);
    return std::make_unique<Sphere>(renderFromObject, reverseOrientation, radius,
                                    params.FiniteFloat("zmin", -radius),
                                    params.FiniteFloat("zmax", radius), params.PhiMax());
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Sphere>(const Transform &renderFromObject) {
    return std::make_unique<Sphere>(renderFromObject, false, 1, -1, 1, 360);
}

PRISM_USER_GEOMETRY(Sphere)

}  // namespace prism
