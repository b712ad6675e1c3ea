#include "render/effects.h"

namespace prism {

const char *EffectName(Effect e) {
    switch (e) {
        case Effect::Shadows:
            return "shadows";
        case Effect::SpecularReflection:
            return "specular reflection";
        case Effect::Refraction:
            return "refraction";
        case Effect::GlossyReflection:
            return "glossy reflection";
        case Effect::GlossyTransmission:
            return "glossy transmission";
        case Effect::Textures:
            return "textures";
        case Effect::SoftShadows:
            return "soft shadows";
        case Effect::Environment:
            return "environment";
        case Effect::DepthOfField:
            return "depth of field";
        case Effect::MotionBlur:
            return "motion blur";
        case Effect::Csg:
            return "CSG";
        case Effect::Instancing:
            return "instancing";
        case Effect::BumpMapping:
            return "bump mapping";
        case Effect::NormalMapping:
            return "normal mapping";
        case Effect::Alpha:
            return "alpha";
        case Effect::IndirectIllumination:
            return "indirect illumination";
        case Effect::Media:
            return "participating media";
        case Effect::Subsurface:
            return "subsurface scattering";
        case Effect::Count:
            break;
    }
    return "?";
}

}  // namespace prism
