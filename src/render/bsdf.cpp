#include "render/bsdf.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "render/bssrdf.h"
#include "render/microfacet.h"

namespace prism {

float FrDielectric(float cosThetaI, float etaI, float etaT) {
    cosThetaI = Clamp(cosThetaI, -1.f, 1.f);
    if (cosThetaI <= 0) {  // leaving the medium: swap the indices
        std::swap(etaI, etaT);
        cosThetaI = std::abs(cosThetaI);
    }
    float sinThetaI = std::sqrt(std::max(0.f, 1 - cosThetaI * cosThetaI));
    float sinThetaT = etaI / etaT * sinThetaI;
    if (sinThetaT >= 1) return 1;  // total internal reflection
    float cosThetaT = std::sqrt(std::max(0.f, 1 - sinThetaT * sinThetaT));
    float rParl =
        ((etaT * cosThetaI) - (etaI * cosThetaT)) / ((etaT * cosThetaI) + (etaI * cosThetaT));
    float rPerp =
        ((etaI * cosThetaI) - (etaT * cosThetaT)) / ((etaI * cosThetaI) + (etaT * cosThetaT));
    return (rParl * rParl + rPerp * rPerp) / 2;
}

RGB FrConductor(float cosThetaI, const RGB &etai, const RGB &etat, const RGB &k) {
    cosThetaI = Clamp(cosThetaI, -1.f, 1.f);
    RGB result;
    for (int c = 0; c < 3; ++c) {
        float eta = etat[c] / etai[c], etak = k[c] / etai[c];
        float cos2 = cosThetaI * cosThetaI, sin2 = 1 - cos2;
        float eta2 = eta * eta, etak2 = etak * etak;
        float t0 = eta2 - etak2 - sin2;
        float a2plusb2 = std::sqrt(t0 * t0 + 4 * eta2 * etak2);
        float t1 = a2plusb2 + cos2;
        float a = std::sqrt(std::max(0.f, 0.5f * (a2plusb2 + t0)));
        float t2 = 2 * cosThetaI * a;
        float rs = (t1 - t2) / (t1 + t2);
        float t3 = cos2 * a2plusb2 + sin2 * sin2;
        float t4 = t2 * sin2;
        float rp = rs * (t3 - t4) / (t3 + t4);
        result[c] = 0.5f * (rp + rs);
    }
    return result;
}

float RoughnessToAlpha(float roughness) {
    roughness = std::max(roughness, 1e-3f);
    float x = std::log(roughness);
    return 1.62142f + 0.819955f * x + 0.1734f * x * x + 0.0171201f * x * x * x +
           0.000640711f * x * x * x * x;
}

RGB FrSchlick(float cosTheta, const RGB &f0, const RGB &f90) {
    float m = Clamp(1 - std::abs(cosTheta), 0.f, 1.f);
    float m5 = (m * m) * (m * m) * m;
    return f0 + (f90 - f0) * m5;
}

RGB Fresnel::Evaluate(float cosThetaI) const {
    switch (kind) {
        case FresnelKind::None:
            return RGB(1);
        case FresnelKind::Dielectric:
            return RGB(FrDielectric(cosThetaI, etaI, etaT));
        case FresnelKind::Conductor:
            return FrConductor(std::abs(cosThetaI), RGB(1), eta, k);
        case FresnelKind::Schlick:
            return FrSchlick(cosThetaI, f0, f90);
        case FresnelKind::ThinDielectric: {
            const float R = FrDielectric(std::abs(cosThetaI), etaI, etaT), T = 1 - R;
            return RGB(R < 1 ? R + T * T * R / (1 - R * R) : 1.f);
        }
    }
    return RGB(1);
}

void BSDF::SetFrame(const Vec3f &shadingNormal, const Vec3f &dpdu, const Vec3f &geometricNormal) {
    ns = shadingNormal;
    ng = geometricNormal;
    Vec3f s = dpdu - ns * Dot(dpdu, ns);
    float len = Length(s);
    if (len > 1e-12f && std::isfinite(len)) {
        ss = s / len;
        ts = Cross(ns, ss);
    } else {
        CoordinateSystem(ns, &ss, &ts);
    }
}

namespace {

inline float CosTheta(const Vec3f &w) { return w.z; }
inline float Cos2Theta(const Vec3f &w) { return w.z * w.z; }
inline float Sin2Theta(const Vec3f &w) { return std::max(0.f, 1 - Cos2Theta(w)); }
inline float Tan2Theta(const Vec3f &w) { return Sin2Theta(w) / Cos2Theta(w); }
inline float Cos2Phi(const Vec3f &w) {
    float s2 = Sin2Theta(w);
    return s2 == 0 ? 1.f : Clamp(w.x * w.x / s2, 0.f, 1.f);
}
inline float Sin2Phi(const Vec3f &w) {
    float s2 = Sin2Theta(w);
    return s2 == 0 ? 0.f : Clamp(w.y * w.y / s2, 0.f, 1.f);
}

// glTF: the share of light that passes the dielectric specular layer, 1 - max(F_d(cos)).
float DielectricPass(const BxDFLobes &l, float cosTheta) {
    return 1 - FrSchlick(cosTheta, l.dielectricF0, l.dielectricF90).MaxComponent();
}

// glTF clearcoat: the share of light that passes the coat, 1 - coat·F_c(cos), F_c = Schlick
// with f0 0.04 (the coat's index 1.5).
float CoatPass(const BxDFLobes &l, float cosTheta) {
    if (l.coat == 0) return 1;
    return 1 - l.coat * FrSchlick(cosTheta, RGB(0.04f), RGB(1)).r;
}

// |v·h| for the half vector of wo and wi (reflection), or 1 when it is undefined.
float CosHalf(const Vec3f &wo, const Vec3f &wi) {
    Vec3f wh = wo + wi;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 1;
    return AbsDot(wo, Normalize(wh));
}

}  // namespace

float TrowbridgeReitzD(const Vec3f &wh, float ax, float ay) {
    float tan2 = Tan2Theta(wh);
    if (std::isinf(tan2)) return 0;
    float cos4 = Cos2Theta(wh) * Cos2Theta(wh);
    float e = (Cos2Phi(wh) / (ax * ax) + Sin2Phi(wh) / (ay * ay)) * tan2;
    return 1 / (float(Pi) * ax * ay * cos4 * (1 + e) * (1 + e));
}

float TrowbridgeReitzLambda(const Vec3f &w, float ax, float ay) {
    float tan2 = Tan2Theta(w);
    if (std::isinf(tan2)) return 0;
    float alpha2 = Cos2Phi(w) * ax * ax + Sin2Phi(w) * ay * ay;
    return (-1 + std::sqrt(1 + alpha2 * tan2)) / 2;
}

namespace {

// pbrt-v3 MicrofacetReflection::f with Trowbridge–Reitz D and Smith G.
RGB MicrofacetReflectionF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    float cosO = std::abs(wo.z), cosI = std::abs(wi.z);
    Vec3f wh = wi + wo;
    if (cosI == 0 || cosO == 0 || (wh.x == 0 && wh.y == 0 && wh.z == 0)) return RGB(0);
    wh = Normalize(wh);
    // Fresnel with wh turned to the normal's side so TIR is handled (pbrt-v3).
    Vec3f whF = wh.z < 0 ? -wh : wh;
    RGB F = l.glossyFresnel.Evaluate(Dot(wi, whF));
    float G = 1 / (1 + TrowbridgeReitzLambda(wo, l.alphaX, l.alphaY) +
                   TrowbridgeReitzLambda(wi, l.alphaX, l.alphaY));
    float coat = l.coat == 0 ? 1.f : CoatPass(l, Dot(wi, whF));
    return l.ks * F * (TrowbridgeReitzD(wh, l.alphaX, l.alphaY) * G * coat / (4 * cosI * cosO));
}

// pbrt-v3 MicrofacetTransmission::f (TransportMode::Radiance) with FresnelDielectric(1, eta):
// the generalized half vector of refraction, D, G, and the (1/eta)^2 radiance scaling.
RGB MicrofacetTransmissionF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    if (wo.z * wi.z > 0) return RGB(0);  // same hemisphere of the shading frame
    float cosO = wo.z, cosI = wi.z;
    if (cosI == 0 || cosO == 0) return RGB(0);
    float eta = cosO > 0 ? l.glossyEta : 1 / l.glossyEta;
    Vec3f wh = wo + wi * eta;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return RGB(0);
    wh = Normalize(wh);
    if (wh.z < 0) wh = -wh;
    // A half vector with wo and wi on the same side of the microfacet is not a refraction.
    if (Dot(wo, wh) * Dot(wi, wh) > 0) return RGB(0);
    float F = FrDielectric(Dot(wo, wh), 1.f, l.glossyEta);
    float sqrtDenom = Dot(wo, wh) + eta * Dot(wi, wh);
    float factor = 1 / eta;
    float G = 1 / (1 + TrowbridgeReitzLambda(wo, l.alphaX, l.alphaY) +
                   TrowbridgeReitzLambda(wi, l.alphaX, l.alphaY));
    float v = TrowbridgeReitzD(wh, l.alphaX, l.alphaY) * G * eta * eta * AbsDot(wi, wh) *
              AbsDot(wo, wh) * factor * factor / (cosI * cosO * sqrtDenom * sqrtDenom);
    return l.ksTransmit * ((1 - F) * std::abs(v));
}

