#include "support/bsdf_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace prism::test {

namespace {

void Put(std::string &out, uint32_t w) {
    for (int i = 0; i < 4; ++i) out.push_back(char((w >> (8 * i)) & 0xff));
}
void PutInt(std::string &out, int32_t v) { Put(out, uint32_t(v)); }
void PutFloat(std::string &out, float f) {
    uint32_t w;
    std::memcpy(&w, &f, 4);
    Put(out, w);
}

}  // namespace

std::string FourierBsdfBytes(const std::vector<float> &mu, int channels, int order, float eta,
                             const std::function<std::vector<float>(float, float)> &coeffs) {
    const size_t n = mu.size();
    std::vector<float> data, avg(n * n, 0.f);
    std::vector<int32_t> offsetLength;
    for (size_t o = 0; o < n; ++o) {
        for (size_t i = 0; i < n; ++i) {
            std::vector<float> a = coeffs(mu[i], mu[o]);
            int m = order;  // trim orders that are zero in every channel
            while (m > 0) {
                bool zero = true;
                for (int c = 0; c < channels; ++c) zero = zero && a[size_t(c * order + m - 1)] == 0;
                if (!zero) break;
                --m;
            }
            offsetLength.push_back(int32_t(data.size()));
            offsetLength.push_back(m);
            for (int c = 0; c < channels; ++c)
                for (int k = 0; k < m; ++k) data.push_back(a[size_t(c * order + k)]);
            avg[o * n + i] = m > 0 ? a[0] : 0.f;
        }
    }
    // Each row's CDF: the integral of the Catmull-Rom spline through its a_0 values.
    std::vector<float> cdf(n * n, 0.f);
    for (size_t o = 0; o < n; ++o) {
        const float *f = &avg[o * n];
        double sum = 0;
        for (size_t i = 0; i + 1 < n; ++i) {
            const double w = mu[i + 1] - mu[i], f0 = f[i], f1 = f[i + 1];
            const double d0 = i > 0 ? w * (f1 - f[i - 1]) / (mu[i + 1] - mu[i - 1]) : f1 - f0;
            const double d1 = i + 2 < n ? w * (f[i + 2] - f0) / (mu[i + 2] - mu[i]) : f1 - f0;
            sum += w * ((f0 + f1) / 2 + (d0 - d1) / 12);
            cdf[o * n + i + 1] = float(sum);
        }
    }
    std::string out("SCATFUN\x01", 8);
    PutInt(out, 1);  // flags: a plain BSDF
    PutInt(out, int32_t(n));
    PutInt(out, int32_t(data.size()));
    PutInt(out, order);
    PutInt(out, channels);
    PutInt(out, 1);  // bases
    for (int i = 0; i < 3; ++i) PutInt(out, 0);
    PutFloat(out, eta);
    for (int i = 0; i < 4; ++i) PutInt(out, 0);
    for (float m : mu) PutFloat(out, m);
    for (float c : cdf) PutFloat(out, c);
    for (int32_t v : offsetLength) PutInt(out, v);
    for (float d : data) PutFloat(out, d);
    return out;
}

std::string LambertianFourierBsdf(float rho, int n) {
    std::vector<float> mu;
    for (int i = 0; i < n; ++i) mu.push_back(-1 + 2 * float(i) / float(n - 1));
    return FourierBsdfBytes(mu, 1, 1, 1.f, [rho](float muI, float muO) {
        return std::vector<float>{muI * muO < 0 ? rho * std::abs(muI) / float(M_PI) : 0.f};
    });
}

}  // namespace prism::test
