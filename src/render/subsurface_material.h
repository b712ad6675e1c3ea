// pbrt's Material "subsurface" and "kdsubsurface": a smooth or rough dielectric interface
// (the glass model's lobes) over a scattering medium whose light leaves elsewhere on the same
// material, by the tabulated BSSRDF of render/bssrdf.h. The path integrators (path, volpath)
// follow light through it (render/subsurface.h); the others render the interface alone, as
// pbrt-v3 does. docs/MATERIALS.md.
#pragma once

#include <memory>

#include "render/bssrdf.h"
#include "render/material.h"

namespace prism {

class SubsurfaceMaterial final : public MaterialModel {
  public:
    struct Params {
        std::shared_ptr<const MaterialModel> interface;  // the dielectric's lobes (glass)
        float eta = 1.33f, g = 0;
        float scale = 1;  // multiplies σa and σs, or mfp
        // Either the coefficients (subsurface) or a diffuse colour and mean free path
        // (kdsubsurface; pbrt-v4's "reflectance" with "mfp").
        TexturePtr sigmaA, sigmaS;
        TexturePtr kd, mfp;
    };
    explicit SubsurfaceMaterial(Params p);

    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override {
        p_.interface->AddParts(b, tc, weight);
    }
    bool MayReflectSpecularly() const override { return p_.interface->MayReflectSpecularly(); }
    bool MayTransmit() const override { return p_.interface->MayTransmit(); }
    bool MayReflectGlossily() const override { return p_.interface->MayReflectGlossily(); }
    bool MayTransmitGlossily() const override { return p_.interface->MayTransmitGlossily(); }
    bool IsRoughGlass() const override { return p_.interface->IsRoughGlass(); }
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override;
    bool HasSubsurface() const override { return true; }
    bool SubsurfaceAt(const TextureContext &tc, const Vec3f &po, const Vec3f &ns, const Vec3f &dpdu,
                      SeparableBssrdf *out) const override;
    float Eta() const { return p_.eta; }

  private:
    Params p_;
    std::shared_ptr<const BssrdfTable> table_;
};

}  // namespace prism
