// Constructive solid geometry (a Prism extension of the pbrt format, docs/FORMAT.md): union,
// intersection and difference of solids, nestable, over analytic shapes and closed triangle
// meshes. A whole CSG tree is ONE Embree user geometry: it is an AnalyticShape (the interface of
// Prism's user geometry) whose root routine gathers each operand's entry/exit crossings along
// the ray (every root of an analytic shape; every hit of a mesh, through the mesh's own Embree
// scene), combines them with the boolean operations and reports the first boundary of the
// result inside (tMin, tMax). Closest-hit and shadow rays share that routine.
//
// The "object space" of a CsgShape is render space (its transform is the identity): each
// operand keeps its own transform. A hit reports the operand in ObjectHit::part and
// SurfaceInteraction::instanceShape (the render scene maps it to the operand's material, like
// a shape inside an instance). Normals point out of the result: a subtracted operand's carved
// surface shows its normal turned around. Scenes without CSG never reach this code.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"

namespace prism {

class Accel;

enum class CsgOp { Union, Intersection, Difference };

// "union", "intersection", "difference" → the operation; false for anything else.
bool ParseCsgOp(const std::string &name, CsgOp *op);
const char *CsgOpName(CsgOp op);

// Whether a triangle mesh bounds a solid: every edge (vertices welded by position) is shared
// by exactly two triangles. Returns "" when closed, else what is wrong ("edge (0 0 0)-(1 0 0)
// belongs to 1 triangle").
std::string MeshClosedError(const TriangleMesh &mesh);

// An operand of a CSG node: a leaf (operand shape) or a nested node, by index.
struct CsgRef {
    bool leaf = true;
    int index = 0;
};

class CsgShape final : public AnalyticShape {
  public:
    CsgShape();
    ~CsgShape() override;

    // Leaves are numbered in the order they are added (that number is ObjectHit::part).
    int AddLeaf(std::unique_ptr<AnalyticShape> shape);
    // The mesh must be closed (MeshClosedError); its orientation does not matter.
    int AddLeaf(std::unique_ptr<TriangleMesh> mesh);
    // Children first; the node added last is the root. Difference is first minus the rest;
    // union and intersection take any number of operands (at least one).
    int AddNode(CsgOp op, std::vector<CsgRef> operands);
    // Call once after the last AddNode (computes bounds, builds the meshes' BVHs).
    void Finish();

    int NumLeaves() const { return int(leaves_.size()); }
    int NumNodes() const { return int(nodes_.size()); }

    const char *Name() const override { return "csg"; }
    Bounds3d ObjectBounds() const override { return bounds_; }
    // Combined from the analytic operands' implicit functions (min, max, max(a, -b)), each in
    // its own object space; mesh operands contribute 0. Only the sign is meaningful.
    double Implicit(const Vec3d &pRender) const override;
    Vec3d ImplicitGradient(const Vec3d &pRender) const override;
    bool Intersect(const Vec3f &o, const Vec3f &d, float tMin, float tMax, Precision precision,
                   ObjectHit *hit) const override;
    LocalGeometry Geometry(const ObjectHit &hit) const override;
    // Curvature is the operand's (si.instanceShape): an analytic operand's own, zero on a mesh
    // operand (its faces are flat: CSG meshes shade with their geometric normals).
    Vec3d NormalFieldDerivative(const Vec3d &, const Vec3d &) const override { return {}; }
    void NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp, Vec3f *dn,
                           int count) const override;

    // Every boundary crossing of the result along the ray after tMin (for tests): t and
    // whether the ray enters the solid there.
    std::vector<std::pair<double, bool>> Crossings(const Vec3f &o, const Vec3f &d, float tMin,
                                                   Precision precision) const;

    struct Crossing;
    struct List;

  private:
    struct Leaf;
    struct Node {
        CsgOp op;
        std::vector<CsgRef> operands;
    };
    void Gather(const CsgRef &ref, const Vec3f &o, const Vec3f &d, float tMin, Precision precision,
                List *out) const;
    void GatherLeaf(int leaf, const Vec3f &o, const Vec3f &d, float tMin, Precision precision,
                    List *out) const;
    double ImplicitOf(const CsgRef &ref, const Vec3d &p) const;
    Bounds3d BoundsOf(const CsgRef &ref) const;

    std::vector<std::unique_ptr<Leaf>> leaves_;
    std::vector<Node> nodes_;
    Bounds3d bounds_;
};

}  // namespace prism
