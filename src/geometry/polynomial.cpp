#include "geometry/polynomial.h"

#include <cmath>
#include <limits>

namespace prism {

double EvalPolynomial(const double *coef, int degree, double x) {
    double v = coef[degree];
    for (int i = degree - 1; i >= 0; --i) v = std::fma(v, x, coef[i]);
    return v;
}

namespace {

// Value and first derivative together (Horner on both).
void EvalWithDerivative(const double *coef, int degree, double x, double *f, double *df) {
    double v = coef[degree], dv = 0;
    for (int i = degree - 1; i >= 0; --i) {
        dv = std::fma(dv, x, v);
        v = std::fma(v, x, coef[i]);
    }
    *f = v;
    *df = dv;
}

// The root of a polynomial that is monotone on [a, b] with fa, fb of opposite signs
// (Numerical Recipes' rtsafe pattern): a Newton step is taken when it lands inside the
// bracket and at least halves the previous step; otherwise the bracket is bisected. The
// bracket shrinks every iteration, so this always terminates.
double SolveBracketed(const double *coef, int degree, double a, double b, double fa) {
    const double eps = std::numeric_limits<double>::epsilon();
    double fb = EvalPolynomial(coef, degree, b);
    // Start from the secant point: good for nearly linear pieces.
    double x = a - fa * (b - a) / (fb - fa);
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    double dx = b - a, dxOld = dx;
    double f, df;
    EvalWithDerivative(coef, degree, x, &f, &df);
    for (int iter = 0; iter < 200; ++iter) {
        if (f == 0) return x;
        if ((f < 0) == (fa < 0)) {
            a = x;
            fa = f;
        } else {
            b = x;
        }
        double step = f / df;
        // Converged: the Newton correction is below an ulp or two (it may even round to x,
        // which must not be mistaken for a step out of the bracket).
        if (std::abs(step) <= 2 * eps * std::abs(x)) return x - step;
        double xn = x - step;
        if (!(xn > a && xn < b) || std::abs(2 * f) > std::abs(dxOld * df)) {
            dxOld = dx;
            dx = 0.5 * (b - a);
            xn = a + dx;
        } else {
            dxOld = dx;
            dx = xn - x;
        }
        if (std::abs(xn - x) <= 2 * eps * std::abs(x) ||
            b - a <= 2 * eps * std::max(std::abs(a), std::abs(b)) ||
            b - a <= std::numeric_limits<double>::denorm_min())
            return xn;
        x = xn;
        EvalWithDerivative(coef, degree, x, &f, &df);
    }
    return x;
}

}  // namespace

int PolynomialRoots(const double *coef, int degree, double lo, double hi, double *roots) {
    // Leading zero coefficients lower the degree (e.g. a ray parallel to some direction).
    while (degree > 0 && coef[degree] == 0) --degree;
    if (degree <= 0 || !(lo <= hi)) return 0;
    if (degree == 1) {
        double r = -coef[0] / coef[1];
        if (r >= lo && r <= hi) {
            roots[0] = r;
            return 1;
        }
        return 0;
    }
    // Critical points split [lo, hi] into pieces where the polynomial is monotone.
    double deriv[MaxPolynomialDegree];
    for (int i = 0; i < degree; ++i) deriv[i] = (i + 1) * coef[i + 1];
    double breaks[MaxPolynomialDegree + 2];
    breaks[0] = lo;
    int nCrit = PolynomialRoots(deriv, degree - 1, lo, hi, breaks + 1);
    int nBreaks = nCrit + 2;
    breaks[nBreaks - 1] = hi;

    int n = 0;
    double fa = EvalPolynomial(coef, degree, lo);
    for (int i = 0; i + 1 < nBreaks; ++i) {
        double a = breaks[i], b = breaks[i + 1];
        double fb = EvalPolynomial(coef, degree, b);
        if (fa == 0) {
            if (n == 0 || roots[n - 1] != a) roots[n++] = a;
        } else if (fb != 0 && ((fa < 0) != (fb < 0)) && b > a) {
            roots[n++] = SolveBracketed(coef, degree, a, b, fa);
        }
        fa = fb;
        if (n == degree) return n;
    }
    if (fa == 0 && (n == 0 || roots[n - 1] != hi) && n < degree) roots[n++] = hi;
    return n;
}

}  // namespace prism
