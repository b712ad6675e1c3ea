// Triangle meshes in render space, shared with Embree without copying.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/transform.h"
#include "geometry/interaction.h"

namespace prism {

// Charges a mesh about to be made to a memory budget (the caller supplies where and under
// which name): `meshBytes` (TriangleMesh::Bytes) are kept, `transientBytes` (the arrays it is
// made from, freed once it exists) must fit beside them but are not kept. Throws when they do
// not fit (MemoryBudgetError, core/memory.h).
using MeshCharge = std::function<void(uint64_t meshBytes, uint64_t transientBytes)>;

class TriangleMesh {
  public:
    // Object-space data; transformed to render space here (in double, rounded once).
    // Throws std::invalid_argument for inconsistent sizes or out-of-range indices.
    TriangleMesh(const Transform &renderFromObject, bool reverseOrientation,
                 const std::vector<Vec3f> &P, std::vector<uint32_t> indices,
                 const std::vector<Vec3f> &N = {}, std::vector<Vec2f> uv = {});

    // The bytes a mesh of this many vertices and indices holds (positions padded by one float,
    // indices, and normals and uv when present), for the memory budget before it is made.
    static uint64_t Bytes(uint64_t vertices, uint64_t indices, bool normals, bool uv) {
        return (3 * vertices + 1) * sizeof(float) + indices * sizeof(uint32_t) +
               (normals ? vertices * sizeof(Vec3f) : 0) + (uv ? vertices * sizeof(Vec2f) : 0);
    }
    uint64_t MemoryBytes() const {
        return Bytes(NumVertices(), indices_.size(), HasNormals(), HasUV()) +
               uv1_.size() * sizeof(Vec2f) + patchFirst_.size() * sizeof(uint32_t);
    }

    size_t NumTriangles() const { return indices_.size() / 3; }
    size_t NumVertices() const { return (positions_.size() - 1) / 3; }
    const float *PositionData() const { return positions_.data(); }  // xyz, padded by one float
    const uint32_t *IndexData() const { return indices_.data(); }
    Vec3f Position(uint32_t i) const {
        return {positions_[3 * i], positions_[3 * i + 1], positions_[3 * i + 2]};
    }
    const uint32_t *Triangle(size_t prim) const { return &indices_[3 * prim]; }
    // Asks the cache for the vertex data Interaction will read for triangle `prim` (its
    // indices are loaded now). For batches of hits shaded one after another.
    void Prefetch(size_t prim) const {
        const uint32_t *v = Triangle(prim);
        for (int i = 0; i < 3; ++i) {
            __builtin_prefetch(&positions_[3 * size_t(v[i])]);
            if (!normals_.empty()) __builtin_prefetch(&normals_[v[i]]);
        }
    }
    // Motion blur (Embree time steps): the mesh moved by each transform (render space to
    // render space, applied to the mesh as made), one per time step after the first, at equal
    // spacing over the shutter; step 0 is the mesh itself. Between steps the vertices move
    // linearly, as Embree interpolates them.
    void SetMotionSteps(const std::vector<Transform> &stepFromStart);
    int NumTimeSteps() const { return 1 + int(stepPositions_.size()); }
    const float *PositionData(int step) const {
        return step == 0 ? positions_.data() : stepPositions_[size_t(step - 1)].data();
    }
    // Per-vertex tangents for tangent-space normal maps: Interaction then gives dpdu and dpdv =
    // the interpolated tangent and bitangent (sign * (n x tangent) at each vertex). SetTangents
    // takes the mesh's own (glTF TANGENT: object-space xyz and the bitangent sign w, 4 floats per
    // vertex); GenerateTangents averages each triangle's dp/du (from its uv) over the triangles
    // around a vertex, weighted by the corner's angle (as MikkTSpace does), made orthogonal to the
    // vertex normal, with the sign of dp/dv's side.
    // `uvSet` 1: from the second texture coordinate set (a normal map that reads TEXCOORD_1).
    void SetTangents(const Transform &renderFromObject, const std::vector<float> &xyzw);
    void GenerateTangents(int uvSet = 0);
    bool HasTangents() const { return !tangents_.empty(); }
    bool HasNormals() const { return !normals_.empty(); }
    bool HasUV() const { return !uv_.empty(); }
    // A second texture coordinate set (glTF TEXCOORD_1, the Prism parameter "uv1"), one per
    // vertex; Interaction gives it as SurfaceInteraction::uv1 (uv where the mesh has none).
    // Throws std::invalid_argument when the count differs from the vertices'.
    void SetUV1(std::vector<Vec2f> uv1);
    bool HasUV1() const { return !uv1_.empty(); }
    bool FlipNormals() const { return flipNormals_; }
    // pbrt-v4's shapes that Prism made into several triangles (a bilinear patch, a PLY quad):
    // patch k is triangles [first[k], first[k + 1]) (the last to the end); an emitter's
    // "power" is given to each patch, as pbrt-v4 gives it to each of its shapes. Empty: each
    // triangle is its own. Throws std::invalid_argument unless first[0] == 0 and the firsts
    // increase strictly below NumTriangles().
    void SetPatches(std::vector<uint32_t> first);
    const std::vector<uint32_t> &PatchFirstTriangles() const { return patchFirst_; }
    Bounds3f RenderBounds() const;

