// pbrt-v3's Material "fourier": a BSDF tabulated in a .bsdf file (render/fourier_bsdf.h).
// docs/MATERIALS.md.
#pragma once

#include <memory>

#include "render/fourier_bsdf.h"
#include "render/material.h"

namespace prism {

class FourierMaterial final : public MaterialModel {
  public:
    explicit FourierMaterial(std::shared_ptr<const FourierTable> table)
        : table_(std::move(table)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    const FourierTable &Table() const { return *table_; }

  private:
    std::shared_ptr<const FourierTable> table_;
};

}  // namespace prism
