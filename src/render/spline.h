// Catmull–Rom splines through tabulated values: the tables of the fourier BSDF (render/
// fourier_bsdf.h) and of the subsurface profile (render/bssrdf.h). Nodes x_0 < ... < x_n-1
// carry values f_i; on [x_i, x_i+1] the spline is the cubic Hermite segment whose end
// derivatives are the central differences (one-sided at the table's ends).
#pragma once

#include <cmath>
#include <vector>

namespace prism {

// The segment [x_i, x_i+1] in t = (x - x_i) / width: end values and end derivatives in t.
struct SplineSegment {
    double f0, f1, d0, d1, width;
    double Value(double t) const {
        const double t2 = t * t, t3 = t2 * t;
        return (2 * t3 - 3 * t2 + 1) * f0 + (-2 * t3 + 3 * t2) * f1 + (t3 - 2 * t2 + t) * d0 +
               (t3 - t2) * d1;
    }
    // ∫ from 0 to t of Value, in units of t (× width for units of x).
    double Integral(double t) const {
        const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
        return f0 * (t4 / 2 - t3 + t) + f1 * (-t4 / 2 + t3) + d0 * (t4 / 4 - 2 * t3 / 3 + t2 / 2) +
               d1 * (t4 / 4 - t3 / 3);
    }
};

// Segment i (0 <= i < n - 1) of the spline through the n nodes x and values f.
SplineSegment SplineSegmentAt(const float *x, int n, const float *f, int i);
inline SplineSegment SplineSegmentAt(const std::vector<float> &x, const float *f, int i) {
    return SplineSegmentAt(x.data(), int(x.size()), f, i);
}

// Solves g(t) = target for t in [lo, hi], g increasing with derivative dg, from the guess t:
// Newton's method, bisecting when a step leaves the bracket.
template <typename G, typename DG>
double InvertIncreasing(G g, DG dg, double target, double lo, double hi, double t) {
    for (int it = 0; it < 60; ++it) {
        const double r = g(t) - target;
        if (std::abs(r) < 1e-9 * (1 + std::abs(target)) || hi - lo < 1e-12) break;
        if (r < 0)
            lo = t;
        else
            hi = t;
        const double d = dg(t);
        double next = d > 0 ? t - r / d : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        t = next;
    }
    return t;
}

// Spline weights of the four nodes around v: the spline's value at v is Σ weights[j]
// f[offset + j] (nodes outside the table get weight 0). False when v is outside [x_0, x_n-1].
bool CatmullRomWeights(const float *x, int n, float v, int *offset, float weights[4]);
inline bool CatmullRomWeights(const std::vector<float> &x, float v, int *offset, float weights[4]) {
    return CatmullRomWeights(x.data(), int(x.size()), v, offset, weights);
}

// The spline's integral over [x_0, x_n-1]; cdf[i] (n entries) gets the integral up to x_i.
double IntegrateCatmullRom(const float *x, int n, const float *f, float *cdf);

// The x at which the spline through increasing values f reaches u: x_0 below f_0, x_n-1 above
// f_n-1.
float InvertCatmullRom(const float *x, int n, const float *f, float u);

// A table of n1 × n2 values (row-major: values[i * n2 + j] at nodes1[i], nodes2[j]) with each
// row's running integral cdf (IntegrateCatmullRom's): the row at alpha is interpolated across
// rows by CatmullRomWeights, and x in nodes2's range is drawn in proportion to it by inverting
// its integral at u·total. Returns x (NaN when alpha is outside nodes1); *value and *pdf (when
// not null) get the interpolated row's value there and value / total.
float SampleCatmullRom2D(const float *nodes1, int n1, const float *nodes2, int n2,
                         const float *values, const float *cdf, float alpha, float u,
                         float *value = nullptr, float *pdf = nullptr);

}  // namespace prism
