#include "render/subsurface_material.h"

#include <fmt/format.h>

#include <cmath>

#include "render/materials.h"
#include "render/medium_presets.h"

namespace prism {

SubsurfaceMaterial::SubsurfaceMaterial(Params p)
    : p_(std::move(p)), table_(BeamDiffusionTable(p_.g, p_.eta)) {}

unsigned SubsurfaceMaterial::LobeNeeds() const {
    return MaterialModel::LobeNeeds() | p_.interface->LobeNeeds();
}

std::vector<const Texture *> SubsurfaceMaterial::Textures() const {
    std::vector<const Texture *> t = p_.interface->Textures();
    for (const TexturePtr &x : {p_.sigmaA, p_.sigmaS, p_.kd, p_.mfp})
        if (x) t.push_back(x.get());
    return t;
}

bool SubsurfaceMaterial::SubsurfaceAt(const TextureContext &tc, const Vec3f &po, const Vec3f &ns,
                                      const Vec3f &dpdu, SeparableBssrdf *out) const {
    RGB sigmaA, sigmaS;
    if (p_.kd) {
        const RGB mfp = p_.mfp->Evaluate(tc).Clamped(0.f) * p_.scale;  // as pbrt: scale × mfp
        SubsurfaceFromDiffuse(*table_, p_.kd->Evaluate(tc).Clamped(0.f, 1.f), mfp, &sigmaA,
                              &sigmaS);
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(sigmaA[c]) || !std::isfinite(sigmaS[c])) sigmaA[c] = sigmaS[c] = 0;
    } else {
        sigmaA = p_.sigmaA->Evaluate(tc).Clamped(0.f) * p_.scale;
        sigmaS = p_.sigmaS->Evaluate(tc).Clamped(0.f) * p_.scale;
    }
    *out = SeparableBssrdf(*table_, po, ns, dpdu, p_.eta, sigmaA, sigmaS);
    return true;
}

namespace {

// A float that must be finite and within [lo, hi]: a SceneError at the parameter otherwise.
float RangedValue(const MaterialParams &p, const char *name, float def, float lo, float hi) {
    const float v = p.Float(name, def);
    if (!(v >= lo && v <= hi) || !std::isfinite(v))
        throw SceneError(p.Loc(name), fmt::format("{} \"{}\" {:g} out of range ({:g} to {:g})",
                                                  p.Type(), name, v, lo, hi));
    return v;
}

}  // namespace

// Material "subsurface" (pbrt-v3 and pbrt-v4) and "kdsubsurface" (pbrt-v3; material_list.inc).
// Parameters:
//   sigma_a, sigma_s        spectrum texture  whole milk  (subsurface) absorption and
//                                                         scattering per unit length; pbrt-v4
//                                                         needs both or neither
//   name                    string            —           (subsurface) a measured medium
//                                                         (Medium "preset" names): its
//                                                         coefficients in mm^-1, and g 0
//   Kd                      spectrum texture  0.5         (kdsubsurface) the diffuse colour
//   reflectance             spectrum texture  —           (pbrt-v4 subsurface, without sigma_a,
//                                                         sigma_s and name) the same
//   mfp                     spectrum texture  0.5 (v4: 1) with Kd or reflectance: the mean free
//                                                         path
//   scale                   float             1           multiplies the coefficients, or the
//                                                         mean free path
//   g                       float             0           phase function asymmetry, -0.99 to
//                                                         0.99
//   eta                     float             1.33        the interface's index, 1 to 10
//   Kr, Kt                  spectrum texture  1           (pbrt-v3) the interface's reflectance
//                                                         and transmittance
//   roughness, uroughness,  float texture     0           a rough interface when non-zero
//   vroughness
//   remaproughness          bool              true
// An unknown measured medium is warned (pbrt-v3: the default is used) or an error (pbrt-v4).
std::shared_ptr<const MaterialModel> CreateSubsurfaceMaterial(const MaterialParams &p,
                                                              const FileLoc &) {
    SubsurfaceMaterial::Params s;
    const bool v4 = p.PbrtVersion() == 4;
    s.g = RangedValue(p, "g", 0.f, -0.99f, 0.99f);
    s.eta = RangedValue(p, "eta", 1.33f, 1.f, 10.f);
    s.scale = RangedValue(p, "scale", 1.f, 0.f, 1e30f);
    const std::string name = p.String("name", "");
    RGB sigmaA = WholeMilkSigmaA, sigmaS = WholeMilkSigmaS;
    bool measured = false;
    if (!name.empty()) {
        measured = MeasuredMedium(name, &sigmaA, &sigmaS);
        if (!measured && v4)
            throw SceneError(p.Loc("name"), "subsurface: unknown measured medium " + Quote(name));
        if (!measured)
            p.Warn(p.Loc("name"), "subsurface: unknown measured medium " + Quote(name) +
                                      "; using the default (whole milk)");
    }
    if (measured) {
        // The table's are reduced coefficients: isotropic scattering.
        if (s.g != 0)
            p.Warn(p.Loc("g"), "subsurface \"g\" is ignored: the measured medium " + Quote(name) +
                                   " gives reduced coefficients (g 0)");
        s.g = 0;
    }
    const bool sigmas = p.Has("sigma_a") || p.Has("sigma_s");
    if (v4 && sigmas && !(p.Has("sigma_a") && p.Has("sigma_s")))
        throw SceneError(p.Loc(p.Has("sigma_a") ? "sigma_a" : "sigma_s"),
                         "subsurface needs both \"sigma_a\" and \"sigma_s\", or neither");
    const char *colour = p.Type() == "kdsubsurface"                           ? "Kd"
                         : v4 && !measured && !sigmas && p.Has("reflectance") ? "reflectance"
                                                                              : nullptr;
    if (colour) {
        s.kd = p.SpectrumTex(colour, RGB(0.5f));
        s.mfp = p.SpectrumTex("mfp", RGB(v4 ? 1.f : 0.5f));
    } else {
        // pbrt-v3 lets sigma_a and sigma_s override a measured medium; pbrt-v4 reads them only
        // without one.
        const bool named = measured && v4;
        s.sigmaA =
            named ? std::make_shared<ConstantTexture>(sigmaA) : p.SpectrumTex("sigma_a", sigmaA);
        s.sigmaS =
            named ? std::make_shared<ConstantTexture>(sigmaS) : p.SpectrumTex("sigma_s", sigmaS);
    }
    TexturePtr kr = p.SpectrumTex("Kr", RGB(1)), kt = p.SpectrumTex("Kt", RGB(1));
    Roughness r = ReadUVRoughness(p, 0.f);
    if (v4) RemapRoughnessAsV4(r);
    s.interface = std::make_shared<GlassMaterial>(
        std::move(kr), std::move(kt), std::make_shared<ConstantTexture>(RGB(s.eta)), std::move(r));
    return std::make_shared<SubsurfaceMaterial>(std::move(s));
}

}  // namespace prism
