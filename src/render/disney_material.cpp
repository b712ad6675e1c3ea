#include "render/disney_material.h"

#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/bssrdf.h"
#include "render/materials.h"

namespace prism {

namespace {

// The scattering distance at a hit (black: none). pbrt-v3's Disney BSSRDF uses a fifth of it.
RGB ScatterDistance(const TexturePtr &sd, const TextureContext &tc) {
    return sd ? sd->Evaluate(tc).Clamped(0.f) * 0.2f : RGB(0);
}

}  // namespace

bool DisneyMaterial::HasSubsurface() const { return !p_.thin && MaybeNonBlack(p_.scatterDistance); }

bool DisneyMaterial::SubsurfaceAt(const TextureContext &tc, const Vec3f &po, const Vec3f &ns,
                                  const Vec3f &dpdu, SeparableBssrdf *out) const {
    if (p_.thin) return false;
    const RGB d = ScatterDistance(p_.scatterDistance, tc);
    if (d.IsBlack()) return false;
    const float diffuseWeight =
        (1 - EvalFloat(p_.metallic, tc)) * (1 - EvalFloat(p_.specTrans, tc));
    *out = SeparableBssrdf::Disney(po, ns, dpdu, EvalFloat(p_.eta, tc),
                                   p_.color->Evaluate(tc).Clamped(0.f) * diffuseWeight, d);
    return true;
}

void DisneyMaterial::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    BxDFLobes &part = b.AddPart(weight);
    DisneyLobe &l = part.disney;
    l.active = true;
    const RGB c = p_.color->Evaluate(tc).Clamped(0.f);
    const float metallic = EvalFloat(p_.metallic, tc), e = EvalFloat(p_.eta, tc);
    const float strans = EvalFloat(p_.specTrans, tc), rough = EvalFloat(p_.roughness, tc);
    const float diffuseWeight = (1 - metallic) * (1 - strans);
    const float dt = EvalFloat(p_.diffTrans, tc) / 2;  // thin: the share of diffuse transmitted
    const float lum = c.Luminance();
    const RGB tint = lum > 0 ? c / lum : RGB(1);
    l.roughness = rough;
    if (diffuseWeight > 0) {
        if (p_.thin) {
            const float flat = EvalFloat(p_.flatness, tc);
            l.diffuse = c * (diffuseWeight * (1 - flat) * (1 - dt));
            l.fakeSS = c * (diffuseWeight * flat * (1 - dt));
        } else if (ScatterDistance(p_.scatterDistance, tc).IsBlack()) {
            l.diffuse = c * diffuseWeight;
        } else {
            // The diffuse light enters the BSSRDF through a smooth dielectric transmission.
            part.kt = RGB(1);
            part.eta = e;
            part.specularFresnel = Dielectric(1, e);
        }
        l.retro = c * diffuseWeight;
        const float sheen = EvalFloat(p_.sheen, tc);
        if (sheen > 0) {
            const float st = EvalFloat(p_.sheenTint, tc);
            l.sheen = (RGB(1) * (1 - st) + tint * st) * (diffuseWeight * sheen);
        }
    }
    const float aspect = std::sqrt(std::max(0.f, 1 - EvalFloat(p_.anisotropic, tc) * 0.9f));
    l.ax = std::max(0.001f, rough * rough / aspect);
    l.ay = std::max(0.001f, rough * rough * aspect);
    const float specTint = EvalFloat(p_.specularTint, tc);
    const float r0 = (e - 1) * (e - 1) / ((e + 1) * (e + 1));
    const RGB dielectric = (RGB(1) * (1 - specTint) + tint * specTint) * r0;
    l.cspec0 = dielectric * (1 - metallic) + c * metallic;
    l.metallic = metallic;
    l.eta = e;
    l.clearcoat = std::max(0.f, EvalFloat(p_.clearcoat, tc));
    l.clearcoatGloss = EvalFloat(p_.clearcoatGloss, tc);
    l.thin = p_.thin;
    if (strans > 0) {
        // Scaled by sqrt(colour): two refractions give the colour back.
        l.transmit = RGB(std::sqrt(c.r), std::sqrt(c.g), std::sqrt(c.b)) * strans;
        if (p_.thin) {
            // Roughness scaled by the index (Burley 2015, figure 15).
            const float rs = (0.65f * e - 0.35f) * rough;
            l.tax = std::max(0.001f, rs * rs / aspect);
            l.tay = std::max(0.001f, rs * rs * aspect);
        } else {
            l.tax = l.ax;
            l.tay = l.ay;
        }
    }
    if (p_.thin) l.diffuseTransmit = c * dt;
}

unsigned DisneyMaterial::LobeNeeds() const {
    return MaterialModel::LobeNeeds() | (MaybeNonZero(p_.anisotropic) ? NeedDpdu : NeedNone);
}

std::vector<const Texture *> DisneyMaterial::Textures() const {
    return {p_.scatterDistance.get(), p_.color.get(),
            p_.metallic.get(),        p_.eta.get(),
            p_.roughness.get(),       p_.specularTint.get(),
            p_.anisotropic.get(),     p_.sheen.get(),
            p_.sheenTint.get(),       p_.clearcoat.get(),
            p_.clearcoatGloss.get(),  p_.specTrans.get(),
            p_.flatness.get(),        p_.diffTrans.get()};
}

// Material "disney" (pbrt-v3; material_list.inc). Parameters:
//   color            spectrum texture  0.5    base colour
//   metallic         float texture     0      0 dielectric to 1 metal
//   eta              float texture     1.5    index of refraction
//   roughness        float texture     0.5
//   speculartint     float texture     0      tints the dielectric specular by the colour's hue
//   anisotropic      float texture     0
//   sheen            float texture     0      grazing retro-reflection
//   sheentint        float texture     0.5
//   clearcoat        float texture     0      a second, GTR1, specular lobe
//   clearcoatgloss   float texture     1
//   spectrans        float texture     0      microfacet transmission
//   thin             bool              false  thin: fake subsurface, diffuse transmission
//   flatness         float texture     0      (thin)
//   difftrans        float texture     1      (thin) twice the diffuse share transmitted
//   scatterdistance  spectrum texture  0      Burley's subsurface scattering distance
std::shared_ptr<const MaterialModel> CreateDisneyMaterial(const MaterialParams &p,
                                                          const FileLoc &) {
    DisneyMaterial::Params d;
    d.color = p.SpectrumTex("color", RGB(0.5f));
    d.metallic = p.FloatTex("metallic", 0.f);
    d.eta = p.FloatTex("eta", 1.5f);
    d.roughness = p.FloatTex("roughness", 0.5f);
    d.specularTint = p.FloatTex("speculartint", 0.f);
    d.anisotropic = p.FloatTex("anisotropic", 0.f);
    d.sheen = p.FloatTex("sheen", 0.f);
    d.sheenTint = p.FloatTex("sheentint", 0.5f);
    d.clearcoat = p.FloatTex("clearcoat", 0.f);
    d.clearcoatGloss = p.FloatTex("clearcoatgloss", 1.f);
    d.specTrans = p.FloatTex("spectrans", 0.f);
    d.flatness = p.FloatTex("flatness", 0.f);
    d.diffTrans = p.FloatTex("difftrans", 1.f);
    d.thin = p.Bool("thin", false);
    if (p.Has("scatterdistance")) d.scatterDistance = p.SpectrumTex("scatterdistance", RGB(0));
    return std::make_shared<DisneyMaterial>(std::move(d));
}

}  // namespace prism
