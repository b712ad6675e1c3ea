#include "core/equal_area.h"

#include <algorithm>
#include <cmath>

namespace prism {

// With u = 2x - 1, v = 2y - 1 in [-1, 1]², the distance r = |u| + |v| from the centre (upper
// hemisphere; 2 - |u| - |v| below it) gives z = ±(1 - r²), and the position along the diamond's
// edge gives φ linearly: φ = (|v| - |u|) / r + 1) π/4 within the octant. Then x, y =
// (cos φ, sin φ) r sqrt(2 - r²), which keeps x² + y² + z² = 1.
Vec3d EqualAreaSquareToSphere(Vec2d p) {
    const double u = 2 * p.x - 1, v = 2 * p.y - 1;
    const double au = std::abs(u), av = std::abs(v);
    const double signedDistance = 1 - (au + av);
    const double r = 1 - std::abs(signedDistance);
    const double phi = (r == 0 ? 1 : (av - au) / r + 1) * (Pi / 4);
    const double z = std::copysign(1 - r * r, signedDistance);
    const double s = r * std::sqrt(std::max(0.0, 2 - r * r));
    return {std::copysign(std::cos(phi), u) * s, std::copysign(std::sin(phi), v) * s, z};
}

// The inverse: r = sqrt(1 - |z|); the angle in the octant, as a fraction of π/2, splits r
// into |v| (that fraction of r) and |u| (the rest); below the equator the point is reflected
// across the diamond's edge, (|u|, |v|) → (1 - |v|, 1 - |u|).
Vec2d EqualAreaSphereToSquare(const Vec3d &w) {
    const double ax = std::abs(w.x), ay = std::abs(w.y), az = std::abs(w.z);
    const double r = std::sqrt(std::max(0.0, 1 - az));
    const double a = std::max(ax, ay), b = std::min(ax, ay);
    double phi = a == 0 ? 0 : std::atan(b / a) * (2 / Pi);  // in [0, 1/2]
    if (ax < ay) phi = 1 - phi;
    double v = phi * r, u = r - v;
    if (w.z < 0) {
        const double t = u;
        u = 1 - v;
        v = 1 - t;
    }
    u = std::copysign(u, w.x);
    v = std::copysign(v, w.y);
    return {(u + 1) / 2, (v + 1) / 2};
}

}  // namespace prism
