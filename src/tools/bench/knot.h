// The knot benchmark scene: a (2,3) torus-knot tube with a ridged displacement over a ground
// quad, one point light, matte materials. A C++ port of ../shared/peers/gen_knot.py, so that
// `prism bench` never needs to write into ../shared (read-only in CI) or to run Python.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace prism {

struct KnotMesh {
    std::vector<std::array<double, 3>> p, n;  // vertices and unit vertex normals
    std::vector<std::array<int, 3>> faces;
};

// nu segments along the knot, nv around the tube: nu * nv * 2 triangles (the ground adds 2).
KnotMesh BuildKnot(int nu, int nv);

struct KnotFiles {
    size_t vertices = 0, triangles = 0;      // triangles include the 2 ground triangles
    std::string pbrt, ply, pov, povInclude;  // written paths ("" when not written)
};

// Writes knot.ply (binary little-endian, the knot only) and knot.pbrt (knot + ground, camera,
// light) into dir, and with pov also knot.pov + knot_mesh.inc, byte for byte what
// gen_knot.py writes for the same nu, nv (floats aside: the PLY holds the same float32s).
// Throws std::runtime_error when a file cannot be written.
KnotFiles WriteKnotScene(const std::string &dir, int nu, int nv, bool pov);

// A pbrt file with the knot's camera and light but nothing to hit: the baseline of the
// memory-per-triangle measurement.
std::string WriteEmptyScene(const std::string &dir);

}  // namespace prism
