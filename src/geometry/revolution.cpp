#include "geometry/revolution.h"

#include <cmath>

namespace prism {

using Kind = RevolutionProfile::Kind;

// ---------------------------------------------------------------------------------------------
// Profile geometry.

Vec2d RevolutionProfile::Point(double v) const {
    switch (kind) {
        case Kind::Sphere: {
            if ((v <= 0 && poleV0) || (v >= 1 && poleV1)) return {0, v <= 0 ? -a : a};
            double th = Lerp(v, b, c);
            return {a * std::sin(th), a * std::cos(th)};
        }
        case Kind::Cylinder:
            return {a, Lerp(v, b, c)};
        case Kind::Disk:
            return {v >= 1 && poleV1 ? 0.0 : Lerp(v, a, b), c};
        case Kind::Cone:
            return {v >= 1 ? 0.0 : a * (1 - v), b * v};
        case Kind::Paraboloid: {
            double rho = v <= 0 && poleV0 ? 0.0 : Lerp(v, b, c);
            return {rho, a * rho * rho};
        }
        case Kind::Hyperboloid: {
            double z = Lerp(v, p1.z, p2.z);
            return {std::sqrt((1 + b * z * z) / a), z};
        }
        case Kind::Torus: {
            double th = 2 * Pi * v;
            return {a + b * std::cos(th), b * std::sin(th)};
        }
    }
    return {0, 0};
}

Vec2d RevolutionProfile::Tangent(double v) const {
    switch (kind) {
        case Kind::Sphere: {
            double th = Lerp(v, b, c);
            return Vec2d(a * std::cos(th), -a * std::sin(th)) * (c - b);
        }
        case Kind::Cylinder:
            return {0, c - b};
        case Kind::Disk:
            return {b - a, 0};
        case Kind::Cone:
            return {-a, b};
        case Kind::Paraboloid: {
            double rho = Lerp(v, b, c);
            return Vec2d(1, 2 * a * rho) * (c - b);
        }
        case Kind::Hyperboloid: {
            double dz = p2.z - p1.z, z = Lerp(v, p1.z, p2.z);
            double rho = std::sqrt((1 + b * z * z) / a);
            return {b * z * dz / (a * rho), dz};
        }
        case Kind::Torus: {
            double th = 2 * Pi * v;
            return Vec2d(-b * std::sin(th), b * std::cos(th)) * (2 * Pi);
        }
    }
    return {0, 0};
}

double RevolutionProfile::Alpha(double v) const {
    if (kind != Kind::Hyperboloid) return 0;
    Vec3d pr = p1 * (1 - v) + p2 * v;
    return std::atan2(pr.y, pr.x);
}

Vec3d RevolutionProfile::Surface(double phi, double v) const {
    Vec2d q = Point(v);
    double ang = phi + Alpha(v);
    // Exactly on the axis at poles; exactly at the rim for cos/sin's rounding otherwise.
    if (q.x == 0) return {0, 0, q.y};
    return {q.x * std::cos(ang), q.x * std::sin(ang), q.y};
}

double RevolutionProfile::Turning() const {
    if (kind == Kind::Torus) return 2 * Pi;
    if (kind == Kind::Sphere) return std::abs(c - b);
    const int steps = 256;
    double total = 0;
    Vec2d prev = Tangent(0);
    for (int i = 1; i <= steps; ++i) {
        Vec2d t = Tangent(double(i) / steps);
        double cr = prev.x * t.y - prev.y * t.x, dt = prev.x * t.x + prev.y * t.y;
        total += std::abs(std::atan2(cr, dt));
        prev = t;
    }
    if (kind == Kind::Hyperboloid) {
        // The rulings twist as well: sample the twist like a bend so quads stay near-planar.
        double da = std::remainder(Alpha(1) - Alpha(0), 2 * Pi);
        total += std::abs(da);
    }
    return total;
}

}  // namespace prism
