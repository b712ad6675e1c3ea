// Wavefront OBJ + MTL reader (via tinyobjloader): one "trianglemesh" per (OBJ shape, material)
// and MTL materials mapped onto pbrt-v3 material types (matte/plastic/mirror/glass).
#pragma once

#include <string>

#include "scene/scene_description.h"

namespace prism {

// Throws SceneError when the file cannot be read or is malformed; a missing .mtl file is a
// warning (the default material is used). The camera is left unspecified.
SceneDescription ReadObjFile(const std::string &path, Diagnostics &diag);

}  // namespace prism
