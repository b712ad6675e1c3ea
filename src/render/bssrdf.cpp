#include "render/bssrdf.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

#include "render/bsdf.h"
#include "render/medium.h"
#include "render/spline.h"

namespace prism {

namespace {

constexpr int NumRhoSamples = 100, NumRadiusSamples = 64;
// The depths (and, for single scattering, distances) each beam integral is summed over.
constexpr int BeamSamples = 100;

}  // namespace

float FresnelMoment1(float eta) {
    const double e = eta, e2 = e * e, e3 = e2 * e, e4 = e3 * e, e5 = e4 * e;
    if (eta < 1)
        return float(0.45966 - 1.73965 * e + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 -
                     0.68441 * e5);
    return float(-4.61686 + 11.1136 * e - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 +
                 0.12746 * e5);
}

float FresnelMoment2(float eta) {
    const double e = eta, e2 = e * e, e3 = e2 * e, e4 = e3 * e, e5 = e4 * e;
    if (eta < 1)
        return float(0.27614 - 0.87350 * e + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 +
                     0.04860 * e5);
    const double r = 1 / e, r2 = r * r, r3 = r2 * r;
    return float(-547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * e - 189.519 * e2 +
                 54.9327 * e3 - 9.00603 * e4 + 0.63942 * e5);
}

float BeamDiffusionMS(float sigmaS, float sigmaA, float g, float eta, float r) {
    // Reduced coefficients, the non-classical diffusion coefficient (Grosjean) and the
    // effective transport coefficient.
    const double sps = double(sigmaS) * (1 - g), spt = sigmaA + sps, rhop = sps / spt;
    const double D = (2 * double(sigmaA) + sps) / (3 * spt * spt);
    const double str = std::sqrt(sigmaA / D);
    // The extrapolation distance of the boundary condition and the exitance weights.
    const double fm1 = FresnelMoment1(eta), fm2 = FresnelMoment2(eta);
    const double ze = -2 * D * (1 + 3 * fm2) / (1 - 2 * fm1);
    const double cPhi = 0.25 * (1 - 2 * fm1), cE = 0.5 * (1 - 3 * fm2);
    const double inv4Pi = 1 / (4 * Pi), rr = double(r) * r;
    double Ed = 0;
    for (int i = 0; i < BeamSamples; ++i) {
        // A real source at depth zr, exponentially distributed along the beam; its image.
        const double zr = -std::log(1 - (i + 0.5) / BeamSamples) / spt;
        const double zv = -zr + 2 * ze;
        const double dr = std::sqrt(rr + zr * zr), dv = std::sqrt(rr + zv * zv);
        const double er = std::exp(-str * dr), ev = std::exp(-str * dv);
        const double phi = inv4Pi / D * (er / dr - ev / dv);
        const double EDn = inv4Pi * (zr * (1 + str * dr) * er / (dr * dr * dr) -
                                     zv * (1 + str * dv) * ev / (dv * dv * dv));
        const double E = phi * cPhi + EDn * cE;
        const double kappa = 1 - std::exp(-2 * spt * (dr + zr));
        Ed += kappa * rhop * rhop * E;
    }
    return float(Ed / BeamSamples);
}

float BeamDiffusionSS(float sigmaS, float sigmaA, float g, float eta, float r) {
    const double st = double(sigmaS) + sigmaA, rho = sigmaS / st;
    // Below the critical angle only: depths from r·sqrt(η² - 1) on.
    const double tCrit = r * std::sqrt(std::max(0.0, double(eta) * eta - 1));
    double Ess = 0;
    for (int i = 0; i < BeamSamples; ++i) {
        const double ti = tCrit - std::log(1 - (i + 0.5) / BeamSamples) / st;
        const double d = std::sqrt(double(r) * r + ti * ti), cosO = ti / d;
        Ess += rho * std::exp(-st * (d + tCrit)) / (d * d) * PhaseHG(float(cosO), g) *
               (1 - FrDielectric(float(-cosO), 1, eta)) * std::abs(cosO);
    }
    return float(Ess / BeamSamples);
}

std::shared_ptr<const BssrdfTable> BeamDiffusionTable(float g, float eta) {
    static std::mutex mutex;
    static std::map<std::pair<float, float>, std::weak_ptr<const BssrdfTable>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    std::weak_ptr<const BssrdfTable> &slot = cache[{g, eta}];
    if (auto t = slot.lock()) return t;
    auto t = std::make_shared<BssrdfTable>();
    // Radii: 0, then geometric from 2.5e-3 by 1.2 (to about 2e2 mean free paths); albedos
    // crowded toward 1, where the profile changes fastest.
    t->radius.resize(NumRadiusSamples);
    t->radius[0] = 0;
    t->radius[1] = 2.5e-3f;
    for (int j = 2; j < NumRadiusSamples; ++j)
        t->radius[size_t(j)] = t->radius[size_t(j - 1)] * 1.2f;
    t->rho.resize(NumRhoSamples);
    for (int i = 0; i < NumRhoSamples; ++i)
        t->rho[size_t(i)] =
            float((1 - std::exp(-8.0 * i / (NumRhoSamples - 1))) / (1 - std::exp(-8.0)));
    t->profile.resize(size_t(NumRhoSamples * NumRadiusSamples));
    t->profileCdf.resize(t->profile.size());
    t->rhoEff.resize(NumRhoSamples);
    for (int i = 0; i < NumRhoSamples; ++i) {
        const float rho = t->rho[size_t(i)];
        float *row = &t->profile[size_t(i * NumRadiusSamples)];
        for (int j = 0; j < NumRadiusSamples; ++j) {
            const float r = t->radius[size_t(j)];
            row[j] = float(2 * Pi * r *
                           (double(BeamDiffusionSS(rho, 1 - rho, g, eta, r)) +
                            BeamDiffusionMS(rho, 1 - rho, g, eta, r)));
        }
        t->rhoEff[size_t(i)] = float(IntegrateCatmullRom(
            t->radius.data(), NumRadiusSamples, row, &t->profileCdf[size_t(i * NumRadiusSamples)]));
    }
    slot = t;
    return t;
}

void SubsurfaceFromDiffuse(const BssrdfTable &t, const RGB &rhoEff, const RGB &mfp, RGB *sigmaA,
                           RGB *sigmaS) {
    for (int c = 0; c < 3; ++c) {
        const float rho = InvertCatmullRom(t.rho.data(), t.NumRho(), t.rhoEff.data(), rhoEff[c]);
        (*sigmaS)[c] = rho / mfp[c];
        (*sigmaA)[c] = (1 - rho) / mfp[c];
    }
}

float SubsurfaceSw(float cosTheta, float eta) {
    const float c = 1 - 2 * FresnelMoment1(1 / eta);
    return (1 - FrDielectric(cosTheta, 1, eta)) / (c * float(Pi));
}

SeparableBssrdf::SeparableBssrdf(const BssrdfTable &table, const Vec3f &po, const Vec3f &ns,
                                 const Vec3f &ss, float eta, const RGB &sigmaA, const RGB &sigmaS)
    : SeparableBssrdf(po, ns, ss, eta) {
    table_ = &table;
    sigmaT_ = sigmaA + sigmaS;
    for (int c = 0; c < 3; ++c) rho_[c] = sigmaT_[c] > 0 ? sigmaS[c] / sigmaT_[c] : 0.f;
}

SeparableBssrdf SeparableBssrdf::Disney(const Vec3f &po, const Vec3f &ns, const Vec3f &ss,
                                        float eta, const RGB &R, const RGB &d) {
    SeparableBssrdf b(po, ns, ss, eta);
    b.R_ = R;
    b.d_ = d;
    return b;
}

SeparableBssrdf::SeparableBssrdf(const Vec3f &po, const Vec3f &ns, const Vec3f &ss, float eta)
    : po_(po), ns_(ns), eta_(eta) {
    // The tangent ss made orthogonal to ns; any frame about ns when it is missing or parallel.
    const Vec3f s = ss - ns * Dot(ss, ns);
    const float len = Length(s);
    if (len > 1e-6f) {
        ss_ = s / len;
        ts_ = Cross(ns_, ss_);
    } else {
        CoordinateSystem(ns_, &ss_, &ts_);
    }
}

bool SeparableBssrdf::TabulatedSr(int ch, float r, double *sr, double *rhoEff) const {
    const BssrdfTable &t = *table_;
    const float rOptical = r * sigmaT_[ch];
    int rhoOff, radOff;
    float rhoW[4], radW[4];
    if (!CatmullRomWeights(t.rho.data(), t.NumRho(), rho_[ch], &rhoOff, rhoW) ||
        !CatmullRomWeights(t.radius.data(), t.NumRadius(), rOptical, &radOff, radW))
        return false;
    double v = 0, eff = 0;
    for (int i = 0; i < 4; ++i) {
        if (rhoW[i] == 0) continue;
        eff += double(t.rhoEff[size_t(rhoOff + i)]) * rhoW[i];
        for (int j = 0; j < 4; ++j)
            if (radW[j] != 0) v += double(rhoW[i]) * radW[j] * t.Profile(rhoOff + i, radOff + j);
    }
    // The table holds 2π r Sr (the profile's marginal in r).
    if (rOptical != 0) v /= 2 * Pi * rOptical;
    *sr = v * sigmaT_[ch] * sigmaT_[ch];
    if (rhoEff) *rhoEff = eff;
    return true;
}

RGB SeparableBssrdf::Sr(float r) const {
    RGB result;
    if (!table_) {
        const double rr = std::max(double(r), 1e-6);  // the profile's singularity at 0
        for (int c = 0; c < 3; ++c) {
            const double d = d_[c];
            if (!(d > 0)) continue;
            result[c] =
                float(R_[c] * (std::exp(-rr / d) + std::exp(-rr / (3 * d))) / (8 * Pi * d * rr));
        }
        return result;
    }
    for (int ch = 0; ch < 3; ++ch) {
        double sr;
        if (TabulatedSr(ch, r, &sr, nullptr)) result[ch] = float(std::max(0.0, sr));
    }
    return result;
}

float SeparableBssrdf::SampleSr(int ch, float u) const {
    if (!table_) {
        // Burley's profile is a mix of two exponentials in r (weights 1/4 and 3/4, as their
        // integrals): one is drawn, then inverted.
        const double d = d_[ch];
        if (!(d > 0)) return -1;
        if (u < 0.25f) return float(d * -std::log1p(-std::min(4.0 * u, 1 - 1e-7)));
        return float(3 * d * -std::log1p(-std::min((u - 0.25) / 0.75, 1 - 1e-7)));
    }
    if (!(sigmaT_[ch] > 0)) return -1;
    const BssrdfTable &t = *table_;
    const float r = SampleCatmullRom2D(t.rho.data(), t.NumRho(), t.radius.data(), t.NumRadius(),
                                       t.profile.data(), t.profileCdf.data(), rho_[ch], u);
    return std::isnan(r) ? -1.f : r / sigmaT_[ch];
}

float SeparableBssrdf::PdfSr(int ch, float r) const {
    if (!table_) {
        const double d = d_[ch], rr = std::max(double(r), 1e-6);
        if (!(d > 0)) return 0;
        return float(0.25 * std::exp(-rr / d) / (2 * Pi * d * rr) +
                     0.75 * std::exp(-rr / (3 * d)) / (6 * Pi * d * rr));
    }
    double sr, rhoEff;
    if (!TabulatedSr(ch, r, &sr, &rhoEff) || !(rhoEff > 0)) return 0;
    return float(std::max(0.0, sr / rhoEff));
}

float SeparableBssrdf::PdfSp(const Vec3f &pi, const Vec3f &ni) const {
    const Vec3f d = po_ - pi;
    const Vec3f dl(Dot(ss_, d), Dot(ts_, d), Dot(ns_, d));
    const Vec3f nl(Dot(ss_, ni), Dot(ts_, ni), Dot(ns_, ni));
    // The radius each axis's projection sees, and the axes' probabilities (ss, ts, ns).
    const float rProj[3] = {std::sqrt(dl.y * dl.y + dl.z * dl.z),
                            std::sqrt(dl.z * dl.z + dl.x * dl.x),
                            std::sqrt(dl.x * dl.x + dl.y * dl.y)};
    const float axisProb[3] = {0.25f, 0.25f, 0.5f};
    const float nAxis[3] = {nl.x, nl.y, nl.z};
    float pdf = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int ch = 0; ch < 3; ++ch)
            pdf += PdfSr(ch, rProj[axis]) * std::abs(nAxis[axis]) * axisProb[axis] / 3;
    return pdf;
}