    // The uv at Embree barycentrics (u, v) of triangle `prim` (pbrt's (0,0), (1,0), (1,1)
    // without uv), for cut-out tests.
    // `uvSet` 1 reads the second set (uv1), or the first where the mesh has none.
    Vec2f UVAt(size_t prim, float u, float v, int uvSet = 0) const {
        const std::vector<Vec2f> &set = uvSet == 1 && !uv1_.empty() ? uv1_ : uv_;
        if (set.empty()) return {u + v, v};
        const uint32_t *vi = Triangle(prim);
        return set[vi[0]] * (1 - u - v) + set[vi[1]] * u + set[vi[2]] * v;
    }
    // Geometric normal as the trace command defines it: (p1-p0) x (p2-p0), flipped by
    // ReverseOrientation XOR handedness; unit length; zero for degenerate triangles.
    Vec3f GeometricNormal(size_t prim) const;
    // Phase 2 for a hit with Embree barycentrics (u, v) of vertices 1 and 2; uv and dpdu/dpdv
    // only as `needs` (SurfaceNeeds) asks.
    // `time` (Ray::time) matters only for a moving mesh; it and `shape` (the render scene's
    // index of this mesh) are stored in the result, so that Accel returns it as built.
    SurfaceInteraction Interaction(size_t prim, float u, float v, float t, const Vec3f &rayDir,
                                   unsigned needs = NeedAll, float time = 0, int shape = -1) const;
    // Curvature (AnalyticShape::NormalDerivatives for meshes): the derivatives of the unit
    // shading normal of triangle `prim` along the tangent vectors dp[i] at the hit si, oriented
    // as n. With per-vertex normals, the interpolated normal's (barycentric differences of the
    // vertex normals, through the hit's barycentrics recomputed from si.p); zero without them
    // (flat faces).
    void NormalDerivatives(size_t prim, const SurfaceInteraction &si, const Vec3f &n,
                           const Vec3f *dp, Vec3f *dn, int count) const;

  private:
    // Vertex i (and its shading normal) where a moving mesh is at `time`.
    Vec3f PositionAt(uint32_t i, float time) const;
    Vec3f NormalAt(uint32_t i, float time) const;

    std::vector<float> positions_;
    std::vector<std::vector<float>> stepPositions_;  // motion steps 1..n-1
    std::vector<std::vector<Vec3f>> stepNormals_;    // (when the mesh has normals)
    std::vector<uint32_t> indices_;
    std::vector<Vec3f> normals_;
    std::vector<Vec2f> uv_;
    std::vector<Vec2f> uv1_;            // second texture coordinate set (may be empty)
    std::vector<uint32_t> patchFirst_;  // SetPatches (may be empty)
    std::vector<Vec3f> tangents_;       // render space, unit (or zero)
    std::vector<Vec3f> bitangents_;
    // Bitangents from tangents_, the vertex normals (or the angle-weighted face normals) and
    // each vertex's sign.
    void FinishTangents(const std::vector<float> &signs);
    bool flipNormals_;
};

}  // namespace prism
