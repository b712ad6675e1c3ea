#include "render/gltf_sampling.h"

#include <cmath>

#include "render/microfacet.h"

namespace prism {

namespace {

// The probability of choosing the diffuse lobe (0 without one, 1 without glossy lobes).
float DiffuseChoice(const BSDF &b) {
    float kd = 0;
    bool glossy = false;
    for (int i = 0; i < b.NumParts(); ++i) {
        kd += (b.Weight(i) * b.Part(i).kd).Luminance();
        glossy = glossy || (!b.Weight(i).IsBlack() && b.Part(i).HasGlossy());
    }
    if (!glossy) return kd > 0 ? 1.f : 0.f;
    return kd > 0 ? kd / (kd + 0.5f) : 0.f;
}

int GlossyParts(const BSDF &b) {
    int n = 0;
    for (int i = 0; i < b.NumParts(); ++i)
        if (!b.Weight(i).IsBlack() && b.Part(i).HasGlossy()) ++n;
    return n;
}

// The density with which BSDF::SampleGlossy draws wi (local) for one part: the visible-normal
// density of the half vector over 4|wo·h|, times the reflection/transmission choice it makes.
float GlossyPdf(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    const float side = wo.z > 0 ? 1.f : -1.f;
    const Vec3f woUp(wo.x, wo.y, wo.z * side);
    Vec3f wiUp(wi.x, wi.y, wi.z * side);
    const bool transmit = wiUp.z < 0;
    if (transmit) {
        if (l.thinTransmit.IsBlack()) return 0;
        wiUp.z = -wiUp.z;  // the mirrored reflection
    } else if (l.ks.IsBlack()) {
        return 0;
    }
    Vec3f wh = woUp + wiUp;
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 0;
    wh = Normalize(wh);
    const float cosOH = Dot(woUp, wh);
    if (!(cosOH > 0)) return 0;
    float pR = 1;
    if (!l.thinTransmit.IsBlack()) {
        const float wR =
            l.ks.IsBlack() ? 0.f : (l.ks * l.glossyFresnel.Evaluate(cosOH)).Luminance();
        const float f = FrSchlick(cosOH, l.dielectricF0, l.dielectricF90).MaxComponent();
        const float wT = l.thinTransmit.Luminance() * (1 - f);
        if (!(wR + wT > 0)) return 0;
        pR = wR / (wR + wT);
    }
    const float pdfWh = TrowbridgeReitzVisiblePdf(woUp, wh, l.alphaX, l.alphaY);
    return (transmit ? 1 - pR : pR) * pdfWh / (4 * cosOH);
}

}  // namespace

float GltfPdf(const BSDF &b, const Vec3f &woW, const Vec3f &wiW) {
    const Vec3f wo = b.ToLocal(woW), wi = b.ToLocal(wiW);
    if (wo.z == 0) return 0;
    const float pD = DiffuseChoice(b);
    float pdf = 0;
    if (pD > 0 && wo.z * wi.z > 0) pdf += pD * std::abs(wi.z) * float(InvPi);
    const int n = GlossyParts(b);
    if (n > 0 && pD < 1) {
        float g = 0;
        for (int i = 0; i < b.NumParts(); ++i)
            if (!b.Weight(i).IsBlack() && b.Part(i).HasGlossy()) g += GlossyPdf(b.Part(i), wo, wi);
        pdf += (1 - pD) * g / float(n);
    }
    return pdf;
}

RGB GltfSampleF(const BSDF &b, const Vec3f &woW, Vec2f u, float uc, Vec3f *wiW, float *pdf) {
    *pdf = 0;
    const Vec3f wo = b.ToLocal(woW);
    if (wo.z == 0) return RGB(0);
    const float pD = DiffuseChoice(b);
    if (uc < pD) {
        // Cosine-weighted on wo's side (Malley's method).
        const float r = std::sqrt(u.x), phi = 2 * float(Pi) * u.y;
        Vec3f wi(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
        if (wo.z < 0) wi.z = -wi.z;
        *wiW = b.FromLocal(wi);
    } else {
        const int n = GlossyParts(b);
        if (n == 0) return RGB(0);
        // Reuse uc, rescaled, to pick the glossy part and then SampleGlossy's own choice.
        float v = (uc - pD) / (1 - pD) * float(n);
        const int k = std::min(int(v), n - 1);
        v -= float(k);
        int part = -1;
        for (int i = 0, seen = 0; i < b.NumParts(); ++i)
            if (!b.Weight(i).IsBlack() && b.Part(i).HasGlossy() && seen++ == k) part = i;
        RGB weight;
        if (part < 0 || !b.SampleGlossy(part, woW, u, std::min(v, 0.99999994f), wiW, &weight))
            return RGB(0);
    }
    *pdf = GltfPdf(b, woW, *wiW);
    if (!(*pdf > 0)) return RGB(0);
    return b.f(woW, *wiW);
}

}  // namespace prism