bool SeparableBssrdf::Probe(float u1, Vec2f u2, Vec3f *from, Vec3f *to, float *uRest) const {
    Vec3f vx, vy, vz;
    if (u1 < 0.5f) {
        vx = ss_, vy = ts_, vz = ns_;
        u1 *= 2;
    } else if (u1 < 0.75f) {
        vx = ts_, vy = ns_, vz = ss_;
        u1 = (u1 - 0.5f) * 4;
    } else {
        vx = ns_, vy = ss_, vz = ts_;
        u1 = (u1 - 0.75f) * 4;
    }
    const int ch = std::clamp(int(u1 * 3), 0, 2);
    *uRest = std::min(u1 * 3 - float(ch), 0x1.fffffep-1f);
    const float r = SampleSr(ch, u2.x);
    if (r < 0) return false;
    // The profile's extent: its 99.9th percentile radius bounds the sphere the chord crosses.
    const float rMax = SampleSr(ch, 0.999f);
    if (!(r < rMax)) return false;
    const float phi = 2 * float(Pi) * u2.y, l = 2 * std::sqrt(rMax * rMax - r * r);
    *from = po_ + (vx * std::cos(phi) + vy * std::sin(phi)) * r - vz * (0.5f * l);
    *to = *from + vz * l;
    return true;
}

}  // namespace prism
