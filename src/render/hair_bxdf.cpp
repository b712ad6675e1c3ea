#include "render/hair_bxdf.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/bsdf.h"

namespace prism {

namespace {

constexpr float kPi = float(Pi);
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

float Sqr(float x) { return x * x; }
float SafeSqrt(float x) { return std::sqrt(std::max(0.f, x)); }
float SafeAsin(float x) { return std::asin(std::clamp(x, -1.f, 1.f)); }

// log I0(x), I0 the modified Bessel function of the first kind of order 0: its power series
// summed until the terms stop counting (pbrt stops at ten terms, up to 2% low near x = 12), and
// beyond x = 12 its asymptotic expansion e^x / sqrt(2πx) · (1 + 1/(8x)).
double LogBesselI0(double x) {
    if (x > 12) return x - 0.5 * std::log(2 * Pi * x) + std::log1p(1 / (8 * x));
    const double q = x * x / 4;
    double term = 1, sum = 1;
    for (int i = 1; i < 40 && term > 1e-9 * sum; ++i) {
        term *= q / double(i * i);
        sum += term;
    }
    return std::log(sum);
}

// The longitudinal lobe: the density over θi (per cos θi dθi) of light leaving at θi for light
// arriving at θo, variance v. Evaluated in logarithms, in double: for narrow lobes the exponent
// is the difference of two numbers of order 1/v.
float LongitudinalLobe(float cosThetaI, float cosThetaO, float sinThetaI, float sinThetaO,
                       float v) {
    const double a = double(cosThetaI) * cosThetaO / v, b = double(sinThetaI) * sinThetaO / v;
    // csch(1/v) / (2v) = e^(-1/v) / (v (1 - e^(-2/v))).
    const double logNorm = -1.0 / v - std::log(double(v)) - std::log1p(-std::exp(-2.0 / v));
    return float(std::exp(LogBesselI0(a) - b + logNorm));
}

// The exit azimuth of path p relative to the entry's, for the entry angle γo and the refracted
// angle γt inside the fibre.
float ExitAzimuth(int p, float gammaO, float gammaT) {
    return 2 * float(p) * gammaT - 2 * gammaO + float(p) * kPi;
}

float Logistic(float x, float s) {
    const float e = std::exp(-std::abs(x) / s);
    return e / (s * Sqr(1 + e));
}
float LogisticCdf(float x, float s) { return 1 / (1 + std::exp(-x / s)); }

// The azimuthal lobe of path p: the logistic of scale s, restricted to [-π, π], around the
// path's exit azimuth.
float AzimuthalLobe(float phi, int p, float s, float gammaO, float gammaT) {
    const float dphi = std::remainder(phi - ExitAzimuth(p, gammaO, gammaT), 2 * kPi);
    return Logistic(dphi, s) / (LogisticCdf(kPi, s) - LogisticCdf(-kPi, s));
}

float SampleTrimmedLogistic(float u, float s) {
    const float lo = LogisticCdf(-kPi, s), k = LogisticCdf(kPi, s) - lo;
    const float x = -s * std::log(1 / (u * k + lo) - 1);
    return std::clamp(x, -kPi, kPi);
}

float Variance(const HairLobe &l, int p) {
    return p == 0 ? l.v0 : p == 1 ? 0.25f * l.v0 : 4 * l.v0;
}

// What a ray from wo sees of the fibre: its angles, each path's attenuation and the tilted
// longitudinal angles the paths reflect about.
struct FibreView {
    float sinThetaO = 0, cosThetaO = 1, phiO = 0, gammaO = 0, gammaT = 0;
    std::array<RGB, HairLobe::PMax + 1> ap;
    std::array<float, HairLobe::PMax + 1> sinOp{}, cosOp{};
};

FibreView See(const HairLobe &l, const Vec3f &wo) {
    FibreView fv;
    fv.sinThetaO = std::clamp(wo.x, -1.f, 1.f);
    fv.cosThetaO = SafeSqrt(1 - Sqr(fv.sinThetaO));
    fv.phiO = std::atan2(wo.z, wo.y);
    fv.gammaO = SafeAsin(l.h);
    // Inside: the refracted longitudinal angle and the modified index for the azimuthal plane
    // (Bravais), so the chord the light crosses and its absorption.
    const float sinThetaT = fv.sinThetaO / l.eta, cosThetaT = SafeSqrt(1 - Sqr(sinThetaT));
    const float etaP = SafeSqrt(Sqr(l.eta) - Sqr(fv.sinThetaO)) / std::max(fv.cosThetaO, 1e-7f);
    const float sinGammaT = l.h / etaP, cosGammaT = SafeSqrt(1 - Sqr(sinGammaT));
    fv.gammaT = SafeAsin(sinGammaT);
    const float chord = 2 * cosGammaT / std::max(cosThetaT, 1e-7f);
    const RGB T(std::exp(-l.sigmaA.r * chord), std::exp(-l.sigmaA.g * chord),
                std::exp(-l.sigmaA.b * chord));
    // Fresnel at the entry (and, by symmetry, at every internal event).
    const float f = FrDielectric(fv.cosThetaO * SafeSqrt(1 - Sqr(l.h)), 1.f, l.eta);
    fv.ap[0] = RGB(f);
    fv.ap[1] = T * Sqr(1 - f);
    fv.ap[2] = fv.ap[1] * T * f;
    const RGB tf = T * f;
    fv.ap[3] = fv.ap[2] * tf / (RGB(1) - tf);
    // The cuticle's tilt: R about θo - 2α, TT about θo + α, TRT about θo + 4α; longer paths
    // are not tilted.
    const float sin2a = 2 * l.sinAlpha * l.cosAlpha, cos2a = Sqr(l.cosAlpha) - Sqr(l.sinAlpha);
    const float sin4a = 2 * sin2a * cos2a, cos4a = Sqr(cos2a) - Sqr(sin2a);
    const float so = fv.sinThetaO, co = fv.cosThetaO;
    fv.sinOp = {so * cos2a - co * sin2a, so * l.cosAlpha + co * l.sinAlpha, so * cos4a + co * sin4a,
                so};
    fv.cosOp = {co * cos2a + so * sin2a, co * l.cosAlpha - so * l.sinAlpha, co * cos4a - so * sin4a,
                co};
    for (float &c : fv.cosOp) c = std::abs(c);
    return fv;
}

// The probability of sampling each path: its attenuation's luminance over the sum.
bool PathPmf(const FibreView &fv, std::array<float, HairLobe::PMax + 1> *pmf) {
    float sum = 0;
    for (int p = 0; p <= HairLobe::PMax; ++p)
        sum += ((*pmf)[size_t(p)] = fv.ap[size_t(p)].Luminance());
    if (!(sum > 0) || !std::isfinite(sum)) return false;
    for (float &x : *pmf) x /= sum;
    return true;
}

// The density of wi (its longitudinal sine and cosine, and azimuth relative to wo's) among
// the paths chosen with `pmf`.
float PathsPdf(const HairLobe &l, const FibreView &fv, const std::array<float, 4> &pmf,
               float sinThetaI, float cosThetaI, float phi) {
    float pdf = 0;
    for (int p = 0; p < HairLobe::PMax; ++p)
        pdf += pmf[size_t(p)] *
               LongitudinalLobe(cosThetaI, fv.cosOp[size_t(p)], sinThetaI, fv.sinOp[size_t(p)],
                                Variance(l, p)) *
               AzimuthalLobe(phi, p, l.s, fv.gammaO, fv.gammaT);
    const int last = HairLobe::PMax;
    pdf += pmf[last] *
           LongitudinalLobe(cosThetaI, fv.cosThetaO, sinThetaI, fv.sinThetaO, Variance(l, last)) /
           (2 * kPi);
    return pdf;
}

}  // namespace

HairLobe HairLobe::Make(float h, float eta, const RGB &sigmaA, float betaM, float betaN,
                        float alphaDegrees) {
    HairLobe l;
    l.h = std::clamp(h, -1.f, 1.f);
    l.eta = std::max(eta, 1e-3f);
    l.sigmaA = sigmaA.Clamped(0.f);
    // Roughness 0 would be a delta lobe; 10⁻³ is far narrower than a pixel's worth of fibres.
    const float bm = std::clamp(betaM, 1e-3f, 1.f), bn = std::clamp(betaN, 1e-3f, 1.f);
    l.v0 = Sqr(0.726f * bm + 0.812f * Sqr(bm) + 3.7f * std::pow(bm, 20.f));
    l.s = std::sqrt(kPi / 8) * (0.265f * bn + 1.194f * Sqr(bn) + 5.372f * std::pow(bn, 22.f));
    l.sinAlpha = float(std::sin(Radians(alphaDegrees)));
    l.cosAlpha = SafeSqrt(1 - Sqr(l.sinAlpha));
    return l;
}

RGB HairLobe::SigmaAFromConcentration(float eumelanin, float pheomelanin) {
    return RGB(0.419f, 0.697f, 1.37f) * std::max(eumelanin, 0.f) +
           RGB(0.187f, 0.4f, 1.05f) * std::max(pheomelanin, 0.f);
}

RGB HairLobe::SigmaAFromReflectance(const RGB &c, float betaN) {
    const float b = betaN;
    const float d = 5.969f - 0.215f * b + 2.532f * Sqr(b) - 10.73f * b * Sqr(b) +
                    5.574f * Sqr(Sqr(b)) + 0.245f * b * Sqr(Sqr(b));
    RGB s;
    for (int i = 0; i < 3; ++i) s[i] = Sqr(std::log(std::clamp(c[i], 1e-4f, 0.99f)) / d);
    return s;
}

RGB HairLobe::f(const Vec3f &wo, const Vec3f &wi) const {
    const FibreView fv = See(*this, wo);
    const float sinThetaI = std::clamp(wi.x, -1.f, 1.f), cosThetaI = SafeSqrt(1 - Sqr(sinThetaI));
    const float phi = std::atan2(wi.z, wi.y) - fv.phiO;
    RGB sum;
    for (int p = 0; p < PMax; ++p)
        sum += fv.ap[size_t(p)] * (LongitudinalLobe(cosThetaI, fv.cosOp[size_t(p)], sinThetaI,
                                                    fv.sinOp[size_t(p)], Variance(*this, p)) *
                                   AzimuthalLobe(phi, p, s, fv.gammaO, fv.gammaT));
    sum += fv.ap[PMax] * (LongitudinalLobe(cosThetaI, fv.cosThetaO, sinThetaI, fv.sinThetaO,
                                           Variance(*this, PMax)) /
                          (2 * kPi));
    const float cosN = std::abs(wi.z);
    return cosN > 0 ? sum / cosN : sum;
}

bool HairLobe::Sample(const Vec3f &wo, float uc, Vec2f u, Vec3f *wi, float *pdf) const {
    const FibreView fv = See(*this, wo);
    std::array<float, PMax + 1> pmf;
    if (!PathPmf(fv, &pmf)) return false;
    int p = 0;
    while (p < PMax && uc >= pmf[size_t(p)]) uc -= pmf[size_t(p++)];
    uc = std::clamp(uc / pmf[size_t(p)], 0.f, kOneMinusEpsilon);
    // θi about the path's mirror angle -θo (tilted), by inverting the lobe's CDF.
    const float v = Variance(*this, p);
    const float u0 = std::max(u.x, 1e-5f);
    const float cosTheta = 1 + v * std::log(u0 + (1 - u0) * std::exp(-2 / v));
    const float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
    const float cosPhi = std::cos(2 * kPi * u.y);
    const float sinThetaI = std::clamp(
        -cosTheta * fv.sinOp[size_t(p)] + sinTheta * cosPhi * fv.cosOp[size_t(p)], -1.f, 1.f);
    const float cosThetaI = SafeSqrt(1 - Sqr(sinThetaI));
    // φi about the path's exit azimuth; the longest paths' is uniform.
    const float dphi = p < PMax
                           ? ExitAzimuth(p, fv.gammaO, fv.gammaT) + SampleTrimmedLogistic(uc, s)
                           : 2 * kPi * uc;
    const float phiI = fv.phiO + dphi;
    *wi = Vec3f(sinThetaI, cosThetaI * std::cos(phiI), cosThetaI * std::sin(phiI));
    *pdf = PathsPdf(*this, fv, pmf, sinThetaI, cosThetaI, dphi);
    return *pdf > 0 && std::isfinite(*pdf);
}

float HairLobe::Pdf(const Vec3f &wo, const Vec3f &wi) const {
    const FibreView fv = See(*this, wo);
    std::array<float, PMax + 1> pmf;
    if (!PathPmf(fv, &pmf)) return 0;
    const float sinThetaI = std::clamp(wi.x, -1.f, 1.f), cosThetaI = SafeSqrt(1 - Sqr(sinThetaI));
    return PathsPdf(*this, fv, pmf, sinThetaI, cosThetaI, std::atan2(wi.z, wi.y) - fv.phiO);
}

RGB HairLobe::Albedo(const Vec3f &wo) const {
    const FibreView fv = See(*this, wo);
    RGB sum;
    for (const RGB &a : fv.ap) sum += a;
    return sum.IsFinite() ? sum.Clamped(0.f, 1.f) : RGB(0);
}

float HairLobe::AlbedoEstimate(const Vec3f &wo) const {
    const FibreView fv = See(*this, wo);
    float sum = 0;
    for (const RGB &a : fv.ap) sum += a.Average();
    return std::isfinite(sum) ? std::clamp(sum, 0.f, 1.f) : 0.f;
}

}  // namespace prism
