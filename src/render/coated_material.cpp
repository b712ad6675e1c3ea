#include "render/coated_material.h"

#include <algorithm>
#include <cmath>

#include "render/materials.h"

namespace prism {

namespace {

// pbrt-v4 TrowbridgeReitzDistribution::RoughnessToAlpha when remapping.
float Alpha(bool remap, float roughness) {
    const float r = std::max(roughness, 0.f);
    return remap ? std::sqrt(r) : r;
}
float Alpha(bool remap, const TexturePtr &t, const TextureContext &tc) {
    return Alpha(remap, EvalFloat(t, tc));
}

}  // namespace

void CoatedMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    LayeredLobe &l = b.AddPart(weight).layered;
    l.base = p_.base;
    l.eta = p_.eta;
    l.coatAlphaX = Alpha(p_.remap, p_.coatU, tc);
    l.coatAlphaY = Alpha(p_.remap, p_.coatV, tc);
    l.thickness = EvalFloat(p_.thickness, tc);
    l.albedo = p_.albedo->Evaluate(tc).Clamped(0.f, 1.f);
    l.g = std::clamp(EvalFloat(p_.g, tc), -1.f, 1.f);
    l.maxDepth = p_.maxDepth;
    l.nSamples = p_.nSamples;
    if (p_.base == LayeredLobe::Base::Diffuse) {
        l.reflectance = p_.reflectance->Evaluate(tc).Clamped(0.f, 1.f);
        return;
    }
    RGB eta, k;
    if (p_.conductorEta) {
        eta = p_.conductorEta->Evaluate(tc);
        k = p_.conductorK->Evaluate(tc);
    } else {
        eta = RGB(1);
        k = ConductorKFromReflectance(p_.reflectance->Evaluate(tc));
    }
    // The base sits under the coat: its index relative to the coat's.
    l.conductorEta = eta / p_.eta;
    l.conductorK = k / p_.eta;
    l.baseAlphaX = Alpha(p_.remap, p_.baseU, tc);
    l.baseAlphaY = Alpha(p_.remap, p_.baseV, tc);
}

// The coat is smooth (a delta reflection) when both its alphas are below 1e-3: possible unless
// a constant roughness rules it out.
bool CoatedMaterial::MayReflectSpecularly() const {
    const auto couldBeSmooth = [&](const TexturePtr &t) {
        const auto *c = dynamic_cast<const ConstantTexture *>(t.get());
        return !c || Alpha(p_.remap, c->Value().r) < LayeredLobe::SmoothAlpha;
    };
    return p_.eta != 1 && couldBeSmooth(p_.coatU) && couldBeSmooth(p_.coatV);
}

unsigned CoatedMaterial::LobeNeeds() const {
    const bool aniso = p_.coatU != p_.coatV || p_.baseU != p_.baseV;
    return MaterialModel::LobeNeeds() | (aniso ? NeedDpdu : NeedNone);
}

std::vector<const Texture *> CoatedMaterial::Textures() const {
    return {p_.reflectance.get(), p_.conductorEta.get(),
            p_.conductorK.get(),  p_.coatU.get(),
            p_.coatV.get(),       p_.baseU.get(),
            p_.baseV.get(),       p_.thickness.get(),
            p_.albedo.get(),      p_.g.get()};
}

namespace {

// What both coated materials share: the layer, the walk, the remapping.
CoatedMaterial::Params ReadLayer(const MaterialParams &p, const char *etaName) {
    CoatedMaterial::Params c;
    c.thickness = p.FloatTex("thickness", 0.01f);
    c.albedo = p.SpectrumTex("albedo", RGB(0));
    c.g = p.FloatTex("g", 0.f);
    c.remap = p.Bool("remaproughness", true);
    c.maxDepth = p.Int("maxdepth", 10);
    c.nSamples = p.Int("nsamples", 1);
    if (c.maxDepth < 1 || c.maxDepth > 1000)
        throw SceneError(p.Loc("maxdepth"),
                         "maxdepth " + std::to_string(c.maxDepth) + " out of range (1 to 1000)");
    if (c.nSamples < 1 || c.nSamples > 1000)
        throw SceneError(p.Loc("nsamples"),
                         "nsamples " + std::to_string(c.nSamples) + " out of range (1 to 1000)");
    c.eta = ReadConstantIndex(p, etaName);
    return c;
}

}  // namespace

// Material "coateddiffuse" (pbrt-v4; material_list.inc). Parameters:
//   reflectance             spectrum texture  0.5   the diffuse base
//   roughness               float texture     0     the coat's (0: smooth, a delta reflection)
//   uroughness, vroughness  float texture     —     override roughness
//   eta                     float (spectrum)  1.5   the coat's index of refraction
//   thickness               float texture     0.01  of the layer between coat and base
//   albedo                  spectrum texture  0     the layer's scattering albedo (0: absorbing)
//   g                       float texture     0     its Henyey–Greenstein asymmetry
//   maxdepth                integer           10    events per walk through the layers
//   nsamples                integer           1     walks per evaluation
//   remaproughness          bool              true  roughness r is alpha sqrt(r)
std::shared_ptr<const MaterialModel> CreateCoatedDiffuseMaterial(const MaterialParams &p,
                                                                 const FileLoc &) {
    CoatedMaterial::Params c = ReadLayer(p, "eta");
    c.base = LayeredLobe::Base::Diffuse;
    c.reflectance = p.SpectrumTex("reflectance", RGB(0.5f));
    const Roughness coat = ReadUVRoughness(p, 0.f);
    c.coatU = coat.u;
    c.coatV = coat.v;
    return std::make_shared<CoatedMaterial>(std::move(c));
}

// Material "coatedconductor" (pbrt-v4; material_list.inc). Parameters:
//   interface.roughness     float texture     0       the coat's
//   interface.uroughness, interface.vroughness  float texture  —  override it
//   interface.eta           float (spectrum)  1.5     the coat's index of refraction
//   conductor.eta, conductor.k  spectrum texture  copper  the base's complex index
//   reflectance             spectrum texture  —       (without conductor.eta) the base's
//                                                     normal-incidence reflectance
//   conductor.roughness     float texture     0       the base's
//   conductor.uroughness, conductor.vroughness  float texture  —  override it
//   thickness, albedo, g, maxdepth, nsamples, remaproughness   as coateddiffuse
std::shared_ptr<const MaterialModel> CreateCoatedConductorMaterial(const MaterialParams &p,
                                                                   const FileLoc &) {
    CoatedMaterial::Params c = ReadLayer(p, "interface.eta");
    c.base = LayeredLobe::Base::Conductor;
    if (p.Has("reflectance") && !p.Has("conductor.eta") && !p.Has("conductor.k")) {
        c.reflectance = p.SpectrumTex("reflectance", RGB(0.9f));
    } else {
        c.conductorEta = p.SpectrumTex("conductor.eta", CopperEta);
        c.conductorK = p.SpectrumTex("conductor.k", CopperK);
    }
    const Roughness coat = ReadUVRoughness(p, 0.f, "interface."),
                    base = ReadUVRoughness(p, 0.f, "conductor.");
    c.coatU = coat.u;
    c.coatV = coat.v;
    c.baseU = base.u;
    c.baseV = base.v;
    return std::make_shared<CoatedMaterial>(std::move(c));
}

}  // namespace prism