// FresnelBlend's two terms (pbrt-v3 FresnelBlend::f): the diffuse base and the glossy coat.
RGB FresnelBlendDiffuseF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    auto pow5 = [](float v) { return (v * v) * (v * v) * v; };
    float cosI = std::abs(wi.z), cosO = std::abs(wo.z);
    return l.blendRd * (RGB(1) - l.blendRs) *
           (28.f / (23.f * float(Pi)) * (1 - pow5(1 - .5f * cosI)) * (1 - pow5(1 - .5f * cosO)));
}

RGB FresnelBlendCoatF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    auto pow5 = [](float v) { return (v * v) * (v * v) * v; };
    float cosI = std::abs(wi.z), cosO = std::abs(wo.z);
    Vec3f wh = wi + wo;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return RGB(0);
    wh = Normalize(wh);
    float cosH = Dot(wi, wh);
    RGB schlick = l.blendRs + (RGB(1) - l.blendRs) * pow5(1 - cosH);
    float denom = 4 * std::abs(cosH) * std::max(cosI, cosO);
    if (denom == 0) return RGB(0);
    return schlick * (TrowbridgeReitzD(wh, l.alphaX, l.alphaY) / denom);
}

// pbrt-v3 FresnelBlend::f (Ashikhmin–Shirley): a Fresnel-weighted diffuse base under a
// glossy coat with Schlick's Fresnel approximation.
RGB FresnelBlendF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    // pbrt-v3 returns 0, not the diffuse base, when wi = -wo.
    Vec3f wh = wi + wo;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return RGB(0);
    return FresnelBlendDiffuseF(l, wo, wi) + FresnelBlendCoatF(l, wo, wi);
}

