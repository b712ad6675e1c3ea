// Helpers shared by the analytic-shape tests: random directions and transforms, a random
// instance of each shape kind, and the residual/normal checks every shape must pass.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "core/rng.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/hyperboloid.h"
#include "geometry/paraboloid.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"

namespace prism {
namespace testing_util {

inline Vec3d RandomDirD(PCG32 &rng) {
    double z = 1 - 2 * rng.UniformDouble(), phi = 2 * Pi * rng.UniformDouble();
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

inline Vec3f RandomDirF(PCG32 &rng) { return Vec3f(RandomDirD(rng)); }

// Uniform scale 1e-2..1e2, random rotation, translation within +-50.
inline Transform RandomTransform(PCG32 &rng) {
    double s = std::pow(10.0, 4 * rng.UniformDouble() - 2);
    Vec3d t(100 * (rng.UniformDouble() - 0.5), 100 * (rng.UniformDouble() - 0.5),
            100 * (rng.UniformDouble() - 0.5));
    return Translate(t) * Rotate(360 * rng.UniformDouble(), RandomDirD(rng)) * Scale(s, s, s);
}

enum class Kind { Sphere, Cylinder, Disk, Cone, Paraboloid, Hyperboloid, Torus };
inline constexpr Kind AllKinds[] = {Kind::Sphere,     Kind::Cylinder,    Kind::Disk, Kind::Cone,
                                    Kind::Paraboloid, Kind::Hyperboloid, Kind::Torus};

inline const char *KindName(Kind k) {
    static const char *names[] = {"sphere",     "cylinder",    "disk", "cone",
                                  "paraboloid", "hyperboloid", "torus"};
    return names[int(k)];
}

// The convex-solid shapes: any piece of their surface bounds a convex set, so a ray leaving
// it outward can never hit it again (partial or not).
inline bool ConvexSolid(Kind k) {
    return k == Kind::Sphere || k == Kind::Cylinder || k == Kind::Cone || k == Kind::Paraboloid;
}

// A full (partial = false) or randomly clipped instance of kind k with unit-ish size.
inline std::unique_ptr<AnalyticShape> MakeShape(Kind k, const Transform &xf, bool partial,
                                                PCG32 &rng, bool reverse = false) {
    double phimax = partial ? 30 + 320 * rng.UniformDouble() : 360;
    double u = rng.UniformDouble();
    switch (k) {
        case Kind::Sphere:
            return partial ? std::make_unique<Sphere>(xf, reverse, 1, -0.8 + 0.5 * u, 0.9, phimax)
                           : std::make_unique<Sphere>(xf, reverse, 1, -1, 1, 360);
        case Kind::Cylinder:
            return std::make_unique<Cylinder>(xf, reverse, 0.5 + u, -1, 0.5 + u, phimax);
        case Kind::Disk:
            return std::make_unique<Disk>(xf, reverse, u - 0.5, 1, partial ? 0.3 : 0, phimax);
        case Kind::Cone:
            return std::make_unique<Cone>(xf, reverse, 0.5 + u, 0.5 + rng.UniformDouble(), phimax);
        case Kind::Paraboloid:
            return std::make_unique<Paraboloid>(xf, reverse, 0.5 + u, partial ? 0.2 : 0, 1.5,
                                                phimax);
        case Kind::Hyperboloid:
            // A segment whose closest approach to the axis is at z = 0, so it is a ruling of the
            // fitted surface (pbrt's fit is only exact for such segments).
            return std::make_unique<Hyperboloid>(xf, reverse, Vec3d(0.3 + u, -0.8, -1),
                                                 Vec3d(0.3 + u, 0.7, 0.875), phimax);
        case Kind::Torus:
            return std::make_unique<Torus>(xf, reverse, 1, 0.1 + 0.5 * u, phimax);
    }
    return nullptr;
}

// Distance from an object-space point to the implicit surface, first order.
inline double Residual(const AnalyticShape &s, const Vec3d &p) {
    return std::abs(s.Implicit(p)) / Length(s.ImplicitGradient(p));
}

}  // namespace testing_util
}  // namespace prism
