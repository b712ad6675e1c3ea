#include "build/shape_factory.h"

#include <filesystem>
#include <stdexcept>

#include "core/memory.h"
#include "geometry/loop_subdiv.h"
#include "geometry/shape_list.h"
#include "scene/ply_reader.h"

namespace prism {

namespace {

const FileLoc &ParamLoc(const ShapeDesc &s, const char *name) {
    const Param *p = s.params.Find(name);
    return p ? p->loc : s.loc;
}

std::unique_ptr<TriangleMesh> MakeMesh(const ShapeDesc &s, const Transform &renderFromObject,
                                       const std::vector<Vec3f> &P, const std::vector<int> &idx,
                                       const std::vector<Vec3f> &N, const std::vector<Vec2f> &uv) {
    std::vector<uint32_t> indices;
    indices.reserve(idx.size());
    for (int i : idx) {
        if (i < 0) throw SceneError(ParamLoc(s, "indices"), "negative vertex index " + std::to_string(i));
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

ShapeGeometry TriangleMeshShape(const ShapeDesc &s, const Transform &renderFromObject,
                                Diagnostics &diag) {
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
    g.mesh = MakeMesh(s, renderFromObject, P, indices, N, uv);
    return g;
}

ShapeGeometry PlyMeshShape(const ShapeDesc &s, const Transform &renderFromObject,
                           const ShapeFactoryContext &ctx) {
    std::string file = s.params.GetString("filename", "");
    if (file.empty()) throw SceneError(s.loc, "plymesh needs a \"filename\"");
    PlyMesh ply = ReadPlyFile(ResolveScenePath(ctx.desc, file), ctx.diag, EffectiveMemoryBudget(ctx.maxMemory));
    WarnIgnored(s.params, {"displacement", "edgelength"}, ctx.diag, "plymesh",
                "displacement mapping is not supported");
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, ply.P, ply.indices, ply.N, ply.uv);
    return g;
}

// scene/'s ParamSet seen through geometry/'s ShapeParams, for the shapes' CreateShape<T>.
class ShapeDescParams final : public ShapeParams {
public:
    explicit ShapeDescParams(const ShapeDesc &s) : s_(s) {}
    const std::string &Type() const override { return s_.type; }
    bool Has(const char *name) const override { return s_.params.Has(name); }
    float Float(const char *name, float def) const override { return s_.params.GetFloat(name, def); }
    Vec3f Point3(const char *name, Vec3f def) const override {
        return s_.params.GetPoint3(name, def);
    }
    FileLoc Loc(const char *name) const override { return ParamLoc(s_, name); }

private:
    const ShapeDesc &s_;
};

// [loopsubdiv] Loop subdivision on the CPU into a triangle mesh with limit normals.
ShapeGeometry LoopSubdivShape(const ShapeDesc &s, const Transform &renderFromObject,
                              const ShapeFactoryContext &ctx) {
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
    LoopSubdivResult r;
    try {
        r = LoopSubdivide(P, indices, levels);
    } catch (const std::invalid_argument &e) {
        bool aboutLevels = std::string(e.what()).find("levels") != std::string::npos;
        throw SceneError(ParamLoc(s, aboutLevels ? levelsName : "indices"),
                         std::string("loopsubdiv: ") + e.what());
    }
    if (r.droppedFaces > 0)
        ctx.diag.Warn(ParamLoc(s, "indices"), "loopsubdiv: skipped " + std::to_string(r.droppedFaces) +
                                                  " degenerate triangle(s)");
    if (r.indices.empty()) throw SceneError(s.loc, "loopsubdiv has no non-degenerate triangles");
    ShapeGeometry g;
    g.mesh = MakeMesh(s, renderFromObject, r.P, r.indices, r.N, {});
    return g;
}

}  // namespace

ShapeGeometry CreateShapeGeometry(const ShapeDesc &s, const Transform &renderFromObject,
                                  const ShapeFactoryContext &ctx) {
#define PRISM_SHAPE(T, name)                                                       \
    if (s.type == name) {                                                          \
        ShapeGeometry g;                                                           \
        g.analytic = CreateShape<T>(ShapeDescParams(s), renderFromObject, s.reverseOrientation); \
        return g;                                                                  \
    }
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE
    if (s.type == "trianglemesh") return TriangleMeshShape(s, renderFromObject, ctx.diag);
    if (s.type == "plymesh") return PlyMeshShape(s, renderFromObject, ctx);
    if (s.type == "loopsubdiv") return LoopSubdivShape(s, renderFromObject, ctx);
    ctx.diag.WarnOnce("shape:" + s.type, s.loc,
                      "shape \"" + s.type + "\" is not supported; every such shape is skipped");
    s.params.MarkAllUsed();
    return {};
}

}  // namespace prism
