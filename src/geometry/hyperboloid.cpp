#include "geometry/hyperboloid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/quadric_solve.h"
#include "geometry/revolution.h"
#include "geometry/shape_list.h"
#include "geometry/user_geometry.h"

namespace prism {

namespace {
RotationalQuadric HyperboloidQuadric(double a, double c) {
    RotationalQuadric q;
    q.A = a;
    q.B = -c;
    q.D = -1;
    return q;
}
}  // namespace

Hyperboloid::Hyperboloid(const Transform &renderFromObject, bool reverseOrientation,
                         const Vec3d &p1, const Vec3d &p2, double phiMaxDeg)
    : AnalyticShapeT(renderFromObject, reverseOrientation),
      p1_(p1),
      p2_(p2),
      phiMax_(Radians(std::min(phiMaxDeg, 360.0))) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(p1[i]) || !std::isfinite(p2[i]))
            throw std::invalid_argument("hyperboloid points must be finite");
    if (!(phiMaxDeg > 0)) throw std::invalid_argument("hyperboloid phimax must be positive");
    if (p1_.z == p2_.z) throw std::invalid_argument("hyperboloid p1 and p2 must have different z");
    zMin_ = std::min(p1_.z, p2_.z);
    zMax_ = std::max(p1_.z, p2_.z);
    // pbrt-v3's fit: through p2 and a point pp = p1 + 2k (p2 - p1) farther along the
    // segment's line, for the first k where the 2x2 system is regular. Solved here in closed
    // form; the loop is bounded, and a line that meets the axis (which sweeps a cone, not a
    // hyperboloid, and makes pbrt-v3 loop forever) is rejected.
    if (p2_.z == 0) std::swap(p1_, p2_);
    double xy2 = p2_.x * p2_.x + p2_.y * p2_.y, z2 = p2_.z * p2_.z;
    bool fitted = false;
    for (int k = 1; k <= 64 && !fitted; ++k) {
        Vec3d pp = p1_ + (p2_ - p1_) * double(2 * k);
        double xy1 = pp.x * pp.x + pp.y * pp.y, zp = pp.z * pp.z;
        double det = xy2 * zp - xy1 * z2;
        if (!(std::abs(det) > 1e-12 * (std::abs(xy2 * zp) + std::abs(xy1 * z2)))) continue;
        ah_ = (zp - z2) / det;
        ch_ = (xy1 - xy2) / det;
        fitted = std::isfinite(ah_) && std::isfinite(ch_);
    }
    if (!fitted)
        throw std::invalid_argument("hyperboloid p1, p2 sweep no hyperboloid (degenerate fit)");
    // a_h < 0 is a hyperboloid of two sheets (pbrt-v3 renders those too, e.g. in the
    // all-shapes scene); only a_h == 0 (a degenerate quadric) is rejected.
    if (ah_ == 0) throw std::invalid_argument("hyperboloid p1, p2 sweep a degenerate quadric");
    // Largest radius over [zmin, zmax]: rho^2 = (1 + c z^2) / a peaks at an end, or at z = 0
    // when c < 0 (an ellipsoid-like fit).
    double r2 = std::max(p1_.x * p1_.x + p1_.y * p1_.y, xy2);
    for (double z : {zMin_, zMax_, Clamp(0.0, zMin_, zMax_)}) {
        double r = (1 + ch_ * z * z) / ah_;  // negative where a two-sheet fit has no surface
        if (std::isfinite(r)) r2 = std::max(r2, r);
    }
    rMax_ = std::sqrt(r2);
}

Bounds3d Hyperboloid::ObjectBounds() const {
    return Bounds3d(Vec3d(-rMax_, -rMax_, zMin_), Vec3d(rMax_, rMax_, zMax_));
}

double Hyperboloid::Implicit(const Vec3d &p) const { return HyperboloidQuadric(ah_, ch_).F(p); }
Vec3d Hyperboloid::ImplicitGradient(const Vec3d &p) const {
    return HyperboloidQuadric(ah_, ch_).Grad(p);
}
Vec3d Hyperboloid::NormalFieldDerivative(const Vec3d &, const Vec3d &dp) const {
    return HyperboloidQuadric(ah_, ch_).GradDerivative(dp);
}

