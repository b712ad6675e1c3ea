#include "assembly/csg.h"

#include <stdexcept>

#include "assembly/media.h"
#include "assembly/shape_factory.h"
#include "core/memory.h"

namespace prism {

namespace {

struct CsgBuilder : BuildStep {
    CsgBuilder(BuildContext &c, MaterialBuilder &m, CsgShape &s, std::vector<ShapeInfo> &o)
        : BuildStep(c), materials(m), csg(s), operands(o) {}
    MaterialBuilder &materials;
    CsgShape &csg;
    std::vector<ShapeInfo> &operands;

    int AddLeaf(const ShapeDesc &s) {
        ShapeFactoryContext fctx{desc, diag, settings.precision, &budget};
        ShapeGeometry geom =
            CreateShapeGeometry(s, scene.renderFromWorld * s.worldFromObject, fctx);
        if (!geom.mesh && !geom.analytic)
            throw SceneError(s.loc, "shape " + Quote(s.type) +
                                        " cannot be a CSG operand (analytic shapes and closed "
                                        "triangle meshes can)");
        if (s.areaLight >= 0)
            diag.Warn(s.loc,
                      "area lights on CSG operands are not supported; the shape does not emit");
        if (s.motion)
            diag.Warn(s.loc,
                      "motion blur of CSG operands is not supported; the operand stays "
                      "where its start transform puts it");
        for (const char *n : {"alpha", "shadowalpha"})
            if (s.params.Has(n)) {
                diag.Warn(s.loc, std::string("\"") + n + "\" is ignored on CSG operands");
                s.params.MarkUsed(n);
            }
        int material = materials.MaterialForShape(s);
        s.params.ReportUnused(diag, "shape " + Quote(s.type));
        int leaf;
        if (geom.mesh) {
            std::string error = MeshClosedError(*geom.mesh);
            if (!error.empty())
                throw SceneError(s.loc, "CSG operand " + Quote(s.type) + ": " + error);
            // The operand's own BVH (the fixed part is charged once, with the top level).
            budget.Charge(EstimateBvhBytes(geom.mesh->NumTriangles(), 0) - kBvhFixedBytes, "BVH",
                          s.loc);
            scene.features.meshes++;
            scene.features.triangles += geom.mesh->NumTriangles();
            leaf = csg.AddLeaf(std::move(geom.mesh));
        } else {
            scene.features.analyticShapes++;
            leaf = csg.AddLeaf(std::move(geom.analytic));
        }
        if (int(operands.size()) <= leaf) operands.resize(size_t(leaf) + 1);
        operands[size_t(leaf)] = {material, -1, s.directiveIndex, s.type, -1};
        NoteShapeMedia(ctx, s, &operands[size_t(leaf)]);
        return leaf;
    }

    int AddNode(const CsgDesc &node) {
        CsgOp op;
        if (!ParseCsgOp(node.op, &op))
            throw SceneError(node.loc, "unknown CSG operation " + Quote(node.op));
        std::vector<CsgRef> refs;
        for (const CsgDesc::Operand &o : node.operands) {
            if (o.shape)
                refs.push_back({true, AddLeaf(node.shapes[size_t(o.index)])});
            else
                refs.push_back({false, AddNode(node.children[size_t(o.index)])});
        }
        if (refs.empty()) throw SceneError(node.loc, "empty CSG node");
        return csg.AddNode(op, std::move(refs));
    }
};

}  // namespace

std::unique_ptr<CsgShape> BuildCsgShape(BuildContext &ctx, MaterialBuilder &materials,
                                        const CsgDesc &node, std::vector<ShapeInfo> *operands) {
    auto csg = std::make_unique<CsgShape>();
    CsgBuilder(ctx, materials, *csg, *operands).AddNode(node);
    try {
        csg->Finish();
    } catch (const std::exception &e) {
        throw SceneError(node.loc, std::string("CSG: ") + e.what());
    }
    return csg;
}

}  // namespace prism
