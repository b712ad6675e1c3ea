// Materials. A Material is what a hit reads: its model (one class per pbrt material type,
// render/materials.h and render/gltf_material.h, made by a Create beside each class and listed
// in material_list.inc) plus what every material may carry — a bump or normal map — and the
// lobes of models whose textures are all constant, built once. Each hit turns a material into
// a BSDF value; docs/MATERIALS.md says what each model does.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "geometry/interaction.h"
#include "render/bsdf.h"
#include "render/texture.h"

namespace prism {

class Material;
class SeparableBssrdf;

// Roughness (after remapping) up to which a metal is treated as a polished conductor: a delta
// reflection that recursion follows. pbrt-v4's threshold (TrowbridgeReitzDistribution::
// EffectivelySmooth); above it a microfacet lobe, however sharp, as pbrt-v3 and pbrt-v4 render
// it (pbrt-v3's remapped roughness never comes below 0.047).
inline constexpr float SpecularMetalAlpha = 1e-3f;

// One material model: the lobes it adds at a hit, and what can be known of them before
// rendering (the effects a scene calls for, the surface data a hit reads).
class MaterialModel {
  public:
    virtual ~MaterialModel() = default;
    // Adds the model's lobes to `bsdf`, scaled by `weight`.
    virtual void AddParts(BSDF &bsdf, const TextureContext &tc, const RGB &weight) const = 0;
    // An invisible interface ("none"): rays continue through it; inside a mix, the light of its
    // share passes unchanged.
    virtual bool IsPassThrough() const { return false; }
    // Lambertian (f = kd/π): kernels without KernelBsdf (render/kernel.h) shade it from
    // LambertianKd without building a BSDF.
    virtual bool IsLambertian() const { return false; }
    virtual RGB LambertianKd(const TextureContext &tc) const { return RGB(0); }
    virtual bool MayReflectSpecularly() const { return false; }
    virtual bool MayTransmit() const { return false; }
    virtual bool MayReflectGlossily() const { return false; }
    virtual bool MayTransmitGlossily() const { return false; }
    // Glass whose roughness is a non-zero constant: glossy (not specular) for the integrators
    // that render rough glass rough.
    virtual bool IsRoughGlass() const { return false; }
    // BSDF parts it can add (mixes add their children's; uber's opacity adds one).
    virtual int MaxParts() const { return 1; }
    // The surface data its lobes read (SurfaceNeeds) through textures: by default uv when a
    // texture is not constant.
    virtual unsigned LobeNeeds() const;
    // The surface data its lobes read themselves, not through a texture (hair: where across
    // the fibre, uv's v, and the fibre's direction, dpdu).
    virtual unsigned GeometryNeeds() const { return NeedNone; }
    // Whether a texture it reads filters over the ray's footprint.
    virtual bool TexturesUseDifferentials() const;
    // Whether light refracted into it may leave elsewhere on the same material (subsurface,
    // kdsubsurface, disney with a scattering distance; render/subsurface.h).
    virtual bool HasSubsurface() const { return false; }
    // The BSSRDF where light enters at po (shading normal ns, tangent dpdu; texture context
    // tc) in *out; false where there is none.
    virtual bool SubsurfaceAt(const TextureContext &tc, const Vec3f &po, const Vec3f &ns,
                              const Vec3f &dpdu, SeparableBssrdf *out) const {
        return false;
    }
    // Radiance the surface emits itself (a "gltf" material's emission), or null.
    virtual const Texture *Emission() const { return nullptr; }
    // glTF occlusion: the factor that scales the environment's light and indirect paths.
    virtual float AmbientOcclusion(const TextureContext &) const { return 1; }
    // The textures it reads (for the defaults above).
    virtual std::vector<const Texture *> Textures() const { return {}; }
};

class Material {
  public:
    Material() = default;
    Material(std::shared_ptr<const MaterialModel> model, std::string typeName)
        : typeName(std::move(typeName)),
          model_(std::move(model)),
          subsurface_(model_->HasSubsurface()) {}

    std::string typeName;  // as written in the scene, for `prism info`
    const MaterialModel &Model() const { return *model_; }
    template <class M>
    const M *ModelAs() const {
        return dynamic_cast<const M *>(model_.get());
    }

    // Radiance the surface emits itself (a "gltf" material's "emissive"/"emissivemap" in a
    // .pbrt file; the glTF reader turns emission into area lights instead): seen by camera
    // rays and by the rays that Whitted and glossy recursion trace, but not light-sampled.
    bool HasEmission() const { return model_->Emission() != nullptr; }
    RGB Emitted(const TextureContext &tc) const {
        return model_->Emission()->Evaluate(tc).Clamped(0.f);
    }
    // glTF occlusionTexture: the factor 1 + strength × (occlusion.r - 1) by which the light
    // that reaches the hit from the environment (infinite lights: an --env map, the studio
    // rig's uniform environment) and along indirect paths (specular and glossy rays, and a
    // path integrator's bounces) is scaled, as the glTF sample viewer scales its image-based
    // light; 1 for every other material. Direct light from point, spot, distant and area
    // lights is not scaled: Prism traces their shadows. docs/MATERIALS.md.
    float AmbientOcclusion(const TextureContext &tc) const { return model_->AmbientOcclusion(tc); }
    // Shading-normal perturbation (render/bump.cpp), applied to the hit before it is shaded:
    // pbrt-v3's "bumpmap" (a float displacement texture), or a tangent-space normal map (glTF
    // normalTexture, OBJ norm, pbrt-v4 "normalmap") whose x and y are scaled by normalScale.
    TexturePtr bump, normalMap;
    float normalScale = 1;
    int normalMapUVSet = 0;  // the uv set the normal map reads (tangents are made from it)
    bool PerturbsShading() const { return bump || normalMap; }
    // Moves si.ns (and dpdu/dpdv) as the bump or normal map says; needs uv and dpdu/dpdv.
    void PerturbShading(SurfaceInteraction &si) const;

