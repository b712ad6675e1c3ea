// Wavefront OBJ + MTL reader (via tinyobjloader): one "trianglemesh" per (OBJ shape, material)
// and MTL materials mapped onto pbrt-v3 material types (matte/plastic/mirror/glass).
#pragma once

#include <string>

#include "scene/scene_description.h"

namespace prism {

class MemoryBudget;

// Throws SceneError when the file cannot be read or is malformed; a missing .mtl file is a
// warning (the default material is used). The camera is left unspecified.
// With a `budget` (core/memory.h), the OBJ file, each MTL file and the meshes built from them
// (their parameter storage) are charged to it; MemoryBudgetError when they do not fit.
SceneDescription ReadObjFile(const std::string &path, Diagnostics &diag,
                             MemoryBudget *budget = nullptr);

}  // namespace prism
