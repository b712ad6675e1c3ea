#include "assembly/shape_factory.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/file_io.h"
#include "core/memory.h"
#include "geometry/bilinear_patch.h"
#include "geometry/heightfield.h"
#include "geometry/loop_subdiv.h"
#include "geometry/nurbs_patch.h"
#include "geometry/shape_list.h"
#include "scene/ply_reader.h"

namespace prism {

namespace {

const FileLoc &ParamLoc(const ShapeDesc &s, const char *name) {
    const Param *p = s.params.Find(name);
    return p ? p->loc : s.loc;
}

// The bytes of these arrays, which a mesh is made from and which are freed after.
uint64_t ArrayBytes(const std::vector<Vec3f> &P, const std::vector<int> &idx,
                    const std::vector<Vec3f> &N, const std::vector<Vec2f> &uv) {
    return P.size() * sizeof(Vec3f) + idx.size() * sizeof(int) + N.size() * sizeof(Vec3f) +
           uv.size() * sizeof(Vec2f);
}

// Charges a mesh of `meshBytes` to the budget as the shape, with `transientBytes` more that
// must fit beside it until it is made (MeshCharge, geometry/triangle_mesh.h).
void ChargeMesh(MemoryBudget &budget, const ShapeDesc &s, uint64_t meshBytes,
                uint64_t transientBytes) {
    std::string what = "shape " + Quote(s.type);
    budget.Check(meshBytes + transientBytes, what, s.loc);
    budget.Charge(meshBytes, what, s.loc);
}

// The render-space mesh, charged to the budget before it is allocated together with the
// arrays it is made from (freed when the shape's factory returns).
std::unique_ptr<TriangleMesh> MakeMesh(const ShapeDesc &s, const Transform &renderFromObject,
                                       const std::vector<Vec3f> &P, const std::vector<int> &idx,
                                       const std::vector<Vec3f> &N, const std::vector<Vec2f> &uv,
                                       MemoryBudget &budget, uint64_t transientBytes) {
    ChargeMesh(budget, s, TriangleMesh::Bytes(P.size(), idx.size(), !N.empty(), !uv.empty()),
               transientBytes);
    std::vector<uint32_t> indices;
    indices.reserve(idx.size());
    for (int i : idx) {
        if (i < 0)
            throw SceneError(ParamLoc(s, "indices"), "negative vertex index " + std::to_string(i));
        indices.push_back(uint32_t(i));
    }
    for (const Vec3f &p : P)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw SceneError(ParamLoc(s, "P"), "vertex position is not finite");
    try {
        return std::make_unique<TriangleMesh>(renderFromObject, s.reverseOrientation, P,
                                              std::move(indices), N, uv);
    } catch (const std::invalid_argument &e) {
        throw SceneError(s.loc, std::string(s.type) + ": " + e.what());
    }
}

// Shape "trianglemesh" (pbrt-v3's). Parameters:
//   indices   integer[]  —   three per triangle; required
//   P         point[]    —   the vertices; required
//   N         normal[]   —   shading normals, one per vertex
//   uv (st)   point2[]   —   texture coordinates, one per vertex
//   uv1       point2[]   —   a second uv set (glTF's TEXCOORD_1; a Prism extension)
//   tangent   float[]    —   four per vertex: tangent-space normal maps' tangents (a Prism
//                            extension)
ShapeGeometry TriangleMeshShape(const ShapeDesc &s, const Transform &renderFromObject,
                                Diagnostics &diag, MemoryBudget &budget) {
    const ParamSet &ps = s.params;
    std::vector<Vec3f> P = ps.GetPoint3s("P");
    std::vector<int> indices = ps.GetInts("indices");
    if (P.empty()) throw SceneError(s.loc, "trianglemesh needs vertex positions \"P\"");
    if (indices.empty()) {
        if (P.size() != 3) throw SceneError(s.loc, "trianglemesh needs \"indices\"");
        indices = {0, 1, 2};
    }
    std::vector<Vec3f> N = ps.GetNormals("N");
    std::vector<Vec2f> uv = ps.GetPoint2s("uv");
    if (uv.empty()) uv = ps.GetPoint2s("st");
    WarnIgnored(ps, {"S"}, diag, "trianglemesh", "shading tangents are not used");
    WarnIgnored(ps, {"faceIndices"}, diag, "trianglemesh", "face indices are not used (no ptex)");
    ShapeGeometry g;
    // The arrays read from the parameters (their storage was charged when the scene was read;
    // these float copies are at most half of it) are freed when this returns.
    g.mesh =
        MakeMesh(s, renderFromObject, P, indices, N, uv, budget, ArrayBytes(P, indices, N, uv));
    // Prism extension (glTF TEXCOORD_1): "point2 uv1", a second texture coordinate set.
    if (ps.Has("uv1")) {
        std::vector<Vec2f> uv1 = ps.GetPoint2s("uv1");
        ChargeMesh(budget, s, uv1.size() * sizeof(Vec2f), 0);
        try {
            g.mesh->SetUV1(std::move(uv1));
        } catch (const std::invalid_argument &e) {
            throw SceneError(ParamLoc(s, "uv1"), std::string(s.type) + ": " + e.what());
        }
    }
    // Prism extension (glTF TANGENT): "float tangent", xyz and the bitangent sign per vertex.
    if (ps.Has("tangent")) {
        try {
            g.mesh->SetTangents(renderFromObject, ps.GetFloats("tangent"));
        } catch (const std::invalid_argument &e) {
            throw SceneError(ParamLoc(s, "tangent"), std::string(s.type) + ": " + e.what());
        }
    }
    return g;
}

// Whether the shape is an area light whose brightness is pbrt-v4's "power".
bool EmitsByPower(const ShapeFactoryContext &ctx, const ShapeDesc &s) {
    return s.areaLight >= 0 && ctx.desc.areaLights[size_t(s.areaLight)].params.Has("power");
}

// Shape "plymesh" (pbrt-v3's). Parameters:
//   filename  string  ""  the PLY file (ASCII or binary, with normals and uv when it has
//                         them), relative to the scene; required
ShapeGeometry PlyMeshShape(const ShapeDesc &s, const Transform &renderFromObject,
                           const ShapeFactoryContext &ctx, MemoryBudget &budget) {
    std::string file = s.params.GetString("filename", "");
    if (file.empty()) throw SceneError(s.loc, "plymesh needs a \"filename\"");
    // ReadPlyFile charges the file and the mesh it reads (ply_reader.h); both are freed when
    // this returns, so that charge is given back once the render-space mesh is made and charged.
    const std::string path = ResolveScenePath(ctx.desc, file);
    const Param *fp = s.params.Find("filename");
    CheckReadConfinement(path, fp ? fp->loc : s.loc, "plymesh file", file);
    uint64_t usedBefore = budget.Used();
    PlyMesh ply = ReadPlyFile(path, ctx.diag, budget);
    uint64_t plyBytes = budget.Used() - usedBefore;
    WarnIgnored(s.params, {"displacement", "edgelength"}, ctx.diag, "plymesh",
                "displacement mapping is not supported");
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, ply.P, ply.indices, ply.N, ply.uv, budget, 0);
    budget.Release(plyBytes);
    // pbrt-v4 reads a quad as one bilinear patch: an emitter's "power" is per quad.
    if (EmitsByPower(ctx, s) && !ply.quadFirst.empty()) {
        std::vector<uint32_t> first;
        first.reserve(g.mesh->NumTriangles() - ply.quadFirst.size());
        size_t q = 0;
        for (uint32_t t = 0; t < g.mesh->NumTriangles(); ++t) {
            first.push_back(t);
            if (q < ply.quadFirst.size() && ply.quadFirst[q] == t) {
                ++q;
                ++t;  // the quad's second triangle
            }
        }
        budget.Charge(first.size() * sizeof(uint32_t), "shape \"plymesh\"", s.loc);
        g.mesh->SetPatches(std::move(first));
    }
    return g;
}

// scene/'s ParamSet seen through geometry/'s ShapeParams, for the shapes' CreateShape<T>.
class ShapeDescParams final : public ShapeParams {
  public:
    explicit ShapeDescParams(const ShapeDesc &s) : s_(s) {}
    const std::string &Type() const override { return s_.type; }
    bool Has(const char *name) const override { return s_.params.Has(name); }
    float Float(const char *name, float def) const override {
        return s_.params.GetFloat(name, def);
    }
    Vec3f Point3(const char *name, Vec3f def) const override {
        return s_.params.GetPoint3(name, def);
    }
    FileLoc Loc(const char *name) const override { return ParamLoc(s_, name); }

