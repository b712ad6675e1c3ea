// Shape, ObjectBegin/End and ObjectInstance directives → the RenderScene's Accel (analytic
// shapes as Embree user geometry, meshes as Embree triangles, one Embree instance per
// ObjectInstance), each shape's material and area light, and the committed BVH.
#pragma once

#include <string>

#include "assembly/build_context.h"
#include "assembly/materials.h"

namespace prism {

void BuildShapesAndInstances(BuildContext &ctx, MaterialBuilder &materials);

}  // namespace prism
