#include "render/fourier_bsdf.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace prism {

namespace {

constexpr double kPi = Pi;

// Little-endian 32-bit words, as the file stores them.
uint32_t Word(const std::string &b, size_t at) {
    return uint32_t(uint8_t(b[at])) | uint32_t(uint8_t(b[at + 1])) << 8 |
           uint32_t(uint8_t(b[at + 2])) << 16 | uint32_t(uint8_t(b[at + 3])) << 24;
}
int32_t Int(const std::string &b, size_t at) { return int32_t(Word(b, at)); }
float Float(const std::string &b, size_t at) {
    const uint32_t w = Word(b, at);
    float f;
    std::memcpy(&f, &w, 4);
    return f;
}

double CosDPhi(const Vec3f &a, const Vec3f &b) {
    const double axy = double(a.x) * a.x + double(a.y) * a.y;
    const double bxy = double(b.x) * b.x + double(b.y) * b.y;
    if (axy == 0 || bxy == 0) return 1;
    return std::clamp((double(a.x) * b.x + double(a.y) * b.y) / std::sqrt(axy * bxy), -1.0, 1.0);
}

}  // namespace

float FourierSeries(const float *a, int m, double cosPhi) {
    double sum = 0, cPrev = cosPhi, c = 1;  // cos((k-1)φ), cos(kφ) at k = 0
    for (int k = 0; k < m; ++k) {
        sum += a[k] * c;
        const double next = 2 * cosPhi * c - cPrev;
        cPrev = c;
        c = next;
    }
    return float(sum);
}

FourierTable FourierTable::Parse(const std::string &b, const std::string &name) {
    auto fail = [&](const std::string &why) {
        throw std::runtime_error("tabulated BSDF " + name + ": " + why);
    };
    static const char kHeader[8] = {'S', 'C', 'A', 'T', 'F', 'U', 'N', '\x01'};
    if (b.size() < 64 || std::memcmp(b.data(), kHeader, 8) != 0)
        fail("not a .bsdf file of version 1 (no \"SCATFUN\\x01\" header)");
    const int32_t flags = Int(b, 8), nMu = Int(b, 12), nCoeffs = Int(b, 16), mMax = Int(b, 20),
                  nChannels = Int(b, 24), nBases = Int(b, 28);
    const float eta = Float(b, 44);
    if (flags != 1) fail("flags " + std::to_string(flags) + " (only 1, a plain BSDF, is read)");
    if (nChannels != 1 && nChannels != 3)
        fail(std::to_string(nChannels) + " channels (1 or 3 are read)");
    if (nBases != 1) fail(std::to_string(nBases) + " bases (textured tables are not read)");
    if (nMu < 2 || nMu > 4096) fail("zenith count " + std::to_string(nMu) + " out of range");
    if (mMax < 1 || mMax > 1 << 16) fail("order " + std::to_string(mMax) + " out of range");
    if (nCoeffs < 0) fail("negative coefficient count");
    if (!(eta > 0) || !std::isfinite(eta)) fail("index of refraction not positive");
    const uint64_t n = uint64_t(nMu), entries = n * n;
    const uint64_t need = 64 + 4 * (n + entries + 2 * entries + uint64_t(nCoeffs));
    if (b.size() < need)
        fail("truncated: " + std::to_string(b.size()) + " bytes where the header needs " +
             std::to_string(need));
    FourierTable t;
    t.mMax_ = mMax;
    t.nChannels_ = nChannels;
    t.eta_ = eta;
    size_t at = 64;
    t.mu_.resize(size_t(n));
    for (float &m : t.mu_) m = Float(b, at), at += 4;
    for (size_t i = 0; i < n; ++i)
        if (!(t.mu_[i] >= -1 && t.mu_[i] <= 1) || (i > 0 && !(t.mu_[i] > t.mu_[i - 1])))
            fail("zenith cosines not increasing within [-1, 1]");
    at += size_t(4 * entries);  // the file's CDF: recomputed below from the coefficients
    t.offset_.resize(size_t(entries));
    t.order_.resize(size_t(entries));
    for (size_t e = 0; e < entries; ++e) {
        t.offset_[e] = Int(b, at), t.order_[e] = Int(b, at + 4), at += 8;
        const int64_t end = int64_t(t.offset_[e]) + int64_t(t.order_[e]) * nChannels;
        if (t.offset_[e] < 0 || t.order_[e] < 0 || t.order_[e] > mMax || end > nCoeffs)
            fail("entry " + std::to_string(e) + " reaches past the coefficients");
    }
    t.coeffs_.resize(size_t(nCoeffs));
    for (float &c : t.coeffs_) {
        c = Float(b, at), at += 4;
        // Far beyond any BSDF's (a glossy peak's f is in the thousands), and small enough
        // that the interpolation's sums stay finite.
        if (!(std::abs(c) <= 1e12f)) fail("a coefficient is not finite or beyond 1e12");
    }
    t.avg_.resize(size_t(entries));
    for (size_t e = 0; e < entries; ++e)
        t.avg_[e] = t.order_[e] > 0 ? t.coeffs_[size_t(t.offset_[e])] : 0.f;
    // Each row's CDF: the integral of its a_0 spline, segment by segment.
    t.cdf_.assign(size_t(entries), 0.f);
    for (size_t o = 0; o < n; ++o) {
        const float *f = &t.avg_[o * n];
        double sum = 0;
        for (int i = 0; i + 1 < nMu; ++i) {
            const SplineSegment s = SplineSegmentAt(t.mu_, f, i);
            sum += s.width * s.Integral(1);
            t.cdf_[o * n + size_t(i + 1)] = float(sum);
        }
    }
    return t;
}

