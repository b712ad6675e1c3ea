#include "render/material.h"

#include <cmath>

namespace prism {

namespace {

float EvalFloat(const TexturePtr &t, const TextureContext &tc) { return t->Evaluate(tc).r; }

float Alpha(const Material &m, const TexturePtr &r, const TextureContext &tc) {
    float v = EvalFloat(r, tc);
    return m.remapRoughness ? RoughnessToAlpha(v) : v;
}

// False only when the texture is a constant black (or absent): the lobe can never appear.
bool MaybeNonBlack(const TexturePtr &t) {
    if (!t) return false;
    auto *c = dynamic_cast<const ConstantTexture *>(t.get());
    return !c || !c->Value().Clamped(0.f).IsBlack();
}

// True unless the texture is a constant of at least 1 in every channel.
bool MaybeBelowOne(const TexturePtr &t) {
    if (!t) return false;
    auto *c = dynamic_cast<const ConstantTexture *>(t.get());
    return !c || c->Value().r < 1 || c->Value().g < 1 || c->Value().b < 1;
}

Fresnel Dielectric(float etaI, float etaT) {
    Fresnel f;
    f.kind = FresnelKind::Dielectric;
    f.etaI = etaI;
    f.etaT = etaT;
    return f;
}

}  // namespace

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
        case Kind::Uber:
            return MaybeNonBlack(Kr);
        case Kind::Mix:
            return mix1->MayReflectSpecularly() || mix2->MayReflectSpecularly();
        case Kind::Gltf: {
            // Textured roughness may go either way; a smooth base or coat is a mirror.
            if (gltf.metallicRoughness) return true;
            float a = gltf.roughness * gltf.roughness;
            float ca = gltf.clearcoatRoughness * gltf.clearcoatRoughness;
            return a <= SpecularMetalAlpha || (gltf.clearcoat > 0 && ca <= SpecularMetalAlpha);
        }
        default:
            return false;
    }
}

bool Material::IsLambertian() const {
    if (kind != Kind::Matte) return false;
    if (!sigma) return true;
    auto *c = dynamic_cast<const ConstantTexture *>(sigma.get());
    return c && !(c->Value().r > 0);  // AddParts: Oren–Nayar only for sigma > 0
}

bool Material::MayTransmit() const {
    switch (kind) {
        case Kind::Glass:
            return true;
        case Kind::Uber:
            return MaybeNonBlack(Kt) || MaybeBelowOne(opacity);
        case Kind::Mix:
            // A "none" child lets part of the light straight through.
            return mix1->MayTransmit() || mix2->MayTransmit() || mix1->IsPassThrough() ||
                   mix2->IsPassThrough();
        case Kind::Gltf:
            return gltf.transmission > 0 && gltf.metallic < 1;
        default:
            return false;
    }
}

namespace {

bool Varies(const TexturePtr &t) { return t && !t->IsConstant(); }

// False when u and v roughness are one constant value (or both absent): the lobe is isotropic.
bool MaybeAnisotropic(const TexturePtr &u, const TexturePtr &v) {
    if (!u && !v) return false;
    if (u == v) return false;
    auto *cu = dynamic_cast<const ConstantTexture *>(u.get());
    auto *cv = dynamic_cast<const ConstantTexture *>(v.get());
    return !cu || !cv || cu->Value().r != cv->Value().r;
}

}  // namespace

unsigned Material::SurfaceNeeds() const {
    if (kind == Kind::None) return NeedNone;
    // Filtered textures read the (u, v) footprint, solved from dpdu and dpdv.
    const bool all = PerturbsShading() || TexturesUseDifferentials();
    return LobeNeeds() | (all ? unsigned(NeedAll) : unsigned(NeedNone));
}

bool Material::TexturesUseDifferentials() const {
    if (kind == Kind::None) return false;
    if (kind == Kind::Mix)
        return mix1->TexturesUseDifferentials() || mix2->TexturesUseDifferentials() ||
               (amount && amount->UsesDifferentials());
    for (const TexturePtr *t : {&Kd, &Ks, &Kr, &Kt, &sigma, &roughness, &uRoughness, &vRoughness,
                                &index, &opacity, &reflect, &transmit, &amount, &gltf.baseColor,
                                &gltf.metallicRoughness, &gltf.emissive, &gltf.occlusion})
        if (*t && (*t)->UsesDifferentials()) return true;
    return false;
}