// glTF thin-walled transmission: the GGX lobe of the reflection mirrored through the surface
// (wi flipped to wo's side), so a straight-through ray is its peak; no refraction.
RGB ThinTransmissionF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    const Vec3f wr(wi.x, wi.y, -wi.z);
    float cosO = std::abs(wo.z), cosI = std::abs(wr.z);
    if (cosI == 0 || cosO == 0 || wo.z * wr.z <= 0) return RGB(0);
    Vec3f wh = Normalize(wo + wr);
    float G = 1 / (1 + TrowbridgeReitzLambda(wo, l.alphaX, l.alphaY) +
                   TrowbridgeReitzLambda(wr, l.alphaX, l.alphaY));
    float v = TrowbridgeReitzD(wh, l.alphaX, l.alphaY) * G / (4 * cosI * cosO);
    return l.thinTransmit * (v * DielectricPass(l, Dot(wo, wh)) * CoatPass(l, Dot(wo, wh)));
}

// Lambertian or Oren–Nayar reflection (pbrt-v3 LambertianReflection, OrenNayar).
RGB DiffuseReflectionF(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    if (l.gltfDiffuse) {
        // glTF: fresnel_mix leaves the diffuse base the light that the specular layer (and
        // the clearcoat) do not reflect at this pair of directions.
        float c = CosHalf(wo, wi);
        return l.kd * (float(InvPi) * DielectricPass(l, c) * CoatPass(l, c));
    }
    if (!l.orenNayar) return l.kd * float(InvPi);
    float sinThetaI = std::sqrt(Sin2Theta(wi)), sinThetaO = std::sqrt(Sin2Theta(wo));
    float maxCos = 0;
    if (sinThetaI > 1e-4f && sinThetaO > 1e-4f) {
        float sinPhiI = wi.y / sinThetaI, cosPhiI = wi.x / sinThetaI;
        float sinPhiO = wo.y / sinThetaO, cosPhiO = wo.x / sinThetaO;
        maxCos = std::max(0.f, cosPhiI * cosPhiO + sinPhiI * sinPhiO);
    }
    float sinAlpha, tanBeta;
    if (std::abs(wi.z) > std::abs(wo.z)) {
        sinAlpha = sinThetaO;
        tanBeta = sinThetaI / std::abs(wi.z);
    } else {
        sinAlpha = sinThetaI;
        tanBeta = sinThetaO / std::abs(wo.z);
    }
    return l.kd * float(InvPi) * (l.orenNayarA + l.orenNayarB * maxCos * sinAlpha * tanBeta);
}