double Hyperboloid::Phi(const Vec3d &p) const {
    double v = (p.z - p1_.z) / (p2_.z - p1_.z);
    Vec3d pr = p1_ * (1 - v) + p2_ * v;
    double phi = std::atan2(pr.x * p.y - p.x * pr.y, p.x * pr.x + p.y * pr.y);
    return phi < 0 ? phi + 2 * Pi : phi;
}

template <typename Real>
bool Hyperboloid::IntersectT(Vec3<Real> o, Vec3<Real> d, Real tMin, Real tMax, Real tSlack,
                             ObjectHit *hit) const {
    auto clip = [this](const Vec3d &p, double *phi) {
        *phi = Phi(p);
        return p.z >= zMin_ && p.z <= zMax_ && *phi <= phiMax_;
    };
    return IntersectRotationalQuadric(HyperboloidQuadric(ah_, ch_), ObjectBounds(), o, d, tMin,
                                      tMax, tSlack, clip, hit);
}

template bool Hyperboloid::IntersectT<float>(Vec3f, Vec3f, float, float, float, ObjectHit *) const;
template bool Hyperboloid::IntersectT<double>(Vec3d, Vec3d, double, double, double,
                                              ObjectHit *) const;

LocalGeometry Hyperboloid::Geometry(const ObjectHit &hit) const {
    const Vec3d &p = hit.p;
    LocalGeometry g;
    double v = (p.z - p1_.z) / (p2_.z - p1_.z);
    g.uv = {hit.phi / phiMax_, v};
    double cosPhi = std::cos(hit.phi), sinPhi = std::sin(hit.phi);
    g.dpdu = Vec3d(-phiMax_ * p.y, phiMax_ * p.x, 0);
    Vec3d e = p2_ - p1_;
    g.dpdv = Vec3d(e.x * cosPhi - e.y * sinPhi, e.x * sinPhi + e.y * cosPhi, e.z);
    // The gradient is the well-conditioned normal; pbrt orients by cross(dpdu, dpdv), whose
    // sign depends on the order of p1 and p2.
    Vec3d grad = HyperboloidQuadric(ah_, ch_).Grad(p);
    g.n = Dot(grad, Cross(g.dpdu, g.dpdv)) < 0 ? -grad : grad;
    return g;
}

// The profile swept about z (tessellation and `prism validate`).
bool Hyperboloid::Revolution(RevolutionProfile *pr) const {
    *pr = RevolutionProfile{};
    pr->kind = RevolutionProfile::Kind::Hyperboloid;
    pr->phiMax = phiMax_;
    pr->a = ah_;
    pr->b = ch_;
    pr->p1 = p1_;
    pr->p2 = p2_;
    // Only a one-sheet fit (rho^2 > 0 over the whole z range) is a tube that can be swept.
    for (double z : {zMin_, zMax_, Clamp(0.0, zMin_, zMax_)})
        if (!((1 + ch_ * z * z) / ah_ > 0)) return false;
    return true;
}

// Shape "hyperboloid" (shape_list.inc; pbrt-v3's names and defaults, each value checked so the
// error points at the offending parameter). Parameters:
//   p1, p2       point  0 0 0, 1 1 1  the segment swept about z (the defaults, a cone, are
//                                     refused)
//   phimax       float  360   the swept angle, degrees, in (0, 360]
template <>
std::unique_ptr<AnalyticShape> CreateShape<Hyperboloid>(const ShapeParams &params,
                                                        const Transform &renderFromObject,
                                                        bool reverseOrientation) {
    Vec3f p1 = params.Point3("p1", Vec3f(0, 0, 0));
    Vec3f p2 = params.Point3("p2", Vec3f(1, 1, 1));
    float phimax = params.PhiMax();
    // The defaults sweep a cone (the segment's line meets the axis), which pbrt-v3's fit
    // never converges on; the constructor rejects that with a message.
    return params.Construct(params.Has("p2") ? "p2" : "p1", [&] {
        return std::make_unique<Hyperboloid>(renderFromObject, reverseOrientation, Vec3d(p1),
                                             Vec3d(p2), phimax);
    });
}

template <>
std::unique_ptr<AnalyticShape> CanonicalShape<Hyperboloid>(const Transform &renderFromObject) {
    return std::make_unique<Hyperboloid>(renderFromObject, false, Vec3d(1, -1, -1), Vec3d(1, 1, 1),
                                         360);
}

PRISM_USER_GEOMETRY(Hyperboloid)

}  // namespace prism
