// The effect set: which effects a scene calls for, each with the reason (and the location of
// the directive) that turned it on. Built while the scene is assembled (assembly/), printed by
// `prism info`, and used by the renderer to run a kernel specialized for exactly these effects.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace prism {

enum class Effect : uint32_t {
    Shadows,             // shadow rays toward lights (per-light detail in EffectSet::lightShadows)
    SpecularReflection,  // perfect mirror lobes
    Refraction,          // perfect specular transmission
    GlossyReflection,    // rough reflection sampled with rays (distribution integrator)
    GlossyTransmission,  // rough transmission sampled with rays (distribution integrator)
    Textures,            // non-constant textures
    SoftShadows,         // area lights: stratified emitter sampling
    Environment,         // an infinite light
    DepthOfField,        // thin lens
    MotionBlur,          // ActiveTransform/TransformTimes with a moving transform, and a shutter
    Csg,                 // CSGBegin/CSGEnd nodes
    Instancing,          // ObjectInstance
    BumpMapping,         // a material's "bumpmap" (render/bump.cpp)
    NormalMapping,       // a material's tangent-space normal map
    Alpha,               // cut-outs: textured "alpha"/"shadowalpha", glTF MASK/BLEND, OBJ map_d
    IndirectIllumination,  // light bouncing off every surface (Integrator "path")
    Media,                 // participating media: a MediumInterface on a shape or the camera
    Subsurface,            // light leaving subsurface materials elsewhere (path, volpath)
    Count
};

inline constexpr uint32_t EffectBit(Effect e) { return 1u << uint32_t(e); }

// One light's shadows: the light ("LightSource \"point\" at scene.pbrt:5") and the shadow rays
// it sends per shading point (more than one: a stratified set, i.e. soft shadows).
struct LightShadows {
    std::string light;
    int shadowRays = 1;
};

struct EffectSet {
    uint32_t mask = 0;
    // Why each effect is on ("ActiveTransform at scene.pbrt:12"); empty when off.
    std::array<std::string, size_t(Effect::Count)> reasons;
    // Each light's shadows, in the order of RenderScene::lights.
    std::vector<LightShadows> lights;
    // The depth beyond which no ray is traced: 1 when nothing is specular or glossy (no ray
    // bounces), else the integrator's maxdepth.
    int maxUsefulDepth = 1;

    bool Has(Effect e) const { return (mask & EffectBit(e)) != 0; }
    // Turns e on; the first reason given is kept.
    void Enable(Effect e, const std::string &why, const FileLoc &loc = {}) {
        if (Has(e)) return;
        mask |= EffectBit(e);
        reasons[size_t(e)] = loc.Valid() ? why + " at " + loc.ToString() : why;
    }
};

// "motion blur", "depth of field", ... (for `prism info`).
const char *EffectName(Effect e);

}  // namespace prism
