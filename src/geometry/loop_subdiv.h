// Loop (1987) subdivision of a triangle mesh on the CPU, with pbrt-v3's boundary rules, the
// vertices pushed to the limit surface, and limit-surface normals (for Shape "loopsubdiv").
#pragma once

#include <cstdint>
#include <vector>

#include "core/vecmath.h"

namespace prism {

// Upper bounds on the work a scene may ask for; LoopSubdivide rejects more.
inline constexpr int MaxLoopSubdivLevels = 8;
inline constexpr uint64_t MaxLoopSubdivTriangles = uint64_t(1) << 22;

struct LoopSubdivResult {
    std::vector<Vec3f> P, N;   // limit positions and normals (object space)
    std::vector<int> indices;  // 3 per triangle, same winding as the input
    int droppedFaces = 0;      // degenerate input faces (repeated vertex) that were skipped
};

// Subdivides `levels` times. Vertices on edges used by one face (or by more than two) follow
// the boundary (crease) rules, so open meshes keep their boundary curves. Throws
// std::invalid_argument with a short message for bad input (index count not a multiple of 3,
// indices out of range, levels outside 0..MaxLoopSubdivLevels, too many output triangles).
LoopSubdivResult LoopSubdivide(const std::vector<Vec3f> &P, const std::vector<int> &indices,
                               int levels);

}  // namespace prism