int FourierTable::Coefficients(float muI, float muO, std::vector<float> *ak) const {
    int offI, offO;
    float wI[4], wO[4];
    ak->assign(size_t(mMax_ * nChannels_), 0.f);
    if (!CatmullRomWeights(mu_, muI, &offI, wI) || !CatmullRomWeights(mu_, muO, &offO, wO))
        return 0;
    const int n = NumMu();
    int order = 0;
    for (int bo = 0; bo < 4; ++bo) {
        for (int ai = 0; ai < 4; ++ai) {
            const float w = wI[ai] * wO[bo];
            const int i = offI + ai, o = offO + bo;
            if (w == 0 || i < 0 || o < 0 || i >= n || o >= n) continue;
            const size_t e = size_t(o) * size_t(n) + size_t(i);
            const int m = order_[e];
            order = std::max(order, m);
            const float *a = &coeffs_[size_t(offset_[e])];
            for (int c = 0; c < nChannels_; ++c)
                for (int k = 0; k < m; ++k) (*ak)[size_t(c * mMax_ + k)] += w * a[c * m + k];
        }
    }
    return order;
}

float FourierTable::Total(float muO) const {
    int off;
    float w[4];
    if (!CatmullRomWeights(mu_, muO, &off, w)) return 0;
    const int n = NumMu();
    double total = 0;
    for (int j = 0; j < 4; ++j)
        if (w[j] != 0 && off + j >= 0 && off + j < n)
            total += w[j] * cdf_[size_t(off + j) * size_t(n) + size_t(n - 1)];
    return float(total);
}

float FourierTable::SampleMu(float muO, float u, float *pdf) const {
    *pdf = 0;
    int off;
    float w[4];
    if (!CatmullRomWeights(mu_, muO, &off, w)) return 0;
    const int n = NumMu();
    // The row for μo: the rows around it blended by their weights.
    thread_local std::vector<float> f, cdf;  // reused: SampleMu runs per BSDF sample
    f.assign(size_t(n), 0.f);
    cdf.assign(size_t(n), 0.f);
    for (int j = 0; j < 4; ++j) {
        if (w[j] == 0 || off + j < 0 || off + j >= n) continue;
        const size_t row = size_t(off + j) * size_t(n);
        for (int i = 0; i < n; ++i) {
            f[size_t(i)] += w[j] * avg_[row + size_t(i)];
            cdf[size_t(i)] += w[j] * cdf_[row + size_t(i)];
        }
    }
    const double total = cdf.back();
    if (!(total > 0)) return 0;
    const double target = double(u) * total;
    const int i = std::clamp(
        int(std::upper_bound(cdf.begin(), cdf.end(), float(target)) - cdf.begin()) - 1, 0, n - 2);
    const SplineSegment s = SplineSegmentAt(mu_, f.data(), i);
    const double r = std::max(0.0, (target - cdf[size_t(i)]) / s.width);
    const double t = InvertIncreasing(
        [&](double x) { return s.Integral(x); }, [&](double x) { return s.Value(x); }, r, 0, 1,
        s.f0 + s.f1 > 0 ? std::clamp(r / (0.5 * (s.f0 + s.f1)), 0.0, 1.0) : 0.5);
    *pdf = float(std::max(0.0, s.Value(t)) / total);
    return float(mu_[size_t(i)] + t * s.width);
}

namespace {

// f for the coefficients ak (order m) at cos φ, with the 1/|μi| and radiance η² scales.
RGB Evaluate(const FourierTable &t, const std::vector<float> &ak, int m, double cosPhi, float muI,
             float muO) {
    const float Y = std::max(0.f, FourierSeries(ak.data(), m, cosPhi));
    float scale = muI != 0 ? 1 / std::abs(muI) : 0.f;
    if (muI * muO > 0) {  // transmission: radiance is scaled by the relative index squared
        const float eta = muI > 0 ? 1 / t.Eta() : t.Eta();
        scale *= eta * eta;
    }
    if (t.NumChannels() == 1) return RGB(Y * scale);
    const float R = FourierSeries(ak.data() + t.MaxOrder(), m, cosPhi);
    const float B = FourierSeries(ak.data() + 2 * t.MaxOrder(), m, cosPhi);
    const float G = 1.39829f * Y - 0.100913f * B - 0.297375f * R;
    return (RGB(R, G, B) * scale).Clamped(0.f);
}

}  // namespace

