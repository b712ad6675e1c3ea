#include "render/hair_material.h"

#include <fmt/format.h>

#include <algorithm>

namespace prism {

namespace {

// A float texture that, when it is a constant, must lie in [lo, hi]: a SceneError at the
// parameter otherwise (varying textures are clamped at each hit).
TexturePtr RangedFloat(const MaterialParams &p, const char *name, float def, float lo, float hi) {
    TexturePtr t = p.FloatTex(name, def);
    if (const auto *c = dynamic_cast<const ConstantTexture *>(t.get())) {
        const float v = c->Value().r;
        if (!(v >= lo && v <= hi))
            throw SceneError(
                p.Loc(name),
                fmt::format("hair \"{}\" {:g} out of range ({:g} to {:g})", name, v, lo, hi));
    }
    return t;
}

}  // namespace

void HairMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    const float betaN = EvalFloat(p_.betaN, tc);
    RGB sigmaA;
    if (p_.sigmaA)
        sigmaA = p_.sigmaA->Evaluate(tc).Clamped(0.f);
    else if (p_.reflectance)
        sigmaA = HairLobe::SigmaAFromReflectance(p_.reflectance->Evaluate(tc), betaN);
    else
        sigmaA = HairLobe::SigmaAFromConcentration(EvalFloat(p_.eumelanin, tc),
                                                   EvalFloat(p_.pheomelanin, tc));
    // pbrt's h: -1 at one edge of the fibre as the ray sees it, 1 at the other.
    const float h = -1 + 2 * tc.uv.y;
    const float alpha = EvalFloat(p_.alpha, tc) * (p_.pbrtV3Tilt ? -1.f : 1.f);
    b.AddPart(weight).hair =
        HairLobe::Make(h, EvalFloat(p_.eta, tc), sigmaA, EvalFloat(p_.betaM, tc), betaN, alpha);
}

std::vector<const Texture *> HairMaterial::Textures() const {
    return {p_.sigmaA.get(), p_.reflectance.get(), p_.eumelanin.get(), p_.pheomelanin.get(),
            p_.eta.get(),    p_.betaM.get(),       p_.betaN.get(),     p_.alpha.get()};
}

// Material "hair" (pbrt-v3 and pbrt-v4; material_list.inc). Parameters:
//   sigma_a       spectrum texture  —     absorption inside the fibre, per unit radius
//   color         spectrum texture  —     (pbrt-v3; without sigma_a) the hair's colour, turned
//                                         into sigma_a by Chiang et al.'s fit
//   reflectance   spectrum texture  —     (pbrt-v4) the same as color
//   eumelanin     float texture     1.3   (without the above) pigment concentration
//   pheomelanin   float texture     0     (without the above) pigment concentration
//   eta           float texture     1.55  the fibre's index of refraction
//   beta_m        float texture     0.3   longitudinal roughness, 0 to 1
//   beta_n        float texture     0.3   azimuthal roughness, 0 to 1
//   alpha         float texture     2     the cuticle scales' tilt in degrees
// sigma_a wins over a colour, and a colour over melanin; what is overridden is warned. The tilt
// shifts the lobes as the file's own renderer does (pbrt-v3 and pbrt-v4 shift them opposite
// ways).
std::shared_ptr<const MaterialModel> CreateHairMaterial(const MaterialParams &p, const FileLoc &) {
    HairMaterial::Params h;
    const char *colour = p.Has("color") ? "color" : p.Has("reflectance") ? "reflectance" : nullptr;
    const bool melanin = p.Has("eumelanin") || p.Has("pheomelanin");
    const auto ignore = [&](const char *name, const char *by) {
        if (!p.Has(name)) return;
        p.Warn(p.Loc(name), "hair \"" + std::string(name) + "\" is ignored: \"" + by +
                                "\" gives the absorption");
        p.MarkUsed(name);
    };
    if (p.Has("sigma_a")) {
        h.sigmaA = p.SpectrumTex("sigma_a", RGB(0));
        if (colour) ignore(colour, "sigma_a");
        ignore("eumelanin", "sigma_a");
        ignore("pheomelanin", "sigma_a");
    } else if (colour) {
        h.reflectance = p.SpectrumTex(colour, RGB(0.5f));
        ignore("eumelanin", colour);
        ignore("pheomelanin", colour);
    } else {
        h.eumelanin = RangedFloat(p, "eumelanin", melanin ? 0.f : 1.3f, 0.f, 1e4f);
        h.pheomelanin = RangedFloat(p, "pheomelanin", 0.f, 0.f, 1e4f);
    }
    h.eta = RangedFloat(p, "eta", 1.55f, 1e-3f, 1e3f);
    h.betaM = RangedFloat(p, "beta_m", 0.3f, 0.f, 1.f);
    h.betaN = RangedFloat(p, "beta_n", 0.3f, 0.f, 1.f);
    h.alpha = RangedFloat(p, "alpha", 2.f, -90.f, 90.f);
    h.pbrtV3Tilt = p.PbrtVersion() == 3;
    return std::make_shared<HairMaterial>(std::move(h));
}

}  // namespace prism
