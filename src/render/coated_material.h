// pbrt-v4's "coateddiffuse" and "coatedconductor": a dielectric coat over a diffuse or
// conductor base, simulated by pbrt-v4's layered BSDF (render/layered_bxdf.h). docs/MATERIALS.md.
#pragma once

#include "render/material.h"

namespace prism {

// No glossy-reflection effect: the path integrators sample the layered lobe whole, and the
// distribution integrator lights it by light samples only, as a diffuse lobe.
class CoatedMaterial final : public MaterialModel {
  public:
    struct Params {
        LayeredLobe::Base base = LayeredLobe::Base::Diffuse;
        TexturePtr reflectance;                 // diffuse base
        TexturePtr conductorEta, conductorK;    // conductor base (null with reflectance)
        TexturePtr coatU, coatV, baseU, baseV;  // roughness (baseU/V: conductor only)
        bool remap = true;                      // roughness r → alpha sqrt(r) (pbrt-v4)
        float eta = 1.5f;                       // the coat's index
        TexturePtr thickness, albedo, g;
        int maxDepth = 10, nSamples = 1;
    };
    explicit CoatedMaterial(Params p) : p_(std::move(p)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override;

  private:
    Params p_;
};

}  // namespace prism
