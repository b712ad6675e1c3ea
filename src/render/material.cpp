#include "render/material.h"

#include <cmath>

namespace prism {

static float EvalFloat(const TexturePtr &t, const TextureContext &tc) { return t->Evaluate(tc).r; }

static float MetalAlpha(const Material &m, const TexturePtr &r, const TextureContext &tc) {
    float v = EvalFloat(r, tc);
    return m.remapRoughness ? RoughnessToAlpha(v) : v;
}

bool Material::MayReflectSpecularly() const {
    switch (kind) {
    case Kind::Mirror:
    case Kind::Glass:
        return true;
    case Kind::Metal: {
        // Constant roughness lets us decide up front; textured roughness may go either way.
        auto *cu = dynamic_cast<const ConstantTexture *>(uRoughness.get());
        auto *cv = dynamic_cast<const ConstantTexture *>(vRoughness.get());
        if (!cu || !cv) return true;
        float au = remapRoughness ? RoughnessToAlpha(cu->Value().r) : cu->Value().r;
        float av = remapRoughness ? RoughnessToAlpha(cv->Value().r) : cv->Value().r;
        return std::max(au, av) <= SpecularMetalAlpha;
    }
    default:
        return false;
    }
}

BSDF Material::GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const {
    BSDF b;
    b.SetFrame(si.ns, si.dpdu, si.n);
    switch (kind) {
    case Kind::Matte: {
        b.kd = Kd->Evaluate(tc).Clamped(0.f);
        float sig = sigma ? EvalFloat(sigma, tc) : 0.f;
        if (sig > 0) {
            float s = float(Radians(sig));
            float s2 = s * s;
            b.orenNayar = true;
            b.orenNayarA = 1 - s2 / (2 * (s2 + 0.33f));
            b.orenNayarB = 0.45f * s2 / (s2 + 0.09f);
        }
        break;
    }
    case Kind::Plastic: {
        b.kd = Kd->Evaluate(tc).Clamped(0.f);
        b.ks = Ks->Evaluate(tc).Clamped(0.f);
        float r = EvalFloat(roughness, tc);
        float a = remapRoughness ? RoughnessToAlpha(r) : r;
        b.alphaX = b.alphaY = std::max(a, 1e-4f);
        // pbrt-v3 plastic.cpp constructs FresnelDielectric(1.5, 1): kept as is so highlights
        // match the reference renderer (it saturates toward grazing angles).
        b.glossyFresnel.kind = FresnelKind::Dielectric;
        b.glossyFresnel.etaI = 1.5f;
        b.glossyFresnel.etaT = 1.f;
        break;
    }
    case Kind::Mirror:
        b.kr = Kr->Evaluate(tc).Clamped(0.f);
        b.specularFresnel.kind = FresnelKind::None;
        break;
    case Kind::Glass: {
        b.kr = Kr->Evaluate(tc).Clamped(0.f);
        b.kt = Kt->Evaluate(tc).Clamped(0.f);
        b.eta = EvalFloat(index, tc);
        b.specularFresnel.kind = FresnelKind::Dielectric;
        b.specularFresnel.etaI = 1.f;
        b.specularFresnel.etaT = b.eta;
        break;
    }
    case Kind::Metal: {
        float au = MetalAlpha(*this, uRoughness, tc), av = MetalAlpha(*this, vRoughness, tc);
        Fresnel fr;
        fr.kind = FresnelKind::Conductor;
        fr.eta = metalEta;
        fr.k = metalK;
        if (std::max(au, av) <= SpecularMetalAlpha) {
            b.kr = RGB(1);
            b.specularFresnel = fr;
        } else {
            b.ks = RGB(1);
            b.alphaX = std::max(au, 1e-4f);
            b.alphaY = std::max(av, 1e-4f);
            b.glossyFresnel = fr;
        }
        break;
    }
    case Kind::None:
        break;
    }
    return b;
}

}  // namespace prism
