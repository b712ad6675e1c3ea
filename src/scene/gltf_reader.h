// glTF 2.0 reader (.gltf and .glb, via tinygltf): the default scene's node hierarchy, triangle
// primitives, the first camera, KHR_lights_punctual lights and approximate pbrt-v3 materials.
#pragma once

#include <string>

#include "scene/scene_description.h"

namespace prism {

class MemoryBudget;

// Throws SceneError for unreadable or malformed files (including accessors that reach past
// their buffers). Embedded images are returned in SceneDescription::embeddedImages and
// referenced by textures as "embedded:<index>"; nothing is written to disk.
// Charged to `budget` (core/memory.h), each refused with a MemoryBudgetError before it is
// read: the .gltf/.glb file, each external buffer, and after conversion the mesh parameters
// and embedded images the description keeps (external images are read by tinygltf and given
// back; the renderer charges them when it decodes them). Buffers must be regular files.
// `camera`: the camera to view through, by its name or its index in the file's cameras (""
// : the first one the scene's traversal reaches); one the scene does not use is an error.
SceneDescription ReadGltfFile(const std::string &path, Diagnostics &diag, MemoryBudget &budget,
                              const std::string &camera = "");
// The same with a budget of its own of `maxMemory` bytes (0: the default budget).
SceneDescription ReadGltfFile(const std::string &path, Diagnostics &diag, uint64_t maxMemory = 0);

}  // namespace prism
