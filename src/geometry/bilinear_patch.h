// pbrt-v4's Shape "bilinearmesh": bilinear patches p(u, v) = lerp(u, lerp(v, p00, p01),
// lerp(v, p10, p11)), tessellated into a triangle mesh fine enough that it departs from the
// patch by at most a tolerance, with the patch's own (u, v), normals and texture coordinates
// at the vertices.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/nurbs_patch.h"

namespace prism {

// A patch's grid is at most this many segments a side; a mesh at most this many triangles
// (BilinearSegments lowers the grids of a mesh that would exceed it, uniformly).
inline constexpr int MaxBilinearSegments = 64;
inline constexpr uint64_t MaxBilinearTriangles = uint64_t(1) << 24;

struct BilinearMesh {
    std::vector<Vec3f> P;      // the vertices (object space)
    std::vector<int> indices;  // 4 per patch: p00, p10, p01, p11
    std::vector<Vec3f> N;      // empty, or one per vertex: interpolated as shading normals
    std::vector<Vec2f> uv;     // empty, or one per vertex: interpolated bilinearly
};

// Throws PatchParamError ("indices", "P", "N", "uv") for no positions, indices missing (allowed
// only for exactly 4 positions: one patch) or not a multiple of 4, an index out of range, N or
// uv not one per vertex, or a position that is not finite.
void ValidateBilinearMesh(const BilinearMesh &mesh);

// The grid segments a side for each patch: the least n with the error of an n x n grid of
// triangles, |t| / (4 n^2) for the patch's twist t = p00 - p10 - p01 + p11 (a cell is split
// along its (0,0)-(1,1) diagonal; its largest departure from the patch is at the cell's
// centre), at most relativeTolerance times the patch's bounding-box diagonal; 1 for a flat
// patch; at most MaxBilinearSegments. The whole mesh stays within maxTriangles.
std::vector<int> BilinearSegments(const BilinearMesh &mesh, double relativeTolerance = 2e-4,
                                  uint64_t maxTriangles = MaxBilinearTriangles);

// The triangles and vertices of the tessellation of the segments BilinearSegments returns,
// and each patch's first triangle (TriangleMesh::SetPatches).
uint64_t BilinearTriangles(const std::vector<int> &segments);
uint64_t BilinearVertices(const std::vector<int> &segments);
std::vector<uint32_t> BilinearPatchFirstTriangles(const std::vector<int> &segments);

// Each patch as an n x n grid of its own vertices (u along i, v along j), two triangles per
// cell wound so (p1 - p0) x (p2 - p0) faces dp/du x dp/dv. uv: the patch's (u, v), or its
// corners' uv interpolated. N: the corners' N interpolated and normalised when the mesh has
// them; else, when any patch is curved (n > 1), dp/du x dp/dv normalised at every vertex so
// the shading is smooth as pbrt-v4's exact patches; else none (flat shading). The mesh must be
// valid.
PatchMesh TessellateBilinearMesh(const BilinearMesh &mesh, const std::vector<int> &segments);

}  // namespace prism