  private:
    const ShapeDesc &s_;
};

// Shape "loopsubdiv" (pbrt-v3's): Loop subdivision on the CPU into a triangle mesh with limit
// normals. Parameters:
//   levels (nlevels)  integer    3  subdivision steps
//   indices           integer[]  —  three per triangle; required
//   P                 point[]    —  the control mesh's vertices; required
ShapeGeometry LoopSubdivShape(const ShapeDesc &s, const Transform &renderFromObject,
                              const ShapeFactoryContext &ctx, MemoryBudget &budget) {
    const ParamSet &ps = s.params;
    const char *levelsName = ps.Has("levels") || !ps.Has("nlevels") ? "levels" : "nlevels";
    int levels = ps.GetInt(levelsName, 3);
    std::vector<Vec3f> P = ps.GetPoint3s("P");
    std::vector<int> indices = ps.GetInts("indices");
    if (P.empty()) throw SceneError(s.loc, "loopsubdiv needs vertex positions \"P\"");
    if (indices.empty()) throw SceneError(s.loc, "loopsubdiv needs \"indices\"");
    for (const Vec3f &p : P)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw SceneError(ParamLoc(s, "P"), "vertex position is not finite");
    {
        // Before subdividing: each level makes 4 triangles of one and a vertex of each edge,
        // so the output has T = 4^levels F triangles and fewer than V0 + T vertices (the
        // edges of all levels number less than 3/4 T). Its arrays (positions and normals, 24
        // bytes a vertex; indices, 12 a triangle) and the mesh made from them must fit.
        // (LoopSubdivide refuses levels and sizes beyond its limits.)
        uint64_t faces = indices.size() / 3;
        int l = std::clamp(levels, 0, MaxLoopSubdivLevels);
        uint64_t tris = std::min<uint64_t>(faces << (2 * l), MaxLoopSubdivTriangles);
        uint64_t verts = P.size() + tris;
        ChargeMesh(budget, s, 0,
                   TriangleMesh::Bytes(verts, 3 * tris, true, false) + verts * 24 + tris * 12);
    }
    LoopSubdivResult r;
    try {
        r = LoopSubdivide(P, indices, levels);
    } catch (const std::invalid_argument &e) {
        bool aboutLevels = std::string(e.what()).find("levels") != std::string::npos;
        throw SceneError(ParamLoc(s, aboutLevels ? levelsName : "indices"),
                         std::string("loopsubdiv: ") + e.what());
    }
    if (r.droppedFaces > 0)
        ctx.diag.Warn(
            ParamLoc(s, "indices"),
            "loopsubdiv: skipped " + std::to_string(r.droppedFaces) + " degenerate triangle(s)");
    if (r.indices.empty()) throw SceneError(s.loc, "loopsubdiv has no non-degenerate triangles");
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, r.P, r.indices, r.N, {}, budget,
                      ArrayBytes(r.P, r.indices, r.N, {}));
    return g;
}

