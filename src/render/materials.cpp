#include "render/materials.h"

#include <cmath>

namespace prism {

namespace {

float Alpha(bool remap, const TexturePtr &r, const TextureContext &tc) {
    float v = EvalFloat(r, tc);
    return remap ? RoughnessToAlpha(v) : v;
}

const ConstantTexture *AsConstant(const TexturePtr &t) {
    return dynamic_cast<const ConstantTexture *>(t.get());
}

// True unless the texture is a constant of at least 1 in every channel.
bool MaybeBelowOne(const TexturePtr &t) {
    if (!t) return false;
    const ConstantTexture *c = AsConstant(t);
    return !c || c->Value().r < 1 || c->Value().g < 1 || c->Value().b < 1;
}

bool Varies(const TexturePtr &t) { return t && !t->IsConstant(); }

// False when u and v roughness are one constant value (or both absent): the lobe is isotropic.
bool MaybeAnisotropic(const TexturePtr &u, const TexturePtr &v) {
    if (!u && !v) return false;
    if (u == v) return false;
    const ConstantTexture *cu = AsConstant(u), *cv = AsConstant(v);
    return !cu || !cv || cu->Value().r != cv->Value().r;
}

TexturePtr Constant(RGB v) { return std::make_shared<ConstantTexture>(v); }

// pbrt-v3 "roughness" / "uroughness" / "vroughness" of uber.
void ReadUberRoughness(const MaterialParams &p, float def, UberMaterial::Params *u) {
    u->roughness = p.FloatTex("roughness", def);
    u->uRoughness = p.Has("uroughness") ? p.FloatTex("uroughness", def) : nullptr;
    u->vRoughness = p.Has("vroughness") ? p.FloatTex("vroughness", def) : nullptr;
    u->remap = p.Bool("remaproughness", true);
}

}  // namespace

Fresnel Dielectric(float etaI, float etaT) {
    Fresnel f;
    f.kind = FresnelKind::Dielectric;
    f.etaI = etaI;
    f.etaT = etaT;
    return f;
}

// False only when the (float) texture is absent or the constant 0.
bool MaybeNonZero(const TexturePtr &t) {
    if (!t) return false;
    const ConstantTexture *c = AsConstant(t);
    return !c || c->Value().r != 0;
}

// False only when the texture is a constant black (or absent): the lobe can never appear.
bool MaybeNonBlack(const TexturePtr &t) {
    if (!t) return false;
    const ConstantTexture *c = AsConstant(t);
    return !c || !c->Value().Clamped(0.f).IsBlack();
}

// pbrt-v4 remaps roughness r to alpha = sqrt(r) (v3 used a polynomial that never reaches 0):
// constant u/v roughness of a v4 material ("conductor", "dielectric") is converted here.
void RemapRoughnessAsV4(Roughness &r) {
    if (!r.remap || !r.u->IsConstant() || !r.v->IsConstant()) return;
    auto v4Alpha = [](TexturePtr &t) {
        if (const ConstantTexture *c = AsConstant(t))
            t = Constant(RGB(std::sqrt(std::max(0.f, c->Value().r))));
    };
    v4Alpha(r.u);
    v4Alpha(r.v);
    r.remap = false;
}

Roughness ReadUVRoughness(const MaterialParams &p, float def, const std::string &prefix) {
    const std::string ur = prefix + "uroughness", vr = prefix + "vroughness";
    TexturePtr rough = p.FloatTex((prefix + "roughness").c_str(), def);
    Roughness r;
    r.u = p.Has(ur.c_str()) ? p.FloatTex(ur.c_str(), 0.f) : rough;
    r.v = p.Has(vr.c_str()) ? p.FloatTex(vr.c_str(), 0.f) : rough;
    r.remap = p.Bool("remaproughness", true);
    return r;
}

RGB ConductorKFromReflectance(RGB r) {
    r = r.Clamped(0.f, 0.9999f);
    return RGB(2 * std::sqrt(r.r / (1 - r.r)), 2 * std::sqrt(r.g / (1 - r.g)),
               2 * std::sqrt(r.b / (1 - r.b)));
}

float ReadConstantIndex(const MaterialParams &p, const char *name) {
    const TexturePtr t = p.FloatTex(name, 1.5f);  // keeps the texture alive while c is read
    const ConstantTexture *c = AsConstant(t);
    if (!c)
        throw SceneError(p.Loc(name), p.Type() + " " + name + " must be a value, not a texture");
    const float eta = c->Value().r == 0 ? 1.f : c->Value().r;  // pbrt-v4: 0 means no interface
    if (!(eta > 0) || !std::isfinite(eta))
        throw SceneError(p.Loc(name), p.Type() + " " + name + " must be positive");
    return eta;
}

// ---- matte -------------------------------------------------------------------------------

void MatteMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    l.kd = Kd_->Evaluate(tc).Clamped(0.f);
    float sig = sigma_ ? EvalFloat(sigma_, tc) : 0.f;
    if (sig > 0) {
        float s = float(Radians(sig));
        float s2 = s * s;
        l.orenNayar = true;
        l.orenNayarA = 1 - s2 / (2 * (s2 + 0.33f));
        l.orenNayarB = 0.45f * s2 / (s2 + 0.09f);
    }
}

