// Whitted materials with pbrt-v3 parameters and semantics: matte, plastic, mirror, glass,
// metal and "" / none (an invisible interface). Each hit turns a material into a BSDF value.
#pragma once

#include <memory>
#include <string>

#include "geometry/interaction.h"
#include "render/bsdf.h"
#include "render/texture.h"

namespace prism {

class Material {
public:
    enum class Kind { Matte, Plastic, Mirror, Glass, Metal, None };

    Kind kind = Kind::Matte;
    std::string typeName;  // as written in the scene, for `prism info`
    TexturePtr Kd, Ks, Kr, Kt, sigma, roughness, uRoughness, vRoughness, index;
    RGB metalEta, metalK;
    bool remapRoughness = true;

    bool IsPassThrough() const { return kind == Kind::None; }
    bool MayTransmit() const { return kind == Kind::Glass; }
    bool MayReflectSpecularly() const;
    BSDF GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const;
};

// Roughness (after remapping) below which a metal is treated as a polished conductor: a delta
// reflection that recursion follows, instead of a highlight that point lights would miss.
inline constexpr float SpecularMetalAlpha = 0.02f;

}  // namespace prism