// The values of a numeric parameter at the precision they were written in (ParamSet's array
// lookups round to float); `typed` is the lookup that checks the type and marks it used.
template <typename Lookup>
std::vector<double> Numbers(const ShapeDesc &s, const char *name, Lookup typed) {
    typed(name);
    const Param *p = s.params.Find(name);
    return p ? p->numbers : std::vector<double>{};
}

int RequiredInt(const ShapeDesc &s, const char *name) {
    if (!s.params.Has(name))
        throw SceneError(s.loc, s.type + " needs \"integer " + std::string(name) + "\"");
    return s.params.GetInt(name, 0);
}

// Reads one direction of a nurbs patch; the range defaults to the knots' whole domain.
void ReadNurbsDirection(const ShapeDesc &s, const char *count, const char *order, const char *knots,
                        const char *t0, const char *t1, int &n, int &k, std::vector<double> &kn,
                        double &lo, double &hi) {
    const ParamSet &ps = s.params;
    n = RequiredInt(s, count);
    k = RequiredInt(s, order);
    kn = Numbers(s, knots, [&](const char *name) { return ps.GetFloats(name); });
    if (kn.empty()) throw SceneError(s.loc, "nurbs needs \"float " + std::string(knots) + "\"");
    bool known = k >= 1 && n >= 1 && size_t(n) < kn.size() && size_t(k - 1) < kn.size();
    // At full precision: a range written as the end knots must not round out of the domain.
    auto range = [&](const char *name, double def) {
        ps.GetFloat(name, 0.f);  // checks the type, marks it used
        const Param *p = ps.Find(name);
        return p && !p->numbers.empty() ? p->numbers[0] : def;
    };
    lo = range(t0, known ? kn[size_t(k - 1)] : 0.0);
    hi = range(t1, known ? kn[size_t(n)] : 1.0);
}

