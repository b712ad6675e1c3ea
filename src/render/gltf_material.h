// glTF 2.0's metallic-roughness material (the specification's Appendix B) with
// KHR_materials_ior, _specular, _transmission (thin-walled), _clearcoat and
// _emissive_strength, expressed in Prism's BSDF lobes (render/bsdf.h):
//  - specular: GGX with alpha = roughness², the height-correlated Smith visibility and Schlick's
//    Fresnel; the metallic blend mix(dielectric, metal, metallic) is linear in the Schlick
//    weight, so both specular terms are one microfacet lobe whose Fresnel has
//    f0 = mix(F0_d, baseColor, metallic) and f90 = mix(F90_d, 1, metallic);
//  - diffuse: (1 - metallic)(1 - transmission) baseColor / π, scaled by 1 - max(F_d(v·h))
//    (fresnel_mix);
//  - thin-walled transmission: (1 - metallic) transmission baseColor × the GGX lobe mirrored
//    through the surface, scaled by the same 1 - max(F_d(v·h));
//  - clearcoat: a second part with a GGX lobe (Schlick f0 0.04) of weight clearcoat, and the
//    first part scaled by 1 - clearcoat·F_c(v·h).
// Below SpecularMetalAlpha (material.h) the GGX lobes become delta lobes (a mirror and a
// straight-through transmission), which Whitted's recursion follows: roughness → 0 converges
// to them. docs/MATERIALS.md describes the model.
#pragma once

#include "render/bsdf.h"
#include "render/material.h"
#include "render/texture.h"

namespace prism {

// The parameters of one glTF material as Prism evaluates them at each hit. The textures are
// already multiplied by their factors (baseColor = texture × baseColorFactor, emissive =
// texture × emissiveFactor × emissiveStrength); metallicRoughness is the raw (linear) texture
// whose B and G channels scale metallic and roughness.
struct GltfMaterialParams {
    TexturePtr baseColor, metallicRoughness, emissive, occlusion;
    float metallic = 1, roughness = 1;
    float ior = 1.5f;
    float transmission = 0;
    float specular = 1;
    RGB specularColor{1, 1, 1};
    float clearcoat = 0, clearcoatRoughness = 0;
    float occlusionStrength = 1;

    // Parts this material adds to a BSDF (the clearcoat adds one).
    int MaxParts() const { return clearcoat > 0 ? 2 : 1; }
    // Adds the material's lobes (see above), scaled by `weight`.
    void AddParts(BSDF &bsdf, const TextureContext &tc, const RGB &weight) const;
};

// Prism's "gltf" material model (material_list.inc; the glTF reader writes it).
class GltfMaterial final : public MaterialModel {
  public:
    explicit GltfMaterial(GltfMaterialParams p) : p_(std::move(p)) {}
    const GltfMaterialParams &Gltf() const { return p_; }
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override {
        p_.AddParts(b, tc, weight);
    }
    bool MayReflectSpecularly() const override;
    bool MayTransmit() const override { return p_.transmission > 0 && p_.metallic < 1; }
    bool MayReflectGlossily() const override;
    bool MayTransmitGlossily() const override;
    int MaxParts() const override { return p_.MaxParts(); }
    const Texture *Emission() const override { return p_.emissive.get(); }
    float AmbientOcclusion(const TextureContext &tc) const override;
    std::vector<const Texture *> Textures() const override {
        return {p_.baseColor.get(), p_.metallicRoughness.get(), p_.emissive.get(),
                p_.occlusion.get()};
    }

  private:
    GltfMaterialParams p_;
};

// The dielectric F0 of glTF (KHR_materials_ior, _specular): ((ior - 1) / (ior + 1))² ×
// specularColor, at most 1, × specular; F90 is specular.
RGB GltfDielectricF0(float ior, float specular, const RGB &specularColor);

// KHR_texture_transform on glTF texture coordinates (origin top-left): uv' = T R S uv, with
// Prism's (origin bottom-left) uv converted to glTF's and back around it.
class UVTransformTexture final : public Texture {
  public:
    UVTransformTexture(TexturePtr child, Vec2f offset, float rotation, Vec2f scale)
        : child_(std::move(child)), offset_(offset), rotation_(rotation), scale_(scale) {}
    RGB Evaluate(const TextureContext &c) const override;
    bool UsesDifferentials() const override { return child_->UsesDifferentials(); }
    // The transformed coordinates (Prism's convention), for tests.
    Vec2f Map(Vec2f uv) const;

  private:
    TexturePtr child_;
    Vec2f offset_;
    float rotation_;
    Vec2f scale_;
};

// glTF textureInfo.texCoord 1: the child reads the second texture coordinate set
// (TextureContext::uv1, a mesh's "uv1") as its uv. KHR_texture_transform wraps inside it, so
// the transform applies to the set it selects.
class TexCoord1Texture final : public Texture {
  public:
    explicit TexCoord1Texture(TexturePtr child) : child_(std::move(child)) {}
    RGB Evaluate(const TextureContext &c) const override {
        TextureContext t = c;
        t.uv = c.uv1;
        // The footprint is set 0's (solved from its dp/du, dp/dv): set 1 is read unfiltered.
        t.dudx = t.dvdx = t.dudy = t.dvdy = 0;
        return child_->Evaluate(t);
    }

  private:
    TexturePtr child_;
};

}  // namespace prism
