// pbrt's Material "hair" (pbrt-v3 and pbrt-v4): the fibre model of render/hair_bxdf.h, with
// its absorption given directly, by a colour, or by melanin concentrations. docs/MATERIALS.md.
#pragma once

#include "render/material.h"

namespace prism {

class HairMaterial final : public MaterialModel {
  public:
    struct Params {
        // Exactly one of the absorption's sources is set: sigmaA, reflectance (its colour), or
        // the two melanin concentrations.
        TexturePtr sigmaA, reflectance, eumelanin, pheomelanin;
        TexturePtr eta, betaM, betaN, alpha;
        // pbrt-v3's tilt (a pbrt-v3 file): its lobes shift along the fibre the other way from
        // pbrt-v4's for the same alpha; alpha is negated in pbrt-v4's form, which puts them
        // where pbrt-v3's are and keeps them normalised.
        bool pbrtV3Tilt = false;
    };
    explicit HairMaterial(Params p) : p_(std::move(p)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    // Where the ray meets the fibre's width is uv's v; the fibre runs along dpdu.
    unsigned GeometryNeeds() const override { return NeedAll; }
    std::vector<const Texture *> Textures() const override;

  private:
    Params p_;
};

}  // namespace prism
