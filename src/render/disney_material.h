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
        TexturePtr scatterDistance;  // null or constant black: no subsurface scattering
        bool thin = false;
    };
    explicit DisneyMaterial(Params p) : p_(std::move(p)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    unsigned LobeNeeds() const override;
    // With a scattering distance (and not thin), pbrt-v3 replaces the diffuse lobe by a delta
    // transmission into Burley's normalised-diffusion BSSRDF.
    bool HasSubsurface() const override;
    bool MayTransmit() const override { return HasSubsurface(); }
    bool SubsurfaceAt(const TextureContext &tc, const Vec3f &po, const Vec3f &ns, const Vec3f &dpdu,
                      SeparableBssrdf *out) const override;
    std::vector<const Texture *> Textures() const override;

  private:
    Params p_;
};

}  // namespace prism