bool MatteMaterial::IsLambertian() const {
    if (!sigma_) return true;
    const ConstantTexture *c = AsConstant(sigma_);
    return c && !(c->Value().r > 0);  // AddParts: Oren–Nayar only for sigma > 0
}

// Material "matte" (pbrt-v4 "diffuse"; material_list.inc). Parameters:
//   Kd (v4: reflectance)  spectrum texture  0.5  diffuse reflectance
//   sigma                 float texture     0    Oren–Nayar roughness, degrees (0: Lambertian)
std::shared_ptr<const MaterialModel> CreateMatteMaterial(const MaterialParams &p, const FileLoc &) {
    TexturePtr kd = p.Has("reflectance") ? p.SpectrumTex("reflectance", RGB(0.5f))
                                         : p.SpectrumTex("Kd", RGB(0.5f));
    return std::make_shared<MatteMaterial>(std::move(kd), p.FloatTex("sigma", 0.f));
}

// ---- plastic -----------------------------------------------------------------------------

void PlasticMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    l.kd = Kd_->Evaluate(tc).Clamped(0.f);
    l.ks = Ks_->Evaluate(tc).Clamped(0.f);
    float a = Alpha(remap_, roughness_, tc);
    l.alphaX = l.alphaY = std::max(a, 1e-4f);
    // pbrt-v3 plastic.cpp constructs FresnelDielectric(1.5, 1): kept as is so highlights
    // match the reference renderer (it saturates toward grazing angles).
    l.glossyFresnel = Dielectric(1.5f, 1.f);
}

bool PlasticMaterial::MayReflectGlossily() const { return MaybeNonBlack(Ks_); }

// Material "plastic" (material_list.inc). Parameters:
//   Kd              spectrum texture  0.25  diffuse reflectance
//   Ks              spectrum texture  0.25  glossy reflectance
//   roughness       float texture     0.1
//   remaproughness  bool              true  roughness is remapped to a microfacet alpha
std::shared_ptr<const MaterialModel> CreatePlasticMaterial(const MaterialParams &p,
                                                           const FileLoc &) {
    TexturePtr kd = p.SpectrumTex("Kd", RGB(0.25f)), ks = p.SpectrumTex("Ks", RGB(0.25f));
    TexturePtr rough = p.FloatTex("roughness", 0.1f);
    return std::make_shared<PlasticMaterial>(std::move(kd), std::move(ks), std::move(rough),
                                             p.Bool("remaproughness", true));
}

// ---- mirror ------------------------------------------------------------------------------

void MirrorMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    l.kr = Kr_->Evaluate(tc).Clamped(0.f);
    l.specularFresnel.kind = FresnelKind::None;
}

// Material "mirror" (material_list.inc). Parameters:
//   Kr  spectrum texture  0.9  reflectance (no Fresnel)
std::shared_ptr<const MaterialModel> CreateMirrorMaterial(const MaterialParams &p,
                                                          const FileLoc &) {
    return std::make_shared<MirrorMaterial>(p.SpectrumTex("Kr", RGB(0.9f)));
}

// ---- glass -------------------------------------------------------------------------------

void GlassMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    l.kr = Kr_->Evaluate(tc).Clamped(0.f);
    l.kt = Kt_->Evaluate(tc).Clamped(0.f);
    l.eta = EvalFloat(index_, tc);
    l.specularFresnel = Dielectric(1.f, l.eta);
    // pbrt-v3 GlassMaterial: smooth when both roughnesses are 0 (before remapping).
    float ru = r_.u ? EvalFloat(r_.u, tc) : 0.f;
    float rv = r_.v ? EvalFloat(r_.v, tc) : 0.f;
    if (ru != 0 || rv != 0) {
        l.roughAlphaX = std::max(r_.remap ? RoughnessToAlpha(ru) : ru, 1e-4f);
        l.roughAlphaY = std::max(r_.remap ? RoughnessToAlpha(rv) : rv, 1e-4f);
    }
}

// Rough glass: either roughness may be non-zero (pbrt-v3 GlassMaterial).
bool GlassMaterial::MayReflectGlossily() const {
    return (MaybeNonZero(r_.u) || MaybeNonZero(r_.v)) && MaybeNonBlack(Kr_);
}

bool GlassMaterial::MayTransmitGlossily() const {
    return (MaybeNonZero(r_.u) || MaybeNonZero(r_.v)) && MaybeNonBlack(Kt_);
}

bool GlassMaterial::IsRoughGlass() const {
    const ConstantTexture *cu = AsConstant(r_.u), *cv = AsConstant(r_.v);
    return cu && cv && (cu->Value().r != 0 || cv->Value().r != 0);
}

unsigned GlassMaterial::LobeNeeds() const {
    return MaterialModel::LobeNeeds() | (MaybeAnisotropic(r_.u, r_.v) ? NeedDpdu : NeedNone);
}

// Material "glass" (pbrt-v4 "dielectric"; material_list.inc). Parameters:
//   Kr, Kt                  spectrum texture  1    reflectance and transmittance
//   index (eta)             float texture     1.5  index of refraction
//   roughness               float texture     0    (v4) both roughnesses
//   uroughness, vroughness  float texture     0    rough glass when either is non-zero
//   remaproughness          bool              true (dielectric: constant roughness as v4's)
// Whitted renders rough glass smooth (its delta lobes), and says so once per material.
std::shared_ptr<const MaterialModel> CreateGlassMaterial(const MaterialParams &p,
                                                         const FileLoc &loc) {
    TexturePtr kr = p.SpectrumTex("Kr", RGB(1)), kt = p.SpectrumTex("Kt", RGB(1));
    TexturePtr index = p.Has("eta") ? p.FloatTex("eta", 1.5f) : p.FloatTex("index", 1.5f);
    Roughness r = ReadUVRoughness(p, 0.f);
    bool isRough = false;
    for (const TexturePtr &t : {r.u, r.v}) {
        const ConstantTexture *c = AsConstant(t);
        if (!c || c->Value().r > 0) isRough = true;
    }
    if (p.Type() == "dielectric") RemapRoughnessAsV4(r);
    if (isRough && !p.RoughGlassRendered())
        p.Warn(loc,
               "rough glass is rendered as smooth glass by the Whitted integrator "
               "(Integrator \"distribution\" renders it rough)");
    return std::make_shared<GlassMaterial>(std::move(kr), std::move(kt), std::move(index),
                                           std::move(r));
}

// ---- thindielectric ----------------------------------------------------------------------

void ThinDielectricMaterial::AddParts(BSDF &b, const TextureContext &, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    l.specularFresnel.kind = FresnelKind::ThinDielectric;
    l.specularFresnel.etaT = eta_;
    l.kr = eta_ != 1 ? RGB(1) : RGB(0);
    l.kt = RGB(1);
    l.eta = 1;  // straight through: the slab's two refractions cancel
}

// Material "thindielectric" (pbrt-v4; material_list.inc). Parameters:
//   eta  float (spectrum)  1.5  the slab's index of refraction (a value: pbrt-v4 does not
//                               texture it)
std::shared_ptr<const MaterialModel> CreateThinDielectricMaterial(const MaterialParams &p,
                                                                  const FileLoc &) {
    return std::make_shared<ThinDielectricMaterial>(ReadConstantIndex(p, "eta"));
}