// Bytes per triangle of the tessellation while it is made (the grid in double with normals,
// the patch mesh, and the render-space mesh), for the memory budget.
constexpr uint64_t NurbsBytesPerTriangle = 128;

// Shape "nurbs" (pbrt-v3's): a NURBS patch tessellated by geometry/nurbs_patch.h's rule into a
// mesh with normals and the parametric (u, v) as uv. Parameters:
//   nu, nv          integer  —  control points in u and v; required
//   uorder, vorder  integer  —  the orders (degree + 1); required
//   uknots, vknots  float[]  —  nu + uorder and nv + vorder knots; required
//   u0, u1, v0, v1  float    —  the parameter range drawn; required
//   P               point[]  —  nu nv control points, u fastest (or Pw)
//   Pw              float[]  —  nu nv rational control points x y z w (or P)
ShapeGeometry NurbsShape(const ShapeDesc &s, const Transform &renderFromObject,
                         const ShapeFactoryContext &ctx, MemoryBudget &budget) {
    const ParamSet &ps = s.params;
    NurbsPatch patch;
    ReadNurbsDirection(s, "nu", "uorder", "uknots", "u0", "u1", patch.nu, patch.uorder,
                       patch.uknots, patch.u0, patch.u1);
    ReadNurbsDirection(s, "nv", "vorder", "vknots", "v0", "v1", patch.nv, patch.vorder,
                       patch.vknots, patch.v0, patch.v1);
    bool hasP = ps.Has("P"), hasPw = ps.Has("Pw");
    if (hasP && hasPw)
        throw SceneError(ParamLoc(s, "Pw"), "nurbs takes \"point P\" or \"float Pw\", not both");
    if (!hasP && !hasPw)
        throw SceneError(s.loc, "nurbs needs control points \"point P\" or \"float Pw\"");
    const char *pointsName = hasP ? "P" : "Pw";
    if (hasP) {
        std::vector<double> xyz = Numbers(s, "P", [&](const char *n) { return ps.GetPoint3s(n); });
        patch.Pw.reserve(xyz.size() / 3 * 4);
        for (size_t i = 0; i + 2 < xyz.size(); i += 3)
            patch.Pw.insert(patch.Pw.end(), {xyz[i], xyz[i + 1], xyz[i + 2], 1.0});
    } else {
        patch.Pw = Numbers(s, "Pw", [&](const char *n) { return ps.GetFloats(n); });
        if (patch.Pw.size() % 4 != 0)
            throw SceneError(ParamLoc(s, "Pw"),
                             "nurbs \"Pw\" has " + std::to_string(patch.Pw.size()) +
                                 " values, not 4 (x w, y w, z w, w) per control point");
    }
    try {
        ValidateNurbs(patch);
    } catch (const PatchParamError &e) {
        const char *name = std::string(e.param) == "Pw" ? pointsName : e.param;
        throw SceneError(ParamLoc(s, name), e.what());
    }
    // The smallest grid must fit the triangle limit and the budget; the tessellation may then
    // refine as far as both allow.
    uint64_t minTriangles = MinNurbsTriangles(patch);
    NurbsTessellationOptions options;
    if (minTriangles > MaxNurbsTriangles)
        throw SceneError(ParamLoc(s, "nu"),
                         "nurbs patch needs at least " + std::to_string(minTriangles) +
                             " triangles (29 segments per direction and one per knot span), "
                             "more than the limit of " +
                             std::to_string(MaxNurbsTriangles));
    ChargeMesh(budget, s, 0, minTriangles * NurbsBytesPerTriangle);
    options.maxTriangles = std::clamp<uint64_t>(budget.Remaining() / NurbsBytesPerTriangle,
                                                minTriangles, MaxNurbsTriangles);
    NurbsTessellation t = TessellateNurbs(patch, options);
    if (t.capped)
        ctx.diag.Warn(
            s.loc, "nurbs: tessellation stopped at " + std::to_string(t.mesh.indices.size() / 3) +
                       " triangles (the limit); chordal error " + std::to_string(t.chordalError) +
                       ", asked " + std::to_string(t.tolerance));
    const PatchMesh &m = t.mesh;
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, m.P, m.indices, m.N, m.uv, budget,
                      ArrayBytes(m.P, m.indices, m.N, m.uv));
    return g;
}