// Trowbridge–Reitz: a normal sampled from the distribution of normals visible from w
// (w.z > 0; Heitz 2018, "Sampling the GGX Distribution of Visible Normals"), and its density.
Vec3f SampleVisibleNormal(const Vec3f &w, float ax, float ay, Vec2f u) {
    Vec3f vh = Normalize(Vec3f(ax * w.x, ay * w.y, w.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    Vec3f t1 = lensq > 0 ? Vec3f(-vh.y, vh.x, 0) / std::sqrt(lensq) : Vec3f(1, 0, 0);
    Vec3f t2 = Cross(vh, t1);
    float r = std::sqrt(u.x), phi = 2 * float(Pi) * u.y;
    float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    float s = 0.5f * (1 + vh.z);
    p2 = (1 - s) * std::sqrt(std::max(0.f, 1 - p1 * p1)) + s * p2;
    Vec3f nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.f, 1 - p1 * p1 - p2 * p2));
    return Normalize(Vec3f(ax * nh.x, ay * nh.y, std::max(1e-6f, nh.z)));
}

float VisibleNormalPdf(const Vec3f &w, const Vec3f &wh, float ax, float ay) {
    float g1 = 1 / (1 + TrowbridgeReitzLambda(w, ax, ay));
    return g1 * std::max(0.f, Dot(w, wh)) * TrowbridgeReitzD(wh, ax, ay) / w.z;
}

// pbrt-v3's SeparableBSSRDFAdapter in radiance transport: η² Sw(wi).
RGB SubsurfaceExitF(const BxDFLobes &l, const Vec3f &wi) {
    const float eta = l.subsurfaceEta;
    return RGB(eta * eta * SubsurfaceSw(wi.z, eta));
}

}  // namespace

RGB BxDFLobes::fDiffuse(const Vec3f &wo, const Vec3f &wi, bool reflect) const {
    RGB result = HasLayered() ? layered.f(wo, wi) : RGB(0);
    if (hair.Active()) result += hair.f(wo, wi);
    if (fourier.Active()) result += fourier.f(wo, wi);
    if (disney.Active()) result += disney.f(wo, wi, reflect);
    if (reflect) {
        if (!kd.IsBlack()) result += DiffuseReflectionF(*this, wo, wi);
        if (fresnelBlend) result += FresnelBlendDiffuseF(*this, wo, wi);
        if (subsurfaceEta > 0) result += SubsurfaceExitF(*this, wi);
    } else if (!kdTransmit.IsBlack()) {
        result += kdTransmit * float(InvPi);
    }
    return result;
}

RGB BxDFLobes::fGlossy(const Vec3f &wo, const Vec3f &wi, bool reflect) const {
    RGB result;
    if (reflect) {
        if (!ks.IsBlack()) result += MicrofacetReflectionF(*this, wo, wi);
        if (fresnelBlend) result += FresnelBlendCoatF(*this, wo, wi);
    } else {
        if (!ksTransmit.IsBlack()) result += MicrofacetTransmissionF(*this, wo, wi);
        if (!thinTransmit.IsBlack()) result += ThinTransmissionF(*this, wo, wi);
    }
    return result;
}

RGB BxDFLobes::f(const Vec3f &wo, const Vec3f &wi, bool reflect) const {
    RGB result = fUnlayered(wo, wi, reflect);
    if (HasLayered()) result += layered.f(wo, wi);
    return result;
}

