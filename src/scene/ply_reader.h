// Reader for PLY triangle meshes (ascii, binary little- and big-endian) as used by pbrt's
// "plymesh" shape. Our own parser: sizes claimed by the header are checked against the file
// size before anything is allocated, so a hostile header cannot exhaust memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vecmath.h"

namespace prism {

struct PlyMesh {
    std::vector<Vec3f> P, N;    // N is empty unless every vertex has nx ny nz
    std::vector<Vec2f> uv;      // empty unless every vertex has u v (or s t, texture_u ...)
    std::vector<int> indices;   // triangles; quads are split, larger polygons fanned
};

// Throws SceneError for unreadable or malformed files (header errors carry file:line:col).
// `maxBytes` is a memory budget: a file larger than it, or whose mesh would need more (file
// plus arrays, estimated from the header), is rejected before the arrays are allocated.
PlyMesh ReadPlyFile(const std::string &path, Diagnostics &diag, uint64_t maxBytes = 8ull << 30);

}  // namespace prism
