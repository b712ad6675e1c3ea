// The effect set (render/effects.h): the build steps note here what each material, light,
// camera, CSG node and instance calls for, with the directive's location; FinishEffects
// completes the set once the scene is built.
#pragma once

#include <string>

#include "assembly/build_context.h"

namespace prism {

// The effects of a material used by a shape: specular reflection, refraction, glossy
// reflection and transmission (only with Integrator "distribution") and textures. `why` names
// the material ("material \"glass\"") and loc its directive.
void NoteMaterialEffects(BuildContext &ctx, const Material &m, const std::string &why,
                         const FileLoc &loc);
// The effects of the light just added to the scene (scene.lights.back()): its shadows, soft
// shadows for area lights, environment for infinite lights.
void NoteLightEffects(BuildContext &ctx, const std::string &why, const FileLoc &loc);
// After the build: the maximum useful depth.
void FinishEffects(BuildContext &ctx);

// The reason for a shape's material: `material "name"` (its Material/MakeNamedMaterial
// directive) or, for pbrt's default material, the shape.
std::string MaterialWhy(const SceneDescription &desc, const ShapeDesc &s, FileLoc *loc);

}  // namespace prism
