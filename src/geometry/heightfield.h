// pbrt-v3's Shape "heightfield": nu x nv heights over the unit square, as a triangle mesh.
#pragma once

#include <vector>

#include "geometry/nurbs_patch.h"

namespace prism {

// The heights are read from the file (and charged to the memory budget with it); this bounds
// the vertex indices.
inline constexpr uint64_t MaxHeightfieldPoints = uint64_t(1) << 28;

// Vertex (i, j), i < nu, j < nv, lies at (i / (nu-1), j / (nv-1), Pz[j nu + i]) with that
// (x, y) as its uv. Each grid cell is two triangles split along its diagonal from (i, j) to
// (i+1, j+1), wound so a flat field faces +z (pbrt-v3's split; its shading is flat: no
// normals). Throws PatchParamError for nu or nv below 2, more than MaxHeightfieldPoints heights, Pz
// not nu * nv values or not finite.
PatchMesh TessellateHeightfield(int nu, int nv, const std::vector<double> &Pz);

}  // namespace prism