// ---- metal -------------------------------------------------------------------------------

void MetalMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    float au = Alpha(r_.remap, r_.u, tc), av = Alpha(r_.remap, r_.v, tc);
    Fresnel fr;
    fr.kind = FresnelKind::Conductor;
    fr.eta = eta_;
    fr.k = k_;
    if (std::max(au, av) <= SpecularMetalAlpha) {
        l.kr = RGB(1);
        l.specularFresnel = fr;
    } else {
        l.ks = RGB(1);
        l.alphaX = std::max(au, 1e-4f);
        l.alphaY = std::max(av, 1e-4f);
        l.glossyFresnel = fr;
    }
}

bool MetalMaterial::MayReflectSpecularly() const {
    // Constant roughness lets us decide up front; textured roughness may go either way.
    const ConstantTexture *cu = AsConstant(r_.u), *cv = AsConstant(r_.v);
    if (!cu || !cv) return true;
    float au = r_.remap ? RoughnessToAlpha(cu->Value().r) : cu->Value().r;
    float av = r_.remap ? RoughnessToAlpha(cv->Value().r) : cv->Value().r;
    return std::max(au, av) <= SpecularMetalAlpha;
}

bool MetalMaterial::MayReflectGlossily() const {
    const ConstantTexture *cu = AsConstant(r_.u), *cv = AsConstant(r_.v);
    if (!cu || !cv) return true;
    float au = r_.remap ? RoughnessToAlpha(cu->Value().r) : cu->Value().r;
    float av = r_.remap ? RoughnessToAlpha(cv->Value().r) : cv->Value().r;
    return std::max(au, av) > SpecularMetalAlpha;
}

unsigned MetalMaterial::LobeNeeds() const {
    return MaterialModel::LobeNeeds() | (MaybeAnisotropic(r_.u, r_.v) ? NeedDpdu : NeedNone);
}

// Material "metal" (pbrt-v4 "conductor"; material_list.inc). Parameters:
//   eta, k                  spectrum         copper  complex index of refraction (as RGB)
//   reflectance             spectrum         —       (v4, without eta and k) the normal-
//                                                    incidence reflectance: eta 1, k from it
//   roughness               float texture    0.01 (conductor: 0)
//   uroughness, vroughness  float texture    0       override roughness
//   remaproughness          bool             true    (conductor: constant roughness as v4's)
std::shared_ptr<const MaterialModel> CreateMetalMaterial(const MaterialParams &p, const FileLoc &) {
    RGB eta, k;
    if (p.Has("reflectance") && !p.Has("eta") && !p.Has("k")) {
        // pbrt-v4 conductor given its normal-incidence reflectance r.
        eta = RGB(1);
        k = ConductorKFromReflectance(p.Spectrum("reflectance", RGB(0.9f)));
    } else {
        // pbrt-v3's default is copper; these are its eta/k spectra reduced to RGB.
        eta = p.Spectrum("eta", CopperEta);
        k = p.Spectrum("k", CopperK);
    }
    // pbrt-v4's conductor defaults to a polished surface; v3's metal to roughness 0.01.
    const bool v4 = p.Type() == "conductor";
    Roughness r = ReadUVRoughness(p, v4 ? 0.f : 0.01f);
    if (v4) RemapRoughnessAsV4(r);
    return std::make_shared<MetalMaterial>(eta, k, std::move(r));
}

// ---- uber --------------------------------------------------------------------------------

void UberMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    if (p_.opacity) {
        // pbrt-v3 adds SpecularTransmission(1 - opacity, 1, 1): light passing straight through.
        RGB op = p_.opacity->Evaluate(tc).Clamped(0.f, 1.f);
        RGB t = (RGB(1) - op).Clamped(0.f, 1.f);
        if (!t.IsBlack()) {
            BxDFLobes &pass = b.AddPart(weight);
            pass.kt = t;
            pass.eta = 1;
        }
    }
    BxDFLobes &l = b.AddPart(weight);
    // pbrt-v3 uber.cpp: every lobe is scaled by the opacity.
    RGB op = p_.opacity ? p_.opacity->Evaluate(tc).Clamped(0.f, 1.f) : RGB(1);
    float e = EvalFloat(p_.index, tc);
    l.kd = op * p_.Kd->Evaluate(tc).Clamped(0.f);
    l.ks = op * p_.Ks->Evaluate(tc).Clamped(0.f);
    if (!l.ks.IsBlack()) {
        float au = Alpha(p_.remap, p_.uRoughness ? p_.uRoughness : p_.roughness, tc);
        float av = p_.vRoughness ? Alpha(p_.remap, p_.vRoughness, tc) : au;
        l.alphaX = std::max(au, 1e-4f);
        l.alphaY = std::max(av, 1e-4f);
        l.glossyFresnel = Dielectric(1.f, e);
    }
    l.kr = op * p_.Kr->Evaluate(tc).Clamped(0.f);
    l.kt = op * p_.Kt->Evaluate(tc).Clamped(0.f);
    l.specularFresnel = Dielectric(1.f, e);
    l.eta = e;
}

bool UberMaterial::MayReflectSpecularly() const { return MaybeNonBlack(p_.Kr); }
bool UberMaterial::MayTransmit() const { return MaybeNonBlack(p_.Kt) || MaybeBelowOne(p_.opacity); }
bool UberMaterial::MayReflectGlossily() const { return MaybeNonBlack(p_.Ks); }
int UberMaterial::MaxParts() const { return MaybeBelowOne(p_.opacity) ? 2 : 1; }

unsigned UberMaterial::LobeNeeds() const {
    const bool aniso =
        p_.vRoughness &&
        MaybeAnisotropic(p_.uRoughness ? p_.uRoughness : p_.roughness, p_.vRoughness);
    return MaterialModel::LobeNeeds() | (aniso ? NeedDpdu : NeedNone);
}

// Material "uber" (material_list.inc). Parameters:
//   Kd, Ks                  spectrum texture  0.25  diffuse and glossy reflectance
//   Kr, Kt                  spectrum texture  0     specular reflection and transmission
//   roughness               float texture     0.1   (uroughness/vroughness override it)
//   index (eta)             float texture     1.5
//   opacity                 spectrum texture  1     below 1: light passes straight through
//   remaproughness          bool              true
std::shared_ptr<const MaterialModel> CreateUberMaterial(const MaterialParams &p, const FileLoc &) {
    UberMaterial::Params u;
    u.Kd = p.SpectrumTex("Kd", RGB(0.25f));
    u.Ks = p.SpectrumTex("Ks", RGB(0.25f));
    u.Kr = p.SpectrumTex("Kr", RGB(0));
    u.Kt = p.SpectrumTex("Kt", RGB(0));
    ReadUberRoughness(p, 0.1f, &u);
    u.index = p.Has("eta") ? p.FloatTex("eta", 1.5f) : p.FloatTex("index", 1.5f);
    u.opacity = p.SpectrumTex("opacity", RGB(1));
    return std::make_shared<UberMaterial>(std::move(u));
}

// ---- substrate ---------------------------------------------------------------------------

void SubstrateMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    // pbrt-v3 substrate.cpp: one FresnelBlend lobe.
    RGB d = Kd_->Evaluate(tc).Clamped(0.f), s = Ks_->Evaluate(tc).Clamped(0.f);
    if (d.IsBlack() && s.IsBlack()) return;
    l.fresnelBlend = true;
    l.blendRd = d;
    l.blendRs = s;
    l.alphaX = std::max(Alpha(r_.remap, r_.u, tc), 1e-4f);
    l.alphaY = std::max(Alpha(r_.remap, r_.v, tc), 1e-4f);
}

bool SubstrateMaterial::MayReflectGlossily() const {
    return MaybeNonBlack(Kd_) || MaybeNonBlack(Ks_);
}

unsigned SubstrateMaterial::LobeNeeds() const {
    return MaterialModel::LobeNeeds() | (MaybeAnisotropic(r_.u, r_.v) ? NeedDpdu : NeedNone);
}