    bool IsPassThrough() const { return model_->IsPassThrough(); }
    // MaterialModel::HasSubsurface, cached: the path integrators ask at every hit.
    bool HasSubsurface() const { return subsurface_; }
    bool IsLambertian() const { return model_->IsLambertian(); }
    // kd as GetBSDF gives it (its one part, of weight 1); only for IsLambertian materials.
    RGB LambertianKd(const TextureContext &tc) const {
        return fixed_ ? fixedParts_[0].lobes.kd : model_->LambertianKd(tc);
    }
    bool MayTransmit() const { return model_->MayTransmit(); }
    bool MayReflectSpecularly() const { return model_->MayReflectSpecularly(); }
    bool MayReflectGlossily() const { return model_->MayReflectGlossily(); }
    bool MayTransmitGlossily() const { return model_->MayTransmitGlossily(); }
    int MaxParts() const { return model_->MaxParts(); }
    // The surface data a hit on this material reads (SurfaceNeeds), decided from its textures:
    // uv when any texture is not constant, dpdu when a glossy lobe may be anisotropic; and what
    // the model reads of the surface itself (MaterialModel::GeometryNeeds).
    unsigned SurfaceNeeds() const { return TextureNeeds() | model_->GeometryNeeds(); }
    // What of that its textures, bump and normal maps read (the "textures" effect).
    unsigned TextureNeeds() const;
    unsigned GeometryNeeds() const { return model_->GeometryNeeds(); }
    // Whether a texture of the material filters over the ray's footprint (Texture::
    // UsesDifferentials), so hits on it compute TextureContext's derivatives. UsesDifferentials
    // is the value Prepare cached.
    bool TexturesUseDifferentials() const { return model_->TexturesUseDifferentials(); }
    bool UsesDifferentials() const { return differentials_; }
    BSDF GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const;
    // Adds this material's lobes to `bsdf`, scaled by `weight` (used by mix).
    void AddParts(BSDF &bsdf, const TextureContext &tc, const RGB &weight) const;
    // Called once the parameters are final (assembly/materials.cpp): a material whose textures
    // are all constant gets its lobes built here once, and AddParts then copies them instead
    // of evaluating textures and remapping roughness at every hit.
    void Prepare();

  private:
    struct FixedPart {
        RGB weight;
        BxDFLobes lobes;
    };
    std::shared_ptr<const MaterialModel> model_;
    bool subsurface_ = false;
    std::vector<FixedPart> fixedParts_;
    bool fixed_ = false;
    bool differentials_ = false;
};

// A Material directive's parameters as a model's Create reads them: core/params.h's plus
// texture-valued parameters (a named texture or a value) and spectra. A Shape's own
// parameters override its material's (pbrt-v3 GetMaterialForShape).
class MaterialParams : public Params {
  public:
    virtual const std::string &Type() const = 0;  // as written ("conductor", "metal", ...)
    virtual TexturePtr SpectrumTex(const char *name, RGB def) const = 0;
    virtual TexturePtr FloatTex(const char *name, float def) const = 0;
    // A spectrum-or-float texture (mix "amount": a spectrum in pbrt-v3, a float in v4).
    virtual TexturePtr AnyTex(const char *name, RGB def) const = 0;
    virtual RGB Spectrum(const char *name, RGB def) const = 0;
    virtual std::vector<std::string> Strings(const char *name) const = 0;
    virtual void MarkUsed(const char *name) const = 0;
    // A glTF map (a spectrum texture with the "<name>transform"/"<name>texcoord" parameters the
    // glTF reader writes), or null when absent.
    virtual TexturePtr Map(const char *name) const = 0;
    // The material a mix names (pbrt-v3 resolves names where the mix is declared), made with
    // its own parameters; how many mixes enclose this material.
    virtual std::shared_ptr<const Material> NamedMaterial(const std::string &name,
                                                          const FileLoc &loc) const = 0;
    virtual int MixDepth() const = 0;
    // Whether the scene's integrator renders rough glass rough (IntegratorTraits::roughGlass).
    virtual bool RoughGlassRendered() const = 0;
    // The pbrt format version whose rules the file is read by (3 for every file that is not
    // pbrt; scene/pbrt_version.h), where the two renderers' models differ.
    virtual int PbrtVersion() const { return 3; }
    // The bytes of the file that the string parameter `name` names, resolved against the
    // scene's folder, confined and charged to the memory budget as the scene's other files
    // are; a SceneError at the parameter when it cannot be read. `what` names it in messages
    // ("tabulated BSDF").
    virtual std::string ReadFile(const char *name, const std::string &what) const = 0;
};

// The model registered as `type` (material_list.inc), or null when none is. Throws SceneError
// for bad parameters.
std::shared_ptr<const MaterialModel> CreateMaterialModel(const std::string &type,
                                                         const MaterialParams &params,
                                                         const FileLoc &loc);
const std::vector<std::string> &MaterialNames();

}  // namespace prism