// Shape "heightfield" (pbrt-v3's): heights over the unit square (geometry/heightfield.h).
// Parameters:
//   nu, nv  integer  —  the grid's size; required
//   Pz      float[]  —  nu nv heights, u fastest; required
ShapeGeometry HeightfieldShape(const ShapeDesc &s, const Transform &renderFromObject,
                               MemoryBudget &budget) {
    int nu = RequiredInt(s, "nu"), nv = RequiredInt(s, "nv");
    std::vector<double> Pz = Numbers(s, "Pz", [&](const char *n) { return s.params.GetFloats(n); });
    if (Pz.empty()) throw SceneError(s.loc, "heightfield needs heights \"float Pz\"");
    PatchMesh m;
    try {
        m = TessellateHeightfield(nu, nv, Pz);
    } catch (const PatchParamError &e) {
        throw SceneError(ParamLoc(s, e.param), e.what());
    }
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, m.P, m.indices, {}, m.uv, budget,
                      ArrayBytes(m.P, m.indices, {}, m.uv));
    return g;
}

// Shape "bilinearmesh" (pbrt-v4's): bilinear patches tessellated into triangles within 2e-4
// of each patch's size (geometry/bilinear_patch.h). Parameters:
//   P                 point3[]   —   the vertices; required
//   indices           integer[]  —   four per patch (p00, p10, p01, p11); required unless P
//                                    has exactly 4 points
//   N                 normal[]   —   shading normals, one per vertex
//   uv                point2[]   —   texture coordinates, one per vertex (default: each
//                                    patch's (u, v))
//   faceIndices       integer[]  —   ptex face indices: not used (no ptex)
//   emissionfilename  string     ""  pbrt-v4 samples an emitting patch by this image: a choice
//                                    of sampling density only, so the image is the same;
//                                    Prism samples by area
ShapeGeometry BilinearMeshShape(const ShapeDesc &s, const Transform &renderFromObject,
                                Diagnostics &diag, MemoryBudget &budget) {
    const ParamSet &ps = s.params;
    BilinearMesh m;
    m.P = ps.GetPoint3s("P");
    m.indices = ps.GetInts("indices");
    if (m.indices.empty() && m.P.size() == 4) m.indices = {0, 1, 2, 3};
    m.N = ps.GetNormals("N");
    m.uv = ps.GetPoint2s("uv");
    WarnIgnored(ps, {"faceIndices"}, diag, "bilinearmesh", "face indices are not used (no ptex)");
    ps.MarkUsed("emissionfilename");
    std::vector<int> segments;
    try {
        ValidateBilinearMesh(m);
        segments = BilinearSegments(m);
    } catch (const PatchParamError &e) {
        throw SceneError(ParamLoc(s, e.param), e.what());
    }
    // The tessellation's arrays, checked against the budget before they are made.
    const uint64_t triangles = BilinearTriangles(segments);
    const uint64_t vertices = BilinearVertices(segments);
    const uint64_t arrays =
        vertices * (2 * sizeof(Vec3f) + sizeof(Vec2f)) + 3 * triangles * sizeof(int);
    budget.Check(arrays + TriangleMesh::Bytes(vertices, 3 * triangles, true, true),
                 "shape \"bilinearmesh\"", s.loc);
    const PatchMesh t = TessellateBilinearMesh(m, segments);
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, t.P, t.indices, t.N, t.uv, budget,
                      ArrayBytes(t.P, t.indices, t.N, t.uv));
    // Each patch is one pbrt-v4 shape (an emitter's "power" is per patch).
    std::vector<uint32_t> first = BilinearPatchFirstTriangles(segments);
    budget.Charge(first.size() * sizeof(uint32_t), "shape \"bilinearmesh\"", s.loc);
    g.mesh->SetPatches(std::move(first));
    return g;
}