RGB BxDFLobes::fUnlayered(const Vec3f &wo, const Vec3f &wi, bool reflect) const {
    RGB result = hair.Active() ? hair.f(wo, wi) : RGB(0);
    if (fourier.Active()) result += fourier.f(wo, wi);
    if (disney.Active()) result += disney.f(wo, wi, reflect);
    if (reflect) {
        if (!kd.IsBlack()) result += DiffuseReflectionF(*this, wo, wi);
        if (subsurfaceEta > 0) result += SubsurfaceExitF(*this, wi);
        if (!ks.IsBlack()) result += MicrofacetReflectionF(*this, wo, wi);
        if (fresnelBlend) result += FresnelBlendF(*this, wo, wi);
    } else {
        if (!kdTransmit.IsBlack()) result += kdTransmit * float(InvPi);
        if (!ksTransmit.IsBlack()) result += MicrofacetTransmissionF(*this, wo, wi);
        if (!thinTransmit.IsBlack()) result += ThinTransmissionF(*this, wo, wi);
    }
    return result;
}

BxDFLobes &BSDF::AddPart(const RGB &weight) {
    PRISM_CHECK(n_ < MaxParts);
    new (&weight_[n_]) RGB(weight);
    return *new (&parts_[n_++]) BxDFLobes();
}

void BSDF::AddPart(const RGB &weight, const BxDFLobes &lobes) {
    PRISM_CHECK(n_ < MaxParts);
    new (&weight_[n_]) RGB(weight);
    new (&parts_[n_++]) BxDFLobes(lobes);
}

RGB BSDF::f(const Vec3f &woW, const Vec3f &wiW) const {
    Vec3f wo = ToLocal(woW), wi = ToLocal(wiW);
    if (wo.z == 0) return RGB(0);
    // pbrt BSDF::f: the geometric normal decides whether this is reflection or transmission,
    // which avoids light leaks through shading normals.
    bool reflect = Dot(wiW, ng) * Dot(woW, ng) > 0;
    if (n_ == 1) return weight_[0] * parts_[0].f(wo, wi, reflect);
    RGB result;
    for (int i = 0; i < n_; ++i)
        if (!weight_[i].IsBlack() && parts_[i].HasNonSpecular())
            result += weight_[i] * parts_[i].f(wo, wi, reflect);
    return result;
}

RGB BSDF::fDiffuse(const Vec3f &woW, const Vec3f &wiW) const {
    Vec3f wo = ToLocal(woW), wi = ToLocal(wiW);
    if (wo.z == 0) return RGB(0);
    bool reflect = Dot(wiW, ng) * Dot(woW, ng) > 0;
    RGB result;
    for (int i = 0; i < n_; ++i)
        if (!weight_[i].IsBlack() && parts_[i].HasDiffuse())
            result += weight_[i] * parts_[i].fDiffuse(wo, wi, reflect);
    return result;
}

namespace {

// pbrt-v4 TrowbridgeReitzDistribution::Regularize, per alpha.
void RegularizeAlpha(float *alpha) {
    if (*alpha < 0.3f) *alpha = std::clamp(2 * *alpha, 0.1f, 0.3f);
}

bool IsMicrofacetFresnel(const Fresnel &f) {
    return f.kind == FresnelKind::Dielectric || f.kind == FresnelKind::Conductor;
}

}  // namespace

void BSDF::Regularize() {
    for (int i = 0; i < n_; ++i) {
        BxDFLobes &l = parts_[i];
        if ((!l.ks.IsBlack() || !l.ksTransmit.IsBlack()) && IsMicrofacetFresnel(l.glossyFresnel)) {
            RegularizeAlpha(&l.alphaX);
            RegularizeAlpha(&l.alphaY);
        }
        // An index-matched dielectric passes light straight through, rough or not (pbrt-v4).
        const bool matched = l.specularFresnel.kind == FresnelKind::Dielectric && l.eta == 1;
        if ((!l.kr.IsBlack() || !l.kt.IsBlack()) && IsMicrofacetFresnel(l.specularFresnel) &&
            !matched) {
            RegularizeAlpha(&l.roughAlphaX);
            RegularizeAlpha(&l.roughAlphaY);
        }
        if (l.layered.Active()) {
            RegularizeAlpha(&l.layered.coatAlphaX);
            RegularizeAlpha(&l.layered.coatAlphaY);
            if (l.layered.base == LayeredLobe::Base::Conductor) {
                RegularizeAlpha(&l.layered.baseAlphaX);
                RegularizeAlpha(&l.layered.baseAlphaY);
            }
        }
    }
}