unsigned Material::LobeNeeds() const {
    if (kind == Kind::None) return NeedNone;
    unsigned needs = NeedNone;
    if (kind == Kind::Mix) {
        needs |= mix1->SurfaceNeeds() | mix2->SurfaceNeeds();
        if (Varies(amount)) needs |= NeedUV;
        return needs;
    }
    for (const TexturePtr *t : {&Kd, &Ks, &Kr, &Kt, &sigma, &roughness, &uRoughness, &vRoughness,
                                &index, &opacity, &reflect, &transmit, &amount})
        if (Varies(*t)) needs |= NeedUV;
    if (kind == Kind::Gltf)
        for (const TexturePtr *t :
             {&gltf.baseColor, &gltf.metallicRoughness, &gltf.emissive, &gltf.occlusion})
            if (Varies(*t)) needs |= NeedUV;
    switch (kind) {
        case Kind::Metal:
        case Kind::Substrate:
        case Kind::Glass:
            if (MaybeAnisotropic(uRoughness, vRoughness)) needs |= NeedDpdu;
            break;
        case Kind::Uber:
            if (vRoughness && MaybeAnisotropic(uRoughness ? uRoughness : roughness, vRoughness))
                needs |= NeedDpdu;
            break;
        default:
            break;
    }
    return needs;
}

int Material::MaxParts() const {
    switch (kind) {
        case Kind::Mix:
            return mix1->MaxParts() + mix2->MaxParts();
        case Kind::Uber:
            return MaybeBelowOne(opacity) ? 2 : 1;
        case Kind::Gltf:
            return gltf.MaxParts();
        default:
            return 1;
    }
}

BSDF Material::GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const {
    BSDF b;
    b.SetFrame(si.ns, si.dpdu, si.n);
    AddParts(b, tc, RGB(1));
    return b;
}

void Material::Prepare() {
    differentials_ = TexturesUseDifferentials();
    fixed_ = false;
    fixedParts_.clear();
    if (kind == Kind::None || (LobeNeeds() & NeedUV)) return;
    // Every texture is constant: the parts do not depend on the hit.
    BSDF b;
    AddParts(b, TextureContext{}, RGB(1));
    for (int i = 0; i < b.NumParts(); ++i) fixedParts_.push_back({b.Weight(i), b.Part(i)});
    fixed_ = true;
}