// Material "substrate" (material_list.inc). Parameters:
//   Kd, Ks                  spectrum texture  0.5  diffuse and glossy reflectance
//   uroughness, vroughness  float texture     0.1
//   remaproughness          bool              true
std::shared_ptr<const MaterialModel> CreateSubstrateMaterial(const MaterialParams &p,
                                                             const FileLoc &) {
    TexturePtr kd = p.SpectrumTex("Kd", RGB(0.5f)), ks = p.SpectrumTex("Ks", RGB(0.5f));
    Roughness r;
    r.u = p.FloatTex("uroughness", 0.1f);
    r.v = p.FloatTex("vroughness", 0.1f);
    r.remap = p.Bool("remaproughness", true);
    return std::make_shared<SubstrateMaterial>(std::move(kd), std::move(ks), std::move(r));
}

// ---- translucent -------------------------------------------------------------------------

void TranslucentMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &l = b.AddPart(weight);
    // pbrt-v3 translucent.cpp: Lambertian reflection r·Kd and transmission t·Kd, microfacet
    // reflection r·Ks and transmission t·Ks through an eta = 1.5 interface.
    const float eta = 1.5f;
    RGB r = reflect_->Evaluate(tc).Clamped(0.f), t = transmit_->Evaluate(tc).Clamped(0.f);
    if (r.IsBlack() && t.IsBlack()) return;
    RGB kd = Kd_->Evaluate(tc).Clamped(0.f);
    l.kd = r * kd;
    l.kdTransmit = t * kd;
    RGB ks = Ks_->Evaluate(tc).Clamped(0.f);
    if (!ks.IsBlack()) {
        float a = std::max(Alpha(remap_, roughness_, tc), 1e-4f);
        l.alphaX = l.alphaY = a;
        l.ks = r * ks;
        l.glossyFresnel = Dielectric(1.f, eta);
        l.ksTransmit = t * ks;
        l.glossyEta = eta;
    }
}

bool TranslucentMaterial::MayReflectGlossily() const {
    return MaybeNonBlack(Ks_) && MaybeNonBlack(reflect_);
}

bool TranslucentMaterial::MayTransmitGlossily() const {
    return MaybeNonBlack(Ks_) && MaybeNonBlack(transmit_);
}

// Material "translucent" (pbrt-v4 "diffusetransmission"; material_list.inc). Parameters:
//   Kd, Ks                      spectrum texture  0.25  diffuse and glossy colour
//   reflect, transmit           spectrum texture  0.5   the shares reflected and transmitted
//   roughness                   float texture     0.1
//   remaproughness              bool              true
//   reflectance, transmittance  spectrum texture  0.25  (v4 diffusetransmission) the shares
//                                                       reflected and transmitted, no glossy
//                                                       part
//   scale                       float             1     (v4 diffusetransmission) multiplies
//                                                       both
std::shared_ptr<const MaterialModel> CreateTranslucentMaterial(const MaterialParams &p,
                                                               const FileLoc &) {
    TexturePtr kd, ks, reflect, transmit;
    if (p.Type() == "diffusetransmission") {
        kd = Constant(RGB(p.Float("scale", 1.f)));
        ks = Constant(RGB(0));
        reflect = p.SpectrumTex("reflectance", RGB(0.25f));
        transmit = p.SpectrumTex("transmittance", RGB(0.25f));
    } else {
        kd = p.SpectrumTex("Kd", RGB(0.25f));
        ks = p.SpectrumTex("Ks", RGB(0.25f));
        reflect = p.SpectrumTex("reflect", RGB(0.5f));
        transmit = p.SpectrumTex("transmit", RGB(0.5f));
    }
    TexturePtr rough = p.FloatTex("roughness", 0.1f);
    return std::make_shared<TranslucentMaterial>(std::move(kd), std::move(ks), std::move(reflect),
                                                 std::move(transmit), std::move(rough),
                                                 p.Bool("remaproughness", true));
}

// ---- mix ---------------------------------------------------------------------------------

void MixMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    // pbrt-v3 MixMaterial: m1's BxDFs scaled by amount, m2's by 1 - amount (per channel).
    RGB s1 = amount_->Evaluate(tc).Clamped(0.f, 1.f);
    RGB s2 = (RGB(1) - s1).Clamped(0.f, 1.f);
    if (!s1.IsBlack()) m1_->AddParts(b, tc, weight * s1);
    if (!s2.IsBlack()) m2_->AddParts(b, tc, weight * s2);
}