bool BSDF::MakeRoughSpecularGlossy() {
    for (int i = 0; i < n_; ++i) {
        BxDFLobes &l = parts_[i];
        if (!(l.roughAlphaX > 0 || l.roughAlphaY > 0)) continue;
        // pbrt-v3 GlassMaterial: MicrofacetReflection(R, FresnelDielectric(1, eta)) and
        // MicrofacetTransmission(T, 1, eta).
        l.ks = l.kr;
        l.glossyFresnel = l.specularFresnel;
        l.ksTransmit = l.kt;
        l.glossyEta = l.eta;
        l.alphaX = std::max(l.roughAlphaX, 1e-4f);
        l.alphaY = std::max(l.roughAlphaY, 1e-4f);
        l.kr = l.kt = RGB(0);
        l.roughAlphaX = l.roughAlphaY = 0;
    }
    return HasGlossy();
}

bool BSDF::SampleGlossy(int part, const Vec3f &woW, Vec2f u, float uc, Vec3f *wiW,
                        RGB *weight) const {
    const BxDFLobes &l = parts_[part];
    if (weight_[part].IsBlack() || !l.HasGlossy()) return false;
    Vec3f wo = ToLocal(woW);
    if (wo.z == 0) return false;
    // Sample on the upper side of the shading frame (the distribution is symmetric in z).
    const float side = wo.z > 0 ? 1.f : -1.f;
    const Vec3f woUp(wo.x, wo.y, wo.z * side);
    const Vec3f wh = SampleVisibleNormal(woUp, l.alphaX, l.alphaY, u);
    const float cosOH = Dot(woUp, wh);
    if (!(cosOH > 0)) return false;
    const float pdfWh = VisibleNormalPdf(woUp, wh, l.alphaX, l.alphaY);
    const bool hasT = !l.ksTransmit.IsBlack();
    const bool hasThin = !l.thinTransmit.IsBlack();
    // eta: index on wi's side over wo's side for a refraction (pbrt-v3 MicrofacetTransmission).
    const float eta = side > 0 ? l.glossyEta : 1 / l.glossyEta;
    float pR = 1;
    if (hasT) {
        float F = FrDielectric(cosOH * side, 1.f, l.glossyEta);
        float wR = (l.ks.IsBlack() ? 0.f : l.ks.Luminance() * F);
        float wT = l.ksTransmit.Luminance() * (1 - F);
        if (!(wR + wT > 0)) return false;
        pR = wR / (wR + wT);
    } else if (hasThin) {
        // glTF: the specular reflection against the thin-walled transmission at this facet.
        float wR = l.ks.IsBlack() ? 0.f : (l.ks * l.glossyFresnel.Evaluate(cosOH)).Luminance();
        float wT = l.thinTransmit.Luminance() * DielectricPass(l, cosOH);
        if (!(wR + wT > 0)) return false;
        pR = wR / (wR + wT);
    }
    Vec3f wiUp;
    float pdf;
    if (uc < pR) {
        wiUp = -woUp + wh * (2 * cosOH);
        if (!(wiUp.z > 0)) return false;
        pdf = pR * pdfWh / (4 * cosOH);
    } else if (hasThin) {
        // The mirrored reflection: wi continues through the surface.
        wiUp = -woUp + wh * (2 * cosOH);
        if (!(wiUp.z > 0)) return false;
        wiUp.z = -wiUp.z;
        pdf = (1 - pR) * pdfWh / (4 * cosOH);
    } else {
        float e = 1 / eta;  // etaI / etaT
        float sin2T = e * e * std::max(0.f, 1 - cosOH * cosOH);
        if (sin2T >= 1) return false;  // total internal reflection
        float cosT = std::sqrt(1 - sin2T);
        wiUp = -woUp * e + wh * (e * cosOH - cosT);
        if (!(wiUp.z < 0)) return false;
        float denom = cosOH + eta * Dot(wiUp, wh);
        pdf = (1 - pR) * pdfWh * std::abs(eta * eta * Dot(wiUp, wh)) / (denom * denom);
    }
    if (!(pdf > 0) || !std::isfinite(pdf)) return false;
    Vec3f wi(wiUp.x, wiUp.y, wiUp.z * side);
    *wiW = FromLocal(wi);
    bool reflect = Dot(*wiW, ng) * Dot(woW, ng) > 0;
    *weight = weight_[part] * l.fGlossy(wo, wi, reflect) * (std::abs(wi.z) / pdf);
    return !weight->IsBlack() && weight->IsFinite();
}

