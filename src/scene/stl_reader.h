// STL (stereolithography) reader: ASCII and binary triangle soups, each solid welded into one
// "trianglemesh" whose exactly equal positions share a vertex (so the mesh is indexed and its
// memory is about a sixth of the soup's). Facet normals are not read: STL exporters often write
// zeros or stale normals, and a welded mesh without "N" is shaded flat by its geometric normals,
// as the file's facets mean. Binary per-facet colours (the attribute word) are not read either.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene_description.h"

namespace prism {

class MemoryBudget;

// Binary when the file's size is exactly 84 + 50 × the triangle count at byte 80; otherwise
// ASCII if it starts with "solid" and holds no zero byte. Throws SceneError for anything else, for
// a truncated binary file, for ASCII syntax errors (at file:line:col) and for non-finite
// coordinates. The file, the welding buffers and the meshes (their parameter storage) are charged
// to `budget` (or to a default budget of its own); MemoryBudgetError when they do not fit. One
// shape per solid, named by the solid; no camera, lights or materials.
SceneDescription ReadStlFile(const std::string &path, Diagnostics &diag,
                             MemoryBudget *budget = nullptr);

// The bytes ReadStlFile charges, beyond the file, for `triangles` triangles before it welds
// them: the soup's positions and indices and the weld table.
uint64_t StlWeldBytes(uint64_t triangles);

}  // namespace prism
