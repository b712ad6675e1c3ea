// BSDF::Sample_f and BSDF::Pdf: importance sampling of a whole BSDF for the path and
// directlighting integrators. The lobes are those of bsdf.cpp; the glossy directions are
// SampleGlossy's (shared with the distribution integrator), so only their density is added here.
#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/microfacet.h"

namespace prism {

namespace {

enum class Lobe {
    Diffuse,
    DiffuseTransmit,
    Glossy,
    SpecularReflect,
    SpecularTransmit,
    Layered,
    Hair,
    Fourier,
    Disney
};

struct Choice {
    int part;
    Lobe lobe;
    float weight;
};

// At most eight lobes per part.
struct Choices {
    Choice c[BSDF::MaxParts * 8];
    int n = 0;
    float total = 0;
    bool layered = false;  // a layered lobe is among them
    void Add(int part, Lobe lobe, float w) {
        if (!(w > 0)) return;
        c[n++] = {part, lobe, w};
        total += w;
        layered = layered || lobe == Lobe::Layered;
    }
};

// The lobes of `b` with their choice weights (albedo estimates) for the direction wo (local).
void Collect(const BSDF &b, const Vec3f &wo, bool withSpecular, Choices *ch) {
    for (int i = 0; i < b.NumParts(); ++i) {
        const RGB &w = b.Weight(i);
        if (w.IsBlack()) continue;
        const BxDFLobes &l = b.Part(i);
        // The layered lobe samples its own delta reflection (rejected when !withSpecular).
        if (l.layered.Active())
            ch->Add(i, Lobe::Layered, w.Average() * l.layered.AlbedoEstimate(wo));
        if (l.hair.Active()) ch->Add(i, Lobe::Hair, w.Average() * l.hair.AlbedoEstimate(wo));
        if (l.fourier.Active())
            ch->Add(i, Lobe::Fourier, w.Average() * l.fourier.AlbedoEstimate(wo));
        if (l.disney.Active()) ch->Add(i, Lobe::Disney, w.Average() * l.disney.AlbedoEstimate(wo));
        if (l.fresnelBlend) {
            // pbrt-v3 FresnelBlend::Sample_f: half the samples diffuse, half glossy.
            const float a = std::max(w.Average(), 1e-4f);
            ch->Add(i, Lobe::Diffuse, a);
            ch->Add(i, Lobe::Glossy, a);
        } else {
            if (!l.kd.IsBlack()) ch->Add(i, Lobe::Diffuse, (w * l.kd).Average());
            if (l.HasGlossy())
                ch->Add(i, Lobe::Glossy, (w * (l.ks + l.ksTransmit + l.thinTransmit)).Average());
        }
        if (l.subsurfaceEta > 0) ch->Add(i, Lobe::Diffuse, w.Average());
        if (!l.kdTransmit.IsBlack())
            ch->Add(i, Lobe::DiffuseTransmit, (w * l.kdTransmit).Average());
        if (!withSpecular) continue;
        // Delta reflection against transmission in proportion to the Fresnel term at wo.
        const float F = l.specularFresnel.kind == FresnelKind::Dielectric
                            ? FrDielectric(wo.z, 1.f, l.eta)
                            : l.specularFresnel.Evaluate(wo.z).Average();
        if (!l.kr.IsBlack()) ch->Add(i, Lobe::SpecularReflect, (w * l.kr).Average() * F);
        const bool fresnelTransmit =
            (l.specularFresnel.kind == FresnelKind::Dielectric && l.eta != 1) ||
            l.specularFresnel.kind == FresnelKind::ThinDielectric;
        if (!l.kt.IsBlack())
            ch->Add(i, Lobe::SpecularTransmit,
                    (w * l.kt).Average() * (fresnelTransmit ? 1 - F : 1.f));
    }
}

// The density with which SampleGlossy draws wi (local) for one part: the visible-normal density
// of the half vector, with the reflection / transmission choice SampleGlossy makes.
float GlossyPdf(const BxDFLobes &l, const Vec3f &wo, const Vec3f &wi) {
    const float side = wo.z > 0 ? 1.f : -1.f;
    const Vec3f woUp(wo.x, wo.y, wo.z * side);
    Vec3f wiUp(wi.x, wi.y, wi.z * side);
    const bool hasT = !l.ksTransmit.IsBlack(), hasThin = !l.thinTransmit.IsBlack();
    const bool transmit = wiUp.z < 0;
    const float eta = side > 0 ? l.glossyEta : 1 / l.glossyEta;
    Vec3f wh;
    if (!transmit || hasThin) {
        if (transmit) wiUp.z = -wiUp.z;  // thin-walled: the mirrored reflection
        wh = woUp + wiUp;
    } else if (hasT) {
        wh = woUp + wiUp * eta;
    } else {
        return 0;
    }
    if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 0;
    wh = Normalize(wh);
    if (wh.z < 0) wh = -wh;
    const float cosOH = Dot(woUp, wh);
    if (!(cosOH > 0)) return 0;
    float pR = 1;
    if (hasT) {
        float F = FrDielectric(cosOH * side, 1.f, l.glossyEta);
        float wR = (l.ks.IsBlack() ? 0.f : l.ks.Luminance() * F);
        float wT = l.ksTransmit.Luminance() * (1 - F);
        if (!(wR + wT > 0)) return 0;
        pR = wR / (wR + wT);
    } else if (hasThin) {
        float wR = l.ks.IsBlack() ? 0.f : (l.ks * l.glossyFresnel.Evaluate(cosOH)).Luminance();
        float wT = l.thinTransmit.Luminance() *
                   (1 - FrSchlick(cosOH, l.dielectricF0, l.dielectricF90).MaxComponent());
        if (!(wR + wT > 0)) return 0;
        pR = wR / (wR + wT);
    }
    const float pdfWh = TrowbridgeReitzVisiblePdf(woUp, wh, l.alphaX, l.alphaY);
    if (!transmit || hasThin) return (transmit ? 1 - pR : pR) * pdfWh / (4 * cosOH);
    if (pR >= 1 || Dot(wiUp, wh) >= 0) return 0;
    const float denom = cosOH + eta * Dot(wiUp, wh);
    if (denom == 0) return 0;
    return (1 - pR) * pdfWh * std::abs(eta * eta * Dot(wiUp, wh)) / (denom * denom);
}

// The density of one non-delta lobe (local directions).
float LobePdf(const BxDFLobes &l, Lobe lobe, const Vec3f &wo, const Vec3f &wi) {
    switch (lobe) {
        case Lobe::Diffuse:
            return wo.z * wi.z > 0 ? std::abs(wi.z) * float(InvPi) : 0.f;
        case Lobe::DiffuseTransmit:
            return wo.z * wi.z < 0 ? std::abs(wi.z) * float(InvPi) : 0.f;
        case Lobe::Glossy:
            return l.HasGlossy() ? GlossyPdf(l, wo, wi) : 0.f;
        case Lobe::Layered:
            return l.HasLayered() ? l.layered.Pdf(wo, wi) : 0.f;
        case Lobe::Hair:
            return l.hair.Active() ? l.hair.Pdf(wo, wi) : 0.f;
        case Lobe::Fourier:
            return l.fourier.Active() ? l.fourier.Pdf(wo, wi) : 0.f;
        case Lobe::Disney:
            return l.disney.Active() ? l.disney.Pdf(wo, wi) : 0.f;
        default:
            return 0;
    }
}

// withLayered false: the density of the other non-delta lobes only (still relative to every
// choice), which is what their samples are drawn from.
float MixturePdf(const BSDF &b, const Choices &ch, const Vec3f &wo, const Vec3f &wi,
                 bool withLayered = true) {
    float pdf = 0, total = 0;
    for (int k = 0; k < ch.n; ++k) {
        const Choice &c = ch.c[k];
        if (c.lobe == Lobe::SpecularReflect || c.lobe == Lobe::SpecularTransmit) continue;
        if (!withLayered && c.lobe == Lobe::Layered) continue;
        total += c.weight;
        pdf += c.weight * LobePdf(b.Part(c.part), c.lobe, wo, wi);
    }
    return total > 0 ? pdf / ch.total : 0.f;
}

// Sample_f's choice of a layered lobe.
bool SampleLayered(const BSDF &b, const Choices &ch, int part, const Vec3f &wo, Vec2f u, float uc,
                   float pChoice, bool withSpecular, BSDFSample *s) {
    LayeredLobe::Sample ls;
    if (!b.Part(part).layered.SampleF(wo, std::min(uc, 0x1.fffffep-1f), u, TransportMode::Radiance,
                                      &ls))
        return false;
    if (ls.specular && !withSpecular) return false;
    s->wi = b.FromLocal(ls.wi);
    s->specular = ls.specular;
    s->transmission = ls.transmission;
    // One lobe chosen with probability pChoice: its path's ratio over that probability. The
    // density for MIS is the mixture's (a delta path: the probability of taking it).
    s->weight = b.Weight(part) * ls.weight / pChoice;
    s->pdf = ls.specular ? pChoice * ls.pdf : MixturePdf(b, ch, wo, ls.wi);
    const float cosI = AbsDot(s->wi, b.ns);
    s->f = cosI > 0 ? s->weight * (s->pdf / cosI) : RGB(0);
    return s->pdf > 0 && std::isfinite(s->pdf) && !s->weight.IsBlack() && s->weight.IsFinite();
}

}  // namespace

float BSDF::Pdf(const Vec3f &woW, const Vec3f &wiW, bool withSpecular) const {
    const Vec3f wo = ToLocal(woW), wi = ToLocal(wiW);
    if (wo.z == 0) return 0;
    Choices ch;
    Collect(*this, wo, withSpecular, &ch);
    return MixturePdf(*this, ch, wo, wi);
}

bool BSDF::Sample_f(const Vec3f &woW, Vec2f u, float uc, bool withSpecular, BSDFSample *s) const {
    const Vec3f wo = ToLocal(woW);
    if (wo.z == 0) return false;
    Choices ch;
    Collect(*this, wo, withSpecular, &ch);
    if (ch.n == 0) return false;
    // The lobe: uc against the running sum of the weights.
    float target = std::min(uc, 0x1.fffffep-1f) * ch.total, sum = 0;
    int k = 0;
    while (k + 1 < ch.n && sum + ch.c[k].weight <= target) sum += ch.c[k++].weight;
    const Choice &c = ch.c[k];
    const float pChoice = c.weight / ch.total;
    const BxDFLobes &l = parts_[c.part];
    *s = BSDFSample();
    if (c.lobe == Lobe::SpecularReflect || c.lobe == Lobe::SpecularTransmit) {
        RGB w;
        const bool ok = c.lobe == Lobe::SpecularReflect
                            ? SampleSpecularReflection(c.part, woW, &s->wi, &w)
                            : SampleSpecularTransmission(c.part, woW, &s->wi, &w);
        if (!ok) return false;
        s->specular = true;
        s->transmission = c.lobe == Lobe::SpecularTransmit;
        s->pdf = pChoice;
        s->weight = w / pChoice;
        const float cosI = AbsDot(s->wi, ns);
        s->f = cosI > 0 ? w / cosI : RGB(0);
        if (s->transmission && l.eta != 1) s->eta = wo.z > 0 ? l.eta : 1 / l.eta;
        return !s->weight.IsBlack() && s->weight.IsFinite();
    }
    if (c.lobe == Lobe::Layered)
        return SampleLayered(*this, ch, c.part, wo, u, (target - sum) / c.weight, pChoice,
                             withSpecular, s);
    // uc again, rescaled within the chosen lobe's share, for the lobe's own choices (hair's
    // path, SampleGlossy's reflection or transmission).
    const float ucLobe = std::min((target - sum) / c.weight, 0x1.fffffep-1f);
    Vec3f wi;
    if (c.lobe == Lobe::Glossy) {
        RGB unused;
        if (!SampleGlossy(c.part, woW, u, ucLobe, &s->wi, &unused)) return false;
        wi = ToLocal(s->wi);
    } else {
        float unused;
        if (c.lobe == Lobe::Hair) {
            if (!l.hair.Sample(wo, ucLobe, u, &wi, &unused)) return false;
        } else if (c.lobe == Lobe::Fourier) {
            if (!l.fourier.Sample(wo, u, &wi, &unused)) return false;
        } else if (c.lobe == Lobe::Disney) {
            if (!l.disney.Sample(wo, ucLobe, u, &wi)) return false;
        } else {
            // Cosine-weighted (Malley's method) on wo's side, or the other side for
            // transmission.
            const float r = std::sqrt(u.x), phi = 2 * float(Pi) * u.y;
            wi = Vec3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
            if ((wo.z < 0) != (c.lobe == Lobe::DiffuseTransmit)) wi.z = -wi.z;
        }
        s->wi = FromLocal(wi);
    }
    s->pdf = MixturePdf(*this, ch, wo, wi);
    if (!(s->pdf > 0) || !std::isfinite(s->pdf)) return false;
    s->f = f(woW, s->wi);
    s->transmission = wo.z * wi.z < 0;
    if (!ch.layered) {
        s->weight = s->f * (AbsDot(s->wi, ns) / s->pdf);
    } else {
        // The layered lobes' samples estimate their own share (SampleLayered), so these
        // directions estimate the other lobes': their f over the density they are drawn from.
        const float pdfOthers = MixturePdf(*this, ch, wo, wi, false);
        if (!(pdfOthers > 0)) return false;
        const bool reflect = Dot(s->wi, ng) * Dot(woW, ng) > 0;
        RGB fOthers;
        for (int i = 0; i < n_; ++i)
            if (!weight_[i].IsBlack())
                fOthers += weight_[i] * parts_[i].fUnlayered(wo, wi, reflect);
        s->weight = fOthers * (AbsDot(s->wi, ns) / pdfOthers);
    }
    return !s->weight.IsBlack() && s->weight.IsFinite();
}

}  // namespace prism