// Shape "curve" (pbrt-v3's; docs/FORMAT.md "Curves"), as Embree's native Bézier curves.
// Parameters:
//   P               point[]   —         control points: degree n + 1 for bezier, n + degree
//                                       for bspline (n segments)
//   basis           string    "bezier"  bezier | bspline
//   degree          integer   3         3 | 2 (elevated to cubic, exactly)
//   type            string    "flat"    flat (faces each ray) | cylinder (a swept tube) |
//                                       ribbon (oriented by N)
//   width           float     1         the width everywhere, unless width0 and width1
//   width0, width1  float     width     the width at the curve's start and end, linear in
//                                       between
//   N               normal[]  —         ribbon: one per segment end (n + 1)
//   splitdepth      integer   3         pbrt-v3 splits each segment 2^splitdepth times for
//                                       its own intersector; here the ray-facing quads per
//                                       segment Embree tessellates a flat curve into
//                                       (2^splitdepth, 1 to 64; cylinders and ribbons do not
//                                       change)
ShapeGeometry CurveShape(const ShapeDesc &s, const Transform &renderFromObject,
                         const ShapeFactoryContext &ctx, MemoryBudget &budget) {
    const ParamSet &ps = s.params;
    std::vector<Vec3f> P = ps.GetPoint3s("P");
    if (P.empty()) throw SceneError(s.loc, "curve needs control points \"P\"");
    for (const Vec3f &p : P)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw SceneError(ParamLoc(s, "P"), "curve control point is not finite");
    const std::string basis = ps.GetString("basis", "bezier");
    if (basis != "bezier" && basis != "bspline")
        throw SceneError(ParamLoc(s, "basis"),
                         "curve \"basis\" must be \"bezier\" or "
                         "\"bspline\", not " +
                             Quote(basis));
    const int degree = ps.GetInt("degree", 3);
    if (degree != 2 && degree != 3)
        throw SceneError(ParamLoc(s, "degree"),
                         "curve \"degree\" must be 2 or 3, not " + std::to_string(degree));
    const std::string typeName = ps.GetString("type", "flat");
    CurveType type;
    if (typeName == "flat")
        type = CurveType::Flat;
    else if (typeName == "cylinder")
        type = CurveType::Cylinder;
    else if (typeName == "ribbon")
        type = CurveType::Ribbon;
    else
        throw SceneError(
            ParamLoc(s, "type"),
            "curve \"type\" must be \"flat\", \"cylinder\" or \"ribbon\", not " + Quote(typeName));
    const bool bspline = basis == "bspline";
    const size_t segments = CurveSegmentCount(P.size(), degree, bspline);
    if (segments == 0 || segments > MaxCurveSegments)
        throw SceneError(
            ParamLoc(s, "P"),
            "curve has " + std::to_string(P.size()) + " control points; a " + basis +
                " curve of degree " + std::to_string(degree) + " and n segments has " +
                (bspline ? "n + " + std::to_string(degree) : std::to_string(degree) + "n + 1") +
                " (n from 1 to " + std::to_string(MaxCurveSegments) + ")");
    const float width = ps.GetFloat("width", 1.f);
    const float width0 = ps.GetFloat("width0", width), width1 = ps.GetFloat("width1", width);
    for (auto [name, w] : {std::pair{"width", width}, {"width0", width0}, {"width1", width1}})
        if (!(w >= 0) || !std::isfinite(w))
            throw SceneError(ParamLoc(s, name),
                             std::string("curve \"") + name + "\" must be a finite width >= 0");
    std::vector<Vec3f> N;
    if (type == CurveType::Ribbon) {
        N = ps.GetNormals("N");
        if (N.empty())
            throw SceneError(s.loc,
                             "a \"ribbon\" curve needs normals \"N\" at its segments' "
                             "ends (" +
                                 std::to_string(segments + 1) + ")");
        if (N.size() != segments + 1)
            throw SceneError(ParamLoc(s, "N"),
                             "a ribbon curve of " + std::to_string(segments) +
                                 " segment(s) needs " + std::to_string(segments + 1) +
                                 " normals \"N\", not " + std::to_string(N.size()));
        for (size_t i = 0; i < N.size(); ++i)
            if (!std::isfinite(N[i].x) || !std::isfinite(N[i].y) || !std::isfinite(N[i].z) ||
                LengthSquared(N[i]) == 0)
                throw SceneError(ParamLoc(s, "N"),
                                 "curve normal " + std::to_string(i) + " is zero or not finite");
    } else {
        WarnIgnored(ps, {"N"}, ctx.diag, "curve", "normals are read for \"ribbon\" curves only");
    }
    const int splitDepth = std::clamp(ps.GetInt("splitdepth", 3), 0, 6);
    // The set, and the Bézier control points it is made from (freed after).
    ChargeMesh(budget, s, CurveSet::Bytes(segments, type == CurveType::Ribbon),
               segments * 4 * sizeof(Vec3f));
    ShapeGeometry g;
    try {
        g.curves = std::make_unique<CurveSet>(renderFromObject, s.reverseOrientation, type,
                                              CubicBezierSegments(P, degree, bspline), width0,
                                              width1, N, 1 << splitDepth);
    } catch (const std::invalid_argument &e) {
        throw SceneError(s.loc, std::string("curve: ") + e.what());
    }
    return g;
}

}  // namespace

