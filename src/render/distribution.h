// Piecewise-constant 1-D and 2-D distributions for importance sampling (environment maps,
// triangle areas).
#pragma once

#include <vector>

#include "core/vecmath.h"

namespace prism {

class Distribution1D {
  public:
    Distribution1D() = default;
    explicit Distribution1D(std::vector<double> f);
    // Continuous sample in [0,1) with density pdf (relative to the unit interval).
    double SampleContinuous(double u, double *pdf, int *offset = nullptr) const;
    // Discrete index with probability f[i] / sum.
    int SampleDiscrete(double u, double *prob = nullptr) const;
    int Count() const { return int(func_.size()); }
    double Integral() const { return integral_; }
    double Func(int i) const { return func_[size_t(i)]; }
    double Cdf(int i) const { return cdf_[size_t(i)]; }

  private:
    std::vector<double> func_, cdf_;
    double integral_ = 0;
};

class Distribution2D {
  public:
    Distribution2D() = default;
    // f is nu x nv, row-major by v (f[v * nu + u]).
    Distribution2D(const std::vector<double> &f, int nu, int nv);
    Vec2d SampleContinuous(Vec2d u, double *pdf) const;
    double Pdf(Vec2d p) const;

  private:
    std::vector<Distribution1D> conditional_;
    Distribution1D marginal_;
};

}  // namespace prism
