// Directions by cosine and azimuth, and the midpoint rule over the sphere of directions, for
// the tests that integrate a BSDF or a density by quadrature.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vecmath.h"

namespace prism::test {

// The unit direction at cos θ = cosTheta, azimuth phi, about +z.
inline Vec3f DirectionAt(float cosTheta, float phi) {
    const float s = std::sqrt(std::max(0.f, 1 - cosTheta * cosTheta));
    return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

// ∫ g(ω) dω over the sphere: the midpoint rule on n × n cells in (cos θ, φ). g returns a value
// that adds and scales (float, double, RGB).
template <typename G>
auto IntegrateSphere(G g, int n) {
    decltype(g(Vec3f(0, 0, 1))) sum{};
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            sum += g(DirectionAt(-1 + 2 * (i + 0.5f) / float(n), float(2 * Pi * (j + 0.5) / n)));
    return sum * float(4 * Pi / (double(n) * n));
}

}  // namespace prism::test
