// Whitted materials with pbrt-v3 parameters and semantics: matte, plastic, mirror, glass,
// metal, uber, substrate, translucent, mix and "" / none (an invisible interface). Each hit
// turns a material into a BSDF value; docs/MATERIALS.md says what each one does.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "geometry/interaction.h"
#include "render/bsdf.h"
#include "render/gltf_material.h"
#include "render/texture.h"

namespace prism {

class Material {
  public:
    enum class Kind {
        Matte,
        Plastic,
        Mirror,
        Glass,
        Metal,
        Uber,
        Substrate,
        Translucent,
        Mix,
        Gltf,  // glTF 2.0 metallic-roughness (render/gltf_material.h)
        None
    };

    Kind kind = Kind::Matte;
    std::string typeName;  // as written in the scene, for `prism info`
    // Spectrum textures: Kd, Ks, Kr, Kt, opacity (uber), reflect/transmit (translucent),
    // amount (mix). Float textures: sigma, roughness, uRoughness/vRoughness (null: use
    // roughness), index (eta).
    TexturePtr Kd, Ks, Kr, Kt, sigma, roughness, uRoughness, vRoughness, index;
    TexturePtr opacity, reflect, transmit, amount;
    RGB metalEta, metalK;
    bool remapRoughness = true;
    // Mix: pbrt-v3 weights mix1 by amount and mix2 by 1 - amount (MixMaterial).
    std::shared_ptr<const Material> mix1, mix2;
    // Gltf: the glTF parameters.
    GltfMaterialParams gltf;

    // Radiance the surface emits itself (a "gltf" material's "emissive"/"emissivemap" in a
    // .pbrt file; the glTF reader turns emission into area lights instead): seen by camera
    // rays and by the rays that Whitted and glossy recursion trace, but not light-sampled.
    bool HasEmission() const { return kind == Kind::Gltf && gltf.emissive != nullptr; }
    RGB Emitted(const TextureContext &tc) const { return gltf.emissive->Evaluate(tc).Clamped(0.f); }
    // glTF occlusionTexture: the factor 1 + strength × (occlusion.r - 1) by which the light
    // that reaches the hit from the environment (infinite lights: an --env map, the studio
    // rig's uniform environment) and along indirect paths (specular and glossy rays, and a
    // path integrator's bounces) is scaled, as the glTF sample viewer scales its image-based
    // light; 1 for every other material. Direct light from point, spot, distant and area
    // lights is not scaled: Prism traces their shadows. docs/MATERIALS.md.
    float AmbientOcclusion(const TextureContext &tc) const {
        if (kind != Kind::Gltf || !gltf.occlusion) return 1;
        const float ao = std::clamp(gltf.occlusion->Evaluate(tc).r, 0.f, 1.f);
        return 1 + gltf.occlusionStrength * (ao - 1);
    }
    // Shading-normal perturbation (render/bump.cpp), applied to the hit before it is shaded:
    // pbrt-v3's "bumpmap" (a float displacement texture), or a tangent-space normal map (glTF
    // normalTexture, OBJ norm, pbrt-v4 "normalmap") whose x and y are scaled by normalScale.
    TexturePtr bump, normalMap;
    float normalScale = 1;
    int normalMapUVSet = 0;  // the uv set the normal map reads (tangents are made from it)
    bool PerturbsShading() const { return bump || normalMap; }
    // Moves si.ns (and dpdu/dpdv) as the bump or normal map says; needs uv and dpdu/dpdv.
    void PerturbShading(SurfaceInteraction &si) const;

    bool IsPassThrough() const { return kind == Kind::None; }
    // Lambertian matte (no Oren–Nayar sigma): f = kd/π. Kernels without KernelBsdf
    // (render/kernel.h) shade such materials from LambertianKd without building a BSDF.
    bool IsLambertian() const;
    // kd as GetBSDF gives it (its one part, of weight 1); only for IsLambertian materials.
    RGB LambertianKd(const TextureContext &tc) const {
        return fixed_ ? fixedParts_[0].lobes.kd : Kd->Evaluate(tc).Clamped(0.f);
    }
    bool MayTransmit() const;
    bool MayReflectSpecularly() const;
    // BSDF parts this material can add (mixes add their children's; uber's opacity adds one).
    int MaxParts() const;
    // The surface data a hit on this material reads (SurfaceNeeds), decided from its textures:
    // uv when any texture is not constant, dpdu when a glossy lobe may be anisotropic.
    unsigned SurfaceNeeds() const;
    // Whether a texture of the material filters over the ray's footprint (Texture::
    // UsesDifferentials), so hits on it compute TextureContext's derivatives. UsesDifferentials
    // is the value Prepare cached.
    bool TexturesUseDifferentials() const;
    bool UsesDifferentials() const { return differentials_; }
    BSDF GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const;
    // Adds this material's lobes to `bsdf`, scaled by `weight` (used by mix).
    void AddParts(BSDF &bsdf, const TextureContext &tc, const RGB &weight) const;
    // Called once the parameters are final (assembly/materials.cpp): a material whose textures
    // are all constant gets its lobes built here once, and AddParts then copies them instead
    // of evaluating textures and remapping roughness at every hit.
    void Prepare();

  private:
    // SurfaceNeeds of the lobes alone (without the shading perturbation).
    unsigned LobeNeeds() const;
    struct FixedPart {
        RGB weight;
        BxDFLobes lobes;
    };
    std::vector<FixedPart> fixedParts_;
    bool fixed_ = false;
    bool differentials_ = false;
};

}  // namespace prism
