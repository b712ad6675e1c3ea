#include "render/disney_bxdf.h"

#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/microfacet.h"

namespace prism {

namespace {

constexpr float InvPiF = float(InvPi);

float SchlickWeight(float cosTheta) {
    const float m = std::clamp(1 - cosTheta, 0.f, 1.f);
    return (m * m) * (m * m) * m;
}

RGB Lerp(float t, const RGB &a, const RGB &b) { return a * (1 - t) + b * t; }

// The specular lobe's Fresnel: Schlick from cspec0 blended with the dielectric term by metallic.
RGB DisneyFresnel(const DisneyLobe &l, float cosI) {
    const RGB schlick = Lerp(SchlickWeight(cosI), l.cspec0, RGB(1));
    return Lerp(l.metallic, RGB(FrDielectric(cosI, 1, l.eta)), schlick);
}

float G1(const Vec3f &w, float ax, float ay) { return 1 / (1 + TrowbridgeReitzLambda(w, ax, ay)); }

// GTR1 (the clearcoat's distribution) and Smith's G for GGX at alpha 0.25.
float GTR1(float cosTheta, float alpha) {
    const float a2 = alpha * alpha;
    return (a2 - 1) / (float(Pi) * std::log(a2) * (1 + (a2 - 1) * cosTheta * cosTheta));
}
float SmithGGGX(float cosTheta, float alpha) {
    const float a2 = alpha * alpha, c2 = cosTheta * cosTheta;
    return 1 / (cosTheta + std::sqrt(a2 + c2 - a2 * c2));
}
float ClearcoatAlpha(const DisneyLobe &l) { return 0.1f + (0.001f - 0.1f) * l.clearcoatGloss; }

Vec3f Reflect(const Vec3f &wo, const Vec3f &n) { return -wo + n * (2 * Dot(wo, n)); }

// The components and their choice weights at wo.
enum Component { CDiffuse, CSpecular, CClearcoat, CTransmit, CDiffuseTransmit, NumComponents };

void Weights(const DisneyLobe &l, const Vec3f &wo, float w[NumComponents]) {
    const float c = std::abs(wo.z);
    w[CDiffuse] = (l.diffuse + l.fakeSS + l.retro + l.sheen).Average();
    w[CSpecular] = std::max(DisneyFresnel(l, c).Average(), 0.02f);
    w[CClearcoat] = l.clearcoat > 0
                        ? std::max(0.25f * l.clearcoat * (0.04f + 0.96f * SchlickWeight(c)), 0.01f)
                        : 0.f;
    w[CTransmit] = l.transmit.IsBlack()
                       ? 0.f
                       : std::max(l.transmit.Average() * (1 - FrDielectric(wo.z, 1, l.eta)), 0.02f);
    w[CDiffuseTransmit] = l.diffuseTransmit.Average();
}

// The relative index and the generalised half vector of a transmission (facing +z), or false.
bool TransmissionHalf(const DisneyLobe &l, const Vec3f &wo, const Vec3f &wi, float *eta,
                      Vec3f *wh) {
    if (wo.z * wi.z >= 0) return false;
    *eta = wo.z > 0 ? l.eta : 1 / l.eta;
    Vec3f h = wo + wi * *eta;
    if (h.x == 0 && h.y == 0 && h.z == 0) return false;
    h = Normalize(h);
    if (h.z < 0) h = -h;
    if (Dot(wo, h) * Dot(wi, h) > 0) return false;
    *wh = h;
    return true;
}

float ComponentPdf(const DisneyLobe &l, int c, const Vec3f &wo, const Vec3f &wi) {
    const bool same = wo.z * wi.z > 0;
    switch (c) {
        case CDiffuse:
            return same ? std::abs(wi.z) * InvPiF : 0.f;
        case CDiffuseTransmit:
            return !same ? std::abs(wi.z) * InvPiF : 0.f;
        case CSpecular: {
            if (!same) return 0;
            const float s = wo.z > 0 ? 1.f : -1.f;
            const Vec3f woUp(wo.x, wo.y, wo.z * s), wiUp(wi.x, wi.y, wi.z * s);
            Vec3f wh = woUp + wiUp;
            if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 0;
            wh = Normalize(wh);
            const float cosOH = Dot(woUp, wh);
            if (!(cosOH > 0)) return 0;
            return TrowbridgeReitzVisiblePdf(woUp, wh, l.ax, l.ay) / (4 * cosOH);
        }
        case CClearcoat: {
            if (!same) return 0;
            Vec3f wh = wo + wi;
            if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 0;
            wh = Normalize(wh);
            const float cosOH = std::abs(Dot(wo, wh));
            if (!(cosOH > 0)) return 0;
            return GTR1(std::abs(wh.z), ClearcoatAlpha(l)) * std::abs(wh.z) / (4 * cosOH);
        }
        case CTransmit: {
            float eta;
            Vec3f wh;
            if (!TransmissionHalf(l, wo, wi, &eta, &wh)) return 0;
            const float s = wo.z > 0 ? 1.f : -1.f;
            // Mirrored to wo's side, with the microfacet normal that faces it.
            const Vec3f woUp(wo.x, wo.y, wo.z * s), whUp = s > 0 ? wh : Vec3f(-wh.x, -wh.y, wh.z);
            const float denom = Dot(wo, wh) + eta * Dot(wi, wh);
            if (denom == 0) return 0;
            const float dwhdwi = std::abs(eta * eta * Dot(wi, wh)) / (denom * denom);
            return TrowbridgeReitzVisiblePdf(woUp, whUp, l.tax, l.tay) * dwhdwi;
        }
        default:
            return 0;
    }
}

}  // namespace

RGB DisneyLobe::f(const Vec3f &wo, const Vec3f &wi, bool reflect) const {
    const float cosO = std::abs(wo.z), cosI = std::abs(wi.z);
    if (cosO == 0 || cosI == 0) return RGB(0);
    if (!reflect) {
        RGB result = diffuseTransmit * InvPiF;
        float eta;
        Vec3f wh;
        if (!transmit.IsBlack() && TransmissionHalf(*this, wo, wi, &eta, &wh)) {
            const float F = FrDielectric(Dot(wo, wh), 1, this->eta);
            const float G = thin ? 1 / (1 + TrowbridgeReitzLambda(wo, tax, tay) +
                                        TrowbridgeReitzLambda(wi, tax, tay))
                                 : G1(wo, tax, tay) * G1(wi, tax, tay);
            const float denom = Dot(wo, wh) + eta * Dot(wi, wh);
            // Radiance transport: 1/η² of the refracted radiance.
            const float v = std::abs(TrowbridgeReitzD(wh, tax, tay) * G * std::abs(Dot(wi, wh)) *
                                     std::abs(Dot(wo, wh)) / (cosI * cosO * denom * denom));
            result += transmit * ((1 - F) * v);
        }
        return result;
    }
    Vec3f wh = wi + wo;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return RGB(0);
    wh = Normalize(wh);
    const float cosD = Dot(wi, wh);
    const float Fo = SchlickWeight(cosO), Fi = SchlickWeight(cosI);
    RGB result = diffuse * (InvPiF * (1 - Fo / 2) * (1 - Fi / 2));
    if (!fakeSS.IsBlack()) {
        const float fss90 = cosD * cosD * roughness;
        const float fss = (1 + (fss90 - 1) * Fo) * (1 + (fss90 - 1) * Fi);
        result += fakeSS * (InvPiF * 1.25f * (fss * (1 / (cosO + cosI) - 0.5f) + 0.5f));
    }
    if (!retro.IsBlack()) {
        const float rr = 2 * roughness * cosD * cosD;
        result += retro * (InvPiF * rr * (Fo + Fi + Fo * Fi * (rr - 1)));
    }
    if (!sheen.IsBlack()) result += sheen * SchlickWeight(cosD);
    // The specular lobe, its Fresnel term at the normal facing the outside, as pbrt-v3's
    // microfacet reflection takes it: seen from inside, the inside's (total internal reflection).
    const Vec3f whUp = wh.z < 0 ? -wh : wh;
    const float D = TrowbridgeReitzD(whUp, ax, ay), G = G1(wo, ax, ay) * G1(wi, ax, ay);
    result += DisneyFresnel(*this, Dot(wi, whUp)) * (D * G / (4 * cosI * cosO));
    if (clearcoat > 0) {
        const float Dr = GTR1(std::abs(wh.z), ClearcoatAlpha(*this));
        const float Fr = 0.04f + 0.96f * SchlickWeight(Dot(wo, wh));
        const float Gr = SmithGGGX(cosO, 0.25f) * SmithGGGX(cosI, 0.25f);
        result += RGB(0.25f * clearcoat * Gr * Fr * Dr);
    }
    return result;
}

float DisneyLobe::Pdf(const Vec3f &wo, const Vec3f &wi) const {
    float w[NumComponents], total = 0, pdf = 0;
    Weights(*this, wo, w);
    for (int c = 0; c < NumComponents; ++c) {
        total += w[c];
        if (w[c] > 0) pdf += w[c] * ComponentPdf(*this, c, wo, wi);
    }
    return total > 0 ? pdf / total : 0.f;
}

bool DisneyLobe::Sample(const Vec3f &wo, float uc, Vec2f u, Vec3f *wi) const {
    if (wo.z == 0) return false;
    float w[NumComponents], total = 0;
    Weights(*this, wo, w);
    for (float x : w) total += x;
    if (!(total > 0)) return false;
    float target = std::min(uc, 0x1.fffffep-1f) * total, sum = 0;
    int c = 0;
    while (c + 1 < NumComponents && (w[c] == 0 || sum + w[c] <= target)) sum += w[c++];
    const float s = wo.z > 0 ? 1.f : -1.f;
    const Vec3f woUp(wo.x, wo.y, wo.z * s);
    switch (c) {
        case CDiffuse:
        case CDiffuseTransmit: {
            const float r = std::sqrt(u.x), phi = 2 * float(Pi) * u.y;
            Vec3f d(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
            d.z *= c == CDiffuse ? s : -s;
            *wi = d;
            return true;
        }
        case CSpecular: {
            const Vec3f wh = TrowbridgeReitzSampleVisible(woUp, ax, ay, u);
            Vec3f d = Reflect(woUp, wh);
            if (d.z <= 0) return false;
            *wi = Vec3f(d.x, d.y, d.z * s);
            return true;
        }
        case CClearcoat: {
            const float a2 = ClearcoatAlpha(*this) * ClearcoatAlpha(*this);
            const float cosT = std::sqrt(std::max(0.f, (1 - std::pow(a2, 1 - u.x)) / (1 - a2)));
            const float sinT = std::sqrt(std::max(0.f, 1 - cosT * cosT)), phi = 2 * float(Pi) * u.y;
            const Vec3f wh(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
            const Vec3f d = Reflect(woUp, wh);
            if (d.z <= 0) return false;
            *wi = Vec3f(d.x, d.y, d.z * s);
            return true;
        }
        default: {
            // Refraction about a visible normal; η is inside over outside on wo's side.
            const Vec3f wh = TrowbridgeReitzSampleVisible(woUp, tax, tay, u);
            const float etaRel = wo.z > 0 ? 1 / eta : eta;  // ηo / ηi
            const float cosI = Dot(woUp, wh);
            const float sin2T = etaRel * etaRel * std::max(0.f, 1 - cosI * cosI);
            if (sin2T >= 1) return false;
            const float cosT = std::sqrt(1 - sin2T);
            const Vec3f d = -woUp * etaRel + wh * (etaRel * cosI - cosT);
            *wi = Vec3f(d.x, d.y, d.z * s);
            return true;
        }
    }
}

float DisneyLobe::AlbedoEstimate(const Vec3f &wo) const {
    float w[NumComponents], total = 0;
    Weights(*this, wo, w);
    for (float x : w) total += x;
    return std::min(total, 1.f);
}

}  // namespace prism
