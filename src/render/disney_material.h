// pbrt-v3's Material "disney": the lobes of render/disney_bxdf.h from its textures.
// docs/MATERIALS.md.
#pragma once

#include "render/material.h"

namespace prism {

class DisneyMaterial final : public MaterialModel {
  public:
    struct Params {
        TexturePtr color, metallic, eta, roughness, specularTint, anisotropic, sheen, sheenTint,
            clearcoat, clearcoatGloss, specTrans, flatness, diffTrans;
        bool thin = false;
    };
    explicit DisneyMaterial(Params p) : p_(std::move(p)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override;

  private:
    Params p_;
};

}  // namespace prism
