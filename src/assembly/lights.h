// LightSource and AreaLightSource directives → render/ lights (pbrt-v3 names and defaults).
#pragma once

#include "assembly/build_context.h"

namespace prism {

// Point, spot, distant and infinite lights; warns once per unsupported type.
void BuildLights(BuildContext &ctx);

// Makes RenderScene shape `shape` (created from `s`) emit as s.areaLight says. Returns the area
// light's description when the shape emits (its unused parameters are reported once, after all
// shapes), nullptr after a warning when it cannot.
const AreaLightDesc *AddAreaLight(BuildContext &ctx, const ShapeDesc &s, int shape);

}  // namespace prism