ShapeGeometry CreateShapeGeometry(const ShapeDesc &s, const Transform &renderFromObject,
                                  const ShapeFactoryContext &ctx) {
#define PRISM_SHAPE(T, name)                                                                     \
    if (s.type == name) {                                                                        \
        ShapeGeometry g;                                                                         \
        g.analytic = CreateShape<T>(ShapeDescParams(s), renderFromObject, s.reverseOrientation); \
        return g;                                                                                \
    }
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE
    MemoryBudget ownBudget(ctx.budget ? 1 : 0);  // the default limit, without a budget given
    MemoryBudget &budget = ctx.budget ? *ctx.budget : ownBudget;
    if (s.type == "trianglemesh") return TriangleMeshShape(s, renderFromObject, ctx.diag, budget);
    if (s.type == "plymesh") return PlyMeshShape(s, renderFromObject, ctx, budget);
    if (s.type == "loopsubdiv") return LoopSubdivShape(s, renderFromObject, ctx, budget);
    if (s.type == "nurbs") return NurbsShape(s, renderFromObject, ctx, budget);
    if (s.type == "heightfield") return HeightfieldShape(s, renderFromObject, budget);
    if (s.type == "curve") return CurveShape(s, renderFromObject, ctx, budget);
    if (s.type == "bilinearmesh") return BilinearMeshShape(s, renderFromObject, ctx.diag, budget);
    ctx.diag.WarnOnce("shape:" + s.type, s.loc,
                      "shape \"" + s.type + "\" is not supported; every such shape is skipped");
    s.params.MarkAllUsed();
    return {};
}

}  // namespace prism
