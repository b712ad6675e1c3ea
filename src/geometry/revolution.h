// Every analytic shape is a profile curve (rho(v), z(v)) swept about z: each shape describes
// itself so (AnalyticShape::Revolution, in the shape's own .cpp) for tessellation and
// `prism validate` (tools/validate/tessellate.h).
#pragma once

#include "core/vecmath.h"

namespace prism {

// P(phi, v) = (rho(v) cos(phi + alpha(v)), rho(v) sin(phi + alpha(v)), z(v)) for phi in
// [0, phiMax], v in [0, 1]. alpha is nonzero only for the hyperboloid, whose azimuth pbrt
// measures from the rotated profile point. v is a geometric parameter chosen for even
// sampling (not always the shape's uv.v).
struct RevolutionProfile {
    enum class Kind { Sphere, Cylinder, Disk, Cone, Paraboloid, Hyperboloid, Torus };
    Kind kind = Kind::Sphere;
    double phiMax = 2 * Pi;
    // Kind-specific parameters:
    //   Sphere: a = radius, b = theta at v=0, c = theta at v=1 (theta from +z)
    //   Cylinder: a = radius, b = zmin, c = zmax
    //   Disk: a = outer radius, b = inner radius, c = height
    //   Cone: a = radius, b = height
    //   Paraboloid: a = k (z = k rho^2), b = rho at v=0, c = rho at v=1
    //   Hyperboloid: a = a_h, b = c_h (a rho^2 - c z^2 = 1), p1, p2 = the profile segment
    //   Torus: a = R, b = r
    double a = 0, b = 0, c = 0;
    Vec3d p1, p2;
    // Ends of the profile that lie on the axis (one vertex, a triangle fan) and whether the
    // profile is a closed curve (torus: v = 0 and v = 1 are the same ring).
    bool poleV0 = false, poleV1 = false, closedV = false;

    Vec2d Point(double v) const;    // (rho, z)
    Vec2d Tangent(double v) const;  // d(rho, z)/dv
    double Alpha(double v) const;
    Vec3d Surface(double phi, double v) const;
    // Total turning of the profile's tangent over v in [0, 1] (radians): sets the number of
    // rings so both directions get the same angular resolution.
    double Turning() const;
    bool FullCircle() const { return phiMax >= 2 * Pi; }
};

}  // namespace prism