bool BSDF::SampleSpecularReflection(int part, const Vec3f &woW, Vec3f *wiW, RGB *weight) const {
    const BxDFLobes &l = parts_[part];
    if (weight_[part].IsBlack()) return false;
    if (l.layered.Active()) {
        // A smooth coat's mirror reflection (and, over polished metal, the paths beneath it).
        const Vec3f wo = ToLocal(woW);
        *weight = weight_[part] * l.layered.SpecularReflectance(wo);
        *wiW = FromLocal(Vec3f(-wo.x, -wo.y, wo.z));
        return !weight->IsBlack();
    }
    if (l.kr.IsBlack()) return false;
    Vec3f wo = ToLocal(woW);
    Vec3f wi(-wo.x, -wo.y, wo.z);
    if (wi.z == 0) return false;
    // f = F(cos) R / |cos|; the |cos| cancels with the one in the rendering equation.
    *weight = weight_[part] * l.kr * l.specularFresnel.Evaluate(CosTheta(wi));
    if (l.coat != 0) *weight *= CoatPass(l, CosTheta(wi));
    *wiW = FromLocal(wi);
    return !weight->IsBlack();
}

bool BSDF::SampleSpecularTransmission(int part, const Vec3f &woW, Vec3f *wiW, RGB *weight) const {
    const BxDFLobes &l = parts_[part];
    if (l.kt.IsBlack() || weight_[part].IsBlack()) return false;
    Vec3f wo = ToLocal(woW);
    if (wo.z == 0) return false;
    if (l.eta == 1) {
        // An index-matched interface (uber opacity, mixes with "none"): straight through,
        // with no Fresnel loss and no radiance scaling.
        *weight = weight_[part] * l.kt;
        // glTF thin-walled transmission: what the specular layer and the coat let through.
        if (l.gltfDiffuse) *weight *= DielectricPass(l, wo.z) * CoatPass(l, wo.z);
        // A thin dielectric slab: what its reflections leave.
        if (l.specularFresnel.kind == FresnelKind::ThinDielectric)
            *weight *= RGB(1) - l.specularFresnel.Evaluate(wo.z);
        *wiW = -woW;
        return !weight->IsBlack();
    }
    bool entering = wo.z > 0;
    float etaI = entering ? 1.f : l.eta, etaT = entering ? l.eta : 1.f;
    // Snell's law about the normal on wo's side.
    Vec3f n(0, 0, entering ? 1.f : -1.f);
    float e = etaI / etaT;
    float cosThetaI = Dot(n, wo);
    float sin2ThetaI = std::max(0.f, 1 - cosThetaI * cosThetaI);
    float sin2ThetaT = e * e * sin2ThetaI;
    if (sin2ThetaT >= 1) return false;  // total internal reflection: all goes to reflection
    float cosThetaT = std::sqrt(1 - sin2ThetaT);
    Vec3f wi = -wo * e + n * (e * cosThetaI - cosThetaT);
    float F = FrDielectric(CosTheta(wi), 1.f, l.eta);
    // Radiance is scaled by (etaI/etaT)^2 across the interface (pbrt-v3, TransportMode::Radiance).
    *weight = weight_[part] * l.kt * (1 - F) * ((etaI * etaI) / (etaT * etaT));
    *wiW = FromLocal(wi);
    return !weight->IsBlack();
}

Vec3f TrowbridgeReitzSampleVisible(const Vec3f &w, float ax, float ay, Vec2f u) {
    return SampleVisibleNormal(w, ax, ay, u);
}

float TrowbridgeReitzVisiblePdf(const Vec3f &w, const Vec3f &wh, float ax, float ay) {
    return VisibleNormalPdf(w, wh, ax, ay);
}

}  // namespace prism
