// glTF 2.0 reader (.gltf and .glb, via tinygltf): the default scene's node hierarchy, triangle
// primitives, the first camera, KHR_lights_punctual lights and approximate pbrt-v3 materials.
#pragma once

#include <string>

#include "scene/scene_description.h"

namespace prism {

// Throws SceneError for unreadable or malformed files (including accessors that reach past
// their buffers). Embedded images are returned in SceneDescription::embeddedImages and
// referenced by textures as "embedded:<index>"; nothing is written to disk.
// The .gltf/.glb file and each external buffer must fit in `maxMemory` bytes (0: the default
// budget of core/memory.h); buffers must be regular files.
SceneDescription ReadGltfFile(const std::string &path, Diagnostics &diag, uint64_t maxMemory = 0);

}  // namespace prism
