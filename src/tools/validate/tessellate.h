// Triangle twins of the analytic shapes: every shape is a profile curve (rho(v), z(v)) swept
// about z, so one tessellator and one set of distance functions serve them all. Used by
// `prism render --tessellate N` and by `prism validate` (docs/SHAPES.md).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/vecmath.h"
#include "geometry/revolution.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"

namespace prism {

struct TessellatedMesh {
    std::vector<Vec3d> P;   // object space, on the surface to double rounding
    std::vector<Vec3d> N;   // unit, along the analytic normal (pbrt orientation)
    std::vector<Vec2d> uv;  // the analytic shape's uv
    std::vector<uint32_t> indices;
    int nPhi = 0, nV = 0;
    // The cone's apex, which has no normal of its own (each generator has one): N holds the
    // axis there; MakeTessellatedMesh gives it a zero shading normal. -1 for other shapes.
    int apexVertex = -1;
};

// Rings derived from nPhi: max(1, round(nPhi * turning / 2pi)); nPhi/2 for a full sphere.
int RingsFor(const RevolutionProfile &profile, int nPhi);

// Tessellates with nPhi segments around the axis (nPhi >= 3 for full circles, >= 1 for
// partial ones). Returns false if the shape has no profile description; throws
// std::length_error beyond MaxTessellationTriangles (memory stays bounded on any input).
inline constexpr size_t MaxTessellationTriangles = size_t(1) << 24;
bool Tessellate(const AnalyticShape &shape, int nPhi, TessellatedMesh *mesh);
// Upper bounds on the vertices and triangles Tessellate makes, without making them (false if
// the shape has no profile; std::length_error as Tessellate).
bool TessellationSize(const AnalyticShape &shape, int nPhi, uint64_t *vertices,
                      uint64_t *triangles);

// The tessellation as an Embree-ready triangle mesh with the shape's transform and
// orientation (nullptr if the shape cannot be tessellated). `charge`, when given, is called
// with its size (TessellationSize) before anything is allocated.
std::unique_ptr<TriangleMesh> MakeTessellatedMesh(const AnalyticShape &shape, int nPhi,
                                                  const MeshCharge &charge = {});

// MakeTessellatedMesh with nPhi segments as a BuildSettings::replaceAnalyticShape hook
// (`prism render --tessellate N`): build/ calls it without depending on validate/.
std::function<std::unique_ptr<TriangleMesh>(const AnalyticShape &, const MeshCharge &)>
TessellateWith(int nPhi);

// Distance in the meridian half-plane from (rho, z) to the profile curve (v clipped to
// [0, 1]); *vClosest receives the closest parameter. Signed: positive on the side of the
// profile normal (tz, -trho), which is the outward side for the closed shapes.
double ProfileDistance(const RevolutionProfile &profile, Vec2d q, double *vClosest = nullptr);

// Unsigned distance from an object-space point to the swept surface (phi clipping applied).
double SurfaceDistance(const RevolutionProfile &profile, const Vec3d &p);

// Maximum distance of the tessellation's triangles from the surface (object space), measured
// on a dense barycentric grid over one phi column (all columns are congruent).
double ChordError(const RevolutionProfile &profile, const TessellatedMesh &mesh);

// Distance from the object-space ray o + t d, t in [t0, t1], to the edges of the patch: the
// rims at v = 0 and v = 1 (unless poles or closed) and the phi = 0, phiMax cuts.
double DistanceToBoundary(const RevolutionProfile &profile, const Vec3d &o, const Vec3d &d,
                          double t0, double t1);

// Distance of the ray to tangency with the surface: the smallest |signed distance| at a
// local extremum of the signed distance along the ray (a near miss or a shallow graze).
// Transversal crossings have no extremum and do not count.
double DistanceToTangency(const RevolutionProfile &profile, const Vec3d &o, const Vec3d &d,
                          double t0, double t1);

}  // namespace prism
