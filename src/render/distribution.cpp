#include "render/distribution.h"

#include <algorithm>

namespace prism {

Distribution1D::Distribution1D(std::vector<double> f) : func_(std::move(f)) {
    size_t n = func_.size();
    cdf_.assign(n + 1, 0);
    for (size_t i = 1; i <= n; ++i) cdf_[i] = cdf_[i - 1] + std::max(0.0, func_[i - 1]) / double(n);
    integral_ = cdf_[n];
    if (integral_ == 0) {
        for (size_t i = 1; i <= n; ++i) cdf_[i] = double(i) / double(n);
    } else {
        for (size_t i = 1; i <= n; ++i) cdf_[i] /= integral_;
    }
}

static int FindInterval(const std::vector<double> &cdf, double u) {
    // Largest index i with cdf[i] <= u, clamped to [0, n-1].
    auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    int i = int(it - cdf.begin()) - 1;
    return Clamp(i, 0, int(cdf.size()) - 2);
}

double Distribution1D::SampleContinuous(double u, double *pdf, int *offset) const {
    int i = FindInterval(cdf_, u);
    if (offset) *offset = i;
    double du = u - cdf_[size_t(i)];
    double width = cdf_[size_t(i) + 1] - cdf_[size_t(i)];
    if (width > 0) du /= width;
    if (pdf) *pdf = integral_ > 0 ? func_[size_t(i)] / integral_ : 1;
    return (i + du) / Count();
}

int Distribution1D::SampleDiscrete(double u, double *prob) const {
    int i = FindInterval(cdf_, u);
    if (prob) *prob = cdf_[size_t(i) + 1] - cdf_[size_t(i)];
    return i;
}

Distribution2D::Distribution2D(const std::vector<double> &f, int nu, int nv) {
    std::vector<double> marginal;
    for (int v = 0; v < nv; ++v) {
        conditional_.emplace_back(
            std::vector<double>(f.begin() + size_t(v) * nu, f.begin() + size_t(v + 1) * nu));
        marginal.push_back(conditional_.back().Integral());
    }
    marginal_ = Distribution1D(marginal);
}

Vec2d Distribution2D::SampleContinuous(Vec2d u, double *pdf) const {
    double pdfs[2];
    int v;
    double d1 = marginal_.SampleContinuous(u.y, &pdfs[1], &v);
    double d0 = conditional_[size_t(v)].SampleContinuous(u.x, &pdfs[0]);
    *pdf = pdfs[0] * pdfs[1];
    return {d0, d1};
}

double Distribution2D::Pdf(Vec2d p) const {
    int nu = conditional_[0].Count(), nv = marginal_.Count();
    int iu = Clamp(int(p.x * nu), 0, nu - 1), iv = Clamp(int(p.y * nv), 0, nv - 1);
    if (marginal_.Integral() == 0) return 0;
    return conditional_[size_t(iv)].Func(iu) / marginal_.Integral();
}

}  // namespace prism