void Material::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    if (fixed_) {
        for (const FixedPart &fp : fixedParts_) b.AddPart(weight * fp.weight, fp.lobes);
        return;
    }
    if (kind == Kind::Mix) {
        // pbrt-v3 MixMaterial: m1's BxDFs scaled by amount, m2's by 1 - amount (per channel).
        RGB s1 = amount->Evaluate(tc).Clamped(0.f, 1.f);
        RGB s2 = (RGB(1) - s1).Clamped(0.f, 1.f);
        if (!s1.IsBlack()) mix1->AddParts(b, tc, weight * s1);
        if (!s2.IsBlack()) mix2->AddParts(b, tc, weight * s2);
        return;
    }
    if (kind == Kind::Gltf) {
        gltf.AddParts(b, tc, weight);
        return;
    }
    if (kind == Kind::Uber && opacity) {
        // pbrt-v3 adds SpecularTransmission(1 - opacity, 1, 1): light passing straight through.
        RGB op = opacity->Evaluate(tc).Clamped(0.f, 1.f);
        RGB t = (RGB(1) - op).Clamped(0.f, 1.f);
        if (!t.IsBlack()) {
            BxDFLobes &pass = b.AddPart(weight);
            pass.kt = t;
            pass.eta = 1;
        }
    }
    BxDFLobes &l = b.AddPart(weight);
    switch (kind) {
        case Kind::Matte: {
            l.kd = Kd->Evaluate(tc).Clamped(0.f);
            float sig = sigma ? EvalFloat(sigma, tc) : 0.f;
            if (sig > 0) {
                float s = float(Radians(sig));
                float s2 = s * s;
                l.orenNayar = true;
                l.orenNayarA = 1 - s2 / (2 * (s2 + 0.33f));
                l.orenNayarB = 0.45f * s2 / (s2 + 0.09f);
            }
            break;
        }
        case Kind::Plastic: {
            l.kd = Kd->Evaluate(tc).Clamped(0.f);
            l.ks = Ks->Evaluate(tc).Clamped(0.f);
            float a = Alpha(*this, roughness, tc);
            l.alphaX = l.alphaY = std::max(a, 1e-4f);
            // pbrt-v3 plastic.cpp constructs FresnelDielectric(1.5, 1): kept as is so highlights
            // match the reference renderer (it saturates toward grazing angles).
            l.glossyFresnel = Dielectric(1.5f, 1.f);
            break;
        }
        case Kind::Mirror:
            l.kr = Kr->Evaluate(tc).Clamped(0.f);
            l.specularFresnel.kind = FresnelKind::None;
            break;
        case Kind::Glass: {
            l.kr = Kr->Evaluate(tc).Clamped(0.f);
            l.kt = Kt->Evaluate(tc).Clamped(0.f);
            l.eta = EvalFloat(index, tc);
            l.specularFresnel = Dielectric(1.f, l.eta);
            // pbrt-v3 GlassMaterial: smooth when both roughnesses are 0 (before remapping).
            float ru = uRoughness ? EvalFloat(uRoughness, tc) : 0.f;
            float rv = vRoughness ? EvalFloat(vRoughness, tc) : 0.f;
            if (ru != 0 || rv != 0) {
                l.roughAlphaX = std::max(remapRoughness ? RoughnessToAlpha(ru) : ru, 1e-4f);
                l.roughAlphaY = std::max(remapRoughness ? RoughnessToAlpha(rv) : rv, 1e-4f);
            }
            break;
        }
        case Kind::Metal: {
            float au = Alpha(*this, uRoughness, tc), av = Alpha(*this, vRoughness, tc);
            Fresnel fr;
            fr.kind = FresnelKind::Conductor;
            fr.eta = metalEta;
            fr.k = metalK;
            if (std::max(au, av) <= SpecularMetalAlpha) {
                l.kr = RGB(1);
                l.specularFresnel = fr;
            } else {
                l.ks = RGB(1);
                l.alphaX = std::max(au, 1e-4f);
                l.alphaY = std::max(av, 1e-4f);
                l.glossyFresnel = fr;
            }
            break;
        }
        case Kind::Uber: {
            // pbrt-v3 uber.cpp: every lobe is scaled by the opacity.
            RGB op = opacity ? opacity->Evaluate(tc).Clamped(0.f, 1.f) : RGB(1);
            float e = EvalFloat(index, tc);
            l.kd = op * Kd->Evaluate(tc).Clamped(0.f);
            l.ks = op * Ks->Evaluate(tc).Clamped(0.f);
            if (!l.ks.IsBlack()) {
                float au = Alpha(*this, uRoughness ? uRoughness : roughness, tc);
                float av = vRoughness ? Alpha(*this, vRoughness, tc) : au;
                l.alphaX = std::max(au, 1e-4f);
                l.alphaY = std::max(av, 1e-4f);
                l.glossyFresnel = Dielectric(1.f, e);
            }
            l.kr = op * Kr->Evaluate(tc).Clamped(0.f);
            l.kt = op * Kt->Evaluate(tc).Clamped(0.f);
            l.specularFresnel = Dielectric(1.f, e);
            l.eta = e;
            break;
        }
        case Kind::Substrate: {
            // pbrt-v3 substrate.cpp: one FresnelBlend lobe.
            RGB d = Kd->Evaluate(tc).Clamped(0.f), s = Ks->Evaluate(tc).Clamped(0.f);
            if (d.IsBlack() && s.IsBlack()) break;
            l.fresnelBlend = true;
            l.blendRd = d;
            l.blendRs = s;
            l.alphaX = std::max(Alpha(*this, uRoughness, tc), 1e-4f);
            l.alphaY = std::max(Alpha(*this, vRoughness, tc), 1e-4f);
            break;
        }
        case Kind::Translucent: {
            // pbrt-v3 translucent.cpp: Lambertian reflection r·Kd and transmission t·Kd, microfacet
            // reflection r·Ks and transmission t·Ks through an eta = 1.5 interface.
            const float eta = 1.5f;
            RGB r = reflect->Evaluate(tc).Clamped(0.f), t = transmit->Evaluate(tc).Clamped(0.f);
            if (r.IsBlack() && t.IsBlack()) break;
            RGB kd = Kd->Evaluate(tc).Clamped(0.f);
            l.kd = r * kd;
            l.kdTransmit = t * kd;
            RGB ks = Ks->Evaluate(tc).Clamped(0.f);
            if (!ks.IsBlack()) {
                float a = std::max(Alpha(*this, roughness, tc), 1e-4f);
                l.alphaX = l.alphaY = a;
                l.ks = r * ks;
                l.glossyFresnel = Dielectric(1.f, eta);
                l.ksTransmit = t * ks;
                l.glossyEta = eta;
            }
            break;
        }
        case Kind::None:
            // Only reached inside a mix: the "none" share of the light continues unchanged.
            l.kt = RGB(1);
            l.eta = 1;
            break;
        case Kind::Mix:
        case Kind::Gltf:
            break;
    }
}

}  // namespace prism
