// Real roots of a polynomial inside an interval, by recursive derivative bracketing
// (after Yuksel, "High-Performance Polynomial Root Finding for Graphics", HPG 2022): the
// derivative's roots split the interval into monotone pieces, each solved by safeguarded
// Newton/bisection. Used by the torus quartic; no closed-form (Ferrari) step anywhere.
#pragma once

namespace prism {

inline constexpr int MaxPolynomialDegree = 8;

// coef[i] multiplies x^i. Evaluation by Horner's rule.
double EvalPolynomial(const double *coef, int degree, double x);

// Writes the real roots in [lo, hi] to roots in ascending order and returns their number
// (at most degree). A root of even multiplicity is found only if the computed polynomial
// touches or crosses zero there; roots are never invented from a sign-preserving minimum.
// degree <= MaxPolynomialDegree.
int PolynomialRoots(const double *coef, int degree, double lo, double hi, double *roots);

}  // namespace prism
