// CSGBegin/CSGEnd nodes (scene/scene_description.h CsgDesc) → one CsgShape each
// (geometry/csg.h): operands become analytic shapes or closed triangle meshes with their own
// transforms; each operand keeps the material of its Shape directive.
#pragma once

#include <memory>
#include <vector>

#include "assembly/build_context.h"
#include "assembly/materials.h"
#include "geometry/csg.h"

namespace prism {

// Builds the CSG tree of a top-level node. `operands` receives one ShapeInfo per leaf, in
// leaf order (CsgShape's part numbers): the render scene's prototype table for the node.
// Throws SceneError at the offending directive for bad CSG (an open mesh, a shape that cannot
// be an operand).
std::unique_ptr<CsgShape> BuildCsgShape(BuildContext &ctx, MaterialBuilder &materials,
                                        const CsgDesc &node, std::vector<ShapeInfo> *operands);

}  // namespace prism