bool MixMaterial::MayReflectSpecularly() const {
    return m1_->MayReflectSpecularly() || m2_->MayReflectSpecularly();
}

bool MixMaterial::MayTransmit() const {
    // A "none" child lets part of the light straight through.
    return m1_->MayTransmit() || m2_->MayTransmit() || m1_->IsPassThrough() || m2_->IsPassThrough();
}

bool MixMaterial::MayReflectGlossily() const {
    return m1_->MayReflectGlossily() || m2_->MayReflectGlossily();
}

bool MixMaterial::MayTransmitGlossily() const {
    return m1_->MayTransmitGlossily() || m2_->MayTransmitGlossily();
}

int MixMaterial::MaxParts() const { return m1_->MaxParts() + m2_->MaxParts(); }

unsigned MixMaterial::LobeNeeds() const {
    return m1_->TextureNeeds() | m2_->TextureNeeds() | (Varies(amount_) ? NeedUV : NeedNone);
}

unsigned MixMaterial::GeometryNeeds() const { return m1_->GeometryNeeds() | m2_->GeometryNeeds(); }

bool MixMaterial::TexturesUseDifferentials() const {
    return m1_->TexturesUseDifferentials() || m2_->TexturesUseDifferentials() ||
           (amount_ && amount_->UsesDifferentials());
}

// Material "mix" (material_list.inc). Parameters:
//   amount                          spectrum (v4: float) texture  0.5  namedmaterial1's share
//   namedmaterial1, namedmaterial2  string                             (v3) the two materials
//   materials                       string[2]                          (v4) [m2 m1]
// Nested mixes deeper than BSDF::MaxParts, or more parts than it, are located errors.
std::shared_ptr<const MaterialModel> CreateMixMaterial(const MaterialParams &p,
                                                       const FileLoc &loc) {
    // Each nesting level adds at least one BSDF part, so deeper nests than this are over the
    // limit anyway; stopping here also bounds the recursion.
    if (p.MixDepth() >= BSDF::MaxParts)
        throw SceneError(loc, "mix materials are nested too deeply (more than " +
                                  std::to_string(BSDF::MaxParts) + " levels)");
    TexturePtr amount = p.AnyTex("amount", RGB(0.5f));
    std::string n1, n2;
    FileLoc loc1 = loc, loc2 = loc;
    if (p.Has("materials")) {
        // pbrt-v4: "string materials" [a b], amount selects b (= v3's namedmaterial1).
        const std::vector<std::string> names = p.Strings("materials");
        if (names.size() != 2)
            throw SceneError(p.Loc("materials"),
                             "mix \"materials\" must name exactly two materials");
        n1 = names[1];
        n2 = names[0];
        loc1 = loc2 = p.Loc("materials");
    } else {
        n1 = p.String("namedmaterial1", "");
        n2 = p.String("namedmaterial2", "");
        loc1 = p.Loc("namedmaterial1");
        loc2 = p.Loc("namedmaterial2");
    }
    std::shared_ptr<const Material> m1 = p.NamedMaterial(n1, loc1);
    std::shared_ptr<const Material> m2 = p.NamedMaterial(n2, loc2);
    auto mix = std::make_shared<MixMaterial>(std::move(m1), std::move(m2), std::move(amount));
    if (mix->MaxParts() > BSDF::MaxParts)
        throw SceneError(loc, "mix material combines more than " + std::to_string(BSDF::MaxParts) +
                                  " materials");
    return mix;
}

// ---- interface ---------------------------------------------------------------------------

void InterfaceMaterial::AddParts(BSDF &b, const TextureContext &, const RGB &weight) const {
    // Only reached inside a mix: the "none" share of the light continues unchanged.
    BxDFLobes &l = b.AddPart(weight);
    l.kt = RGB(1);
    l.eta = 1;
}

// Material "" / "none" / "interface" (material_list.inc): no parameters.
std::shared_ptr<const MaterialModel> CreateInterfaceMaterial(const MaterialParams &,
                                                             const FileLoc &) {
    return std::make_shared<InterfaceMaterial>();
}

}  // namespace prism
