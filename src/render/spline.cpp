#include "render/spline.h"

#include <algorithm>
#include <limits>

namespace prism {

namespace {

// Segment i from the values at nodes i - 1 .. i + 2 (those outside the table unread).
SplineSegment SegmentOf(const float *x, int n, int i, double fm1, double f0, double f1, double f2) {
    SplineSegment s;
    s.f0 = f0;
    s.f1 = f1;
    s.width = double(x[i + 1]) - x[i];
    s.d0 = i > 0 ? s.width * (f1 - fm1) / (double(x[i + 1]) - x[i - 1]) : f1 - f0;
    s.d1 = i + 2 < n ? s.width * (f2 - f0) / (double(x[i + 2]) - x[i]) : f1 - f0;
    return s;
}

}  // namespace

SplineSegment SplineSegmentAt(const float *x, int n, const float *f, int i) {
    return SegmentOf(x, n, i, i > 0 ? f[i - 1] : 0.0, f[i], f[i + 1], i + 2 < n ? f[i + 2] : 0.0);
}

bool CatmullRomWeights(const float *x, int n, float v, int *offset, float weights[4]) {
    if (n < 2 || !(v >= x[0] && v <= x[n - 1])) return false;
    const int i = std::clamp(int(std::upper_bound(x, x + n, v) - x) - 1, 0, n - 2);
    *offset = i - 1;
    const double x0 = x[i], x1 = x[i + 1], w = x1 - x0;
    const double t = (v - x0) / w, t2 = t * t, t3 = t2 * t;
    double wt[4] = {0, 2 * t3 - 3 * t2 + 1, -2 * t3 + 3 * t2, 0};
    const double h10 = t3 - 2 * t2 + t, h11 = t3 - t2;
    if (i > 0) {
        const double c = h10 * w / (x1 - x[i - 1]);
        wt[2] += c;
        wt[0] -= c;
    } else {
        wt[2] += h10;
        wt[1] -= h10;
    }
    if (i + 2 < n) {
        const double c = h11 * w / (x[i + 2] - x0);
        wt[3] += c;
        wt[1] -= c;
    } else {
        wt[2] += h11;
        wt[1] -= h11;
    }
    for (int j = 0; j < 4; ++j) weights[j] = float(wt[j]);
    return true;
}

double IntegrateCatmullRom(const float *x, int n, const float *f, float *cdf) {
    double sum = 0;
    cdf[0] = 0;
    for (int i = 0; i + 1 < n; ++i) {
        const SplineSegment s = SplineSegmentAt(x, n, f, i);
        sum += s.width * s.Integral(1);
        cdf[i + 1] = float(sum);
    }
    return sum;
}

float InvertCatmullRom(const float *x, int n, const float *f, float u) {
    if (!(u > f[0])) return x[0];
    if (!(u < f[n - 1])) return x[n - 1];
    const int i = std::clamp(int(std::upper_bound(f, f + n, u) - f) - 1, 0, n - 2);
    const SplineSegment s = SplineSegmentAt(x, n, f, i);
    const double guess = s.f1 != s.f0 ? (u - s.f0) / (s.f1 - s.f0) : 0.5;
    // The spline of increasing values may overshoot within a segment; the bracket keeps t in
    // [0, 1] and the derivative's sign does not matter to the bisection fallback.
    const double t =
        InvertIncreasing([&](double t) { return s.Value(t); },
                         [&](double t) {
                             const double t2 = t * t;
                             return (6 * t2 - 6 * t) * s.f0 + (-6 * t2 + 6 * t) * s.f1 +
                                    (3 * t2 - 4 * t + 1) * s.d0 + (3 * t2 - 2 * t) * s.d1;
                         },
                         u, 0, 1, guess);
    return float(x[i] + t * s.width);
}

float SampleCatmullRom2D(const float *nodes1, int n1, const float *nodes2, int n2,
                         const float *values, const float *cdf, float alpha, float u, float *value,
                         float *pdf) {
    int offset;
    float w[4];
    if (!CatmullRomWeights(nodes1, n1, alpha, &offset, w))
        return std::numeric_limits<float>::quiet_NaN();
    // The interpolated row's entry j of a table.
    auto row = [&](const float *table, int j) {
        double sum = 0;
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0) sum += double(w[k]) * table[(offset + k) * n2 + j];
        return sum;
    };
    const double total = row(cdf, n2 - 1);
    if (!(total > 0)) return std::numeric_limits<float>::quiet_NaN();
    const double target = double(u) * total;
    // The segment whose running integral brackets the target.
    int lo = 0, hi = n2 - 1;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        (row(cdf, mid) <= target ? lo : hi) = mid;
    }
    const int i = lo;
    auto at = [&](int j) { return j >= 0 && j < n2 ? row(values, j) : 0.0; };
    const SplineSegment s = SegmentOf(nodes2, n2, i, at(i - 1), at(i), at(i + 1), at(i + 2));
    const double r = (target - row(cdf, i)) / s.width;
    const double full = s.Integral(1);
    const double t = InvertIncreasing([&](double t) { return s.Integral(t); },
                                      [&](double t) { return s.Value(t); }, r, 0, 1,
                                      full > 0 ? std::clamp(r / full, 0.0, 1.0) : 0.5);
    const double fx = s.Value(t);
    if (value) *value = float(fx);
    if (pdf) *pdf = float(std::max(0.0, fx) / total);
    return float(nodes2[i] + t * s.width);
}

}  // namespace prism