RGB FourierLobe::f(const Vec3f &wo, const Vec3f &wi) const {
    const float muI = -wi.z, muO = wo.z;
    thread_local std::vector<float> ak;  // reused: f and Pdf run per light sample
    const int m = table->Coefficients(muI, muO, &ak);
    if (m == 0) return RGB(0);
    return Evaluate(*table, ak, m, CosDPhi(-wi, wo), muI, muO);
}

float FourierLobe::Pdf(const Vec3f &wo, const Vec3f &wi) const {
    const float muI = -wi.z, muO = wo.z;
    thread_local std::vector<float> ak;  // reused: f and Pdf run per light sample
    const int m = table->Coefficients(muI, muO, &ak);
    const float total = table->Total(muO);
    if (m == 0 || !(total > 0)) return 0;
    return std::max(0.f, FourierSeries(ak.data(), m, CosDPhi(-wi, wo))) / float(2 * kPi * total);
}

bool FourierLobe::Sample(const Vec3f &wo, Vec2f u, Vec3f *wi, float *pdf) const {
    const float muO = wo.z;
    float pdfMu = 0;
    const float muI = table->SampleMu(muO, u.y, &pdfMu);
    if (!(pdfMu > 0)) return false;
    thread_local std::vector<float> ak;  // reused: Sample runs per BSDF sample
    const int m = table->Coefficients(muI, muO, &ak);
    if (m == 0 || !(ak[0] > 0)) return false;
    // φ from the luminance series: its even half [0, π] by inverting its integral
    // a0 φ + Σ a_k sin(kφ) / k, mirrored to (π, 2π) for half of u.
    float v = u.x;
    const bool flip = v < 0.5f;
    v = flip ? 1 - 2 * v : 2 * v - 1;
    const auto series = [&](double phi) {
        return double(FourierSeries(ak.data(), m, std::cos(phi)));
    };
    const auto integral = [&](double phi) {
        double sum = ak[0] * phi;
        for (int k = 1; k < m; ++k) sum += ak[size_t(k)] * std::sin(k * phi) / k;
        return sum;
    };
    double phi =
        InvertIncreasing(integral, series, double(v) * ak[0] * kPi, 0, kPi, double(v) * kPi);
    const double value = series(phi);
    if (!(value > 0)) return false;
    if (flip) phi = 2 * kPi - phi;
    *pdf = float(pdfMu * value / (2 * kPi * ak[0]));
    // wi: zenith cosine −μi, azimuth φ from wo's about the normal (pointing away).
    const double sinI = std::sqrt(std::max(0.0, 1 - double(muI) * muI));
    const double oxy = std::sqrt(double(wo.x) * wo.x + double(wo.y) * wo.y);
    const double ox = oxy > 0 ? wo.x / oxy : 1, oy = oxy > 0 ? wo.y / oxy : 0;
    const double c = std::cos(phi), s = std::sin(phi);
    *wi = Vec3f(float(-sinI * (c * ox - s * oy)), float(-sinI * (s * ox + c * oy)), -muI);
    return *pdf > 0 && std::isfinite(*pdf);
}

RGB FourierLobe::Albedo(const Vec3f &wo) const {
    const FourierTable &t = *table;
    const int n = t.NumMu(), channels = t.NumChannels();
    // a_0 of each channel at every grid cosine μi for this μo: the spline's nodes along μi.
    std::vector<float> a0(size_t(channels * n));
    std::vector<float> ak;
    for (int i = 0; i < n; ++i) {
        t.Coefficients(t.Mu()[size_t(i)], wo.z, &ak);  // zeros where the table has none
        for (int c = 0; c < channels; ++c) a0[size_t(c * n + i)] = ak[size_t(c * t.MaxOrder())];
    }
    double sum[3] = {0, 0, 0};
    for (int c = 0; c < channels; ++c) {
        for (int i = 0; i + 1 < n; ++i) {
            const SplineSegment s = SplineSegmentAt(t.Mu(), &a0[size_t(c * n)], i);
            const float mid = 0.5f * (t.Mu()[size_t(i)] + t.Mu()[size_t(i + 1)]);
            double eta2 = 1;  // transmission: f's radiance scale
            if (mid * wo.z > 0)
                eta2 = mid > 0 ? 1 / (double(t.Eta()) * t.Eta()) : t.Eta() * t.Eta();
            sum[c] += 2 * kPi * eta2 * s.width * s.Integral(1);
        }
    }
    if (channels == 1) return RGB(float(sum[0])).Clamped(0.f);
    const double Y = sum[0], R = sum[1], B = sum[2];
    const double G = 1.39829 * Y - 0.100913 * B - 0.297375 * R;
    const RGB a{float(R), float(G), float(B)};
    return a.IsFinite() ? a.Clamped(0.f) : RGB(0);
}

float FourierLobe::AlbedoEstimate(const Vec3f &wo) const {
    const float a = float(2 * kPi) * table->Total(wo.z);
    return std::isfinite(a) ? std::clamp(a, 0.f, 1.f) : 0.f;
}

}  // namespace prism
