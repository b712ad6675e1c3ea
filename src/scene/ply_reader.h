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
    std::vector<Vec3f> P, N;          // N is empty unless every vertex has nx ny nz
    std::vector<Vec2f> uv;            // empty unless every vertex has u v (or s t, texture_u ...)
    std::vector<int> indices;         // triangles; quads are split, larger polygons fanned
    std::vector<uint32_t> quadFirst;  // the first of the two triangles of each quad, ascending
};

class MemoryBudget;

// Throws SceneError for unreadable or malformed files (header errors carry file:line:col).
// The mesh is charged to `budget` (core/memory.h) before its arrays are allocated: the file
// plus P, N, uv (32 bytes per vertex) and the indices (24 bytes per face, a quad being two
// triangles), estimated from the header, as "mesh" at the vertex element's location. A file
// larger than what remains is refused before it is read. MemoryBudgetError either way.
PlyMesh ReadPlyFile(const std::string &path, Diagnostics &diag, MemoryBudget &budget);
// The same with a budget of its own of `maxBytes` (0: the default budget).
PlyMesh ReadPlyFile(const std::string &path, Diagnostics &diag, uint64_t maxBytes = 8ull << 30);
// The bytes ReadPlyFile charges for a mesh of this many vertices and faces read from a file of
// `fileBytes` bytes.
uint64_t PlyMeshBytes(uint64_t fileBytes, uint64_t vertices, uint64_t faces);

}  // namespace prism
