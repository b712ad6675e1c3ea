// Helpers shared by the quadric root routines.
#pragma once

#include <cmath>
#include <utility>

#include "core/vecmath.h"

namespace prism {

// Roots of a t^2 + b t + c = 0 from a discriminant computed by the caller (which may use a
// cancellation-free form), with the stable q / (c/q) pairing. Returns false if there is no
// real root. t0 <= t1 on success.
template <typename Real>
inline bool SolveQuadratic(Real a, Real b, Real c, Real discrim, Real *t0, Real *t1, Real *q) {
    if (discrim < 0 || a == 0) return false;
    Real rootDiscrim = std::sqrt(discrim);
    *q = (b < 0) ? Real(-0.5) * (b - rootDiscrim) : Real(-0.5) * (b + rootDiscrim);
    if (*q == 0) {
        // b == 0 and discrim == 0: the double root at 0.
        *t0 = *t1 = 0;
        return true;
    }
    *t0 = *q / a;
    *t1 = c / *q;
    if (*t0 > *t1) std::swap(*t0, *t1);
    return true;
}

// Azimuth in [0, 2pi).
inline double Azimuth(double x, double y) {
    double phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * Pi : phi;
}

}  // namespace prism
