// Shape directives → geometry (an analytic shape or a triangle mesh), with pbrt-v3's
// parameter names and defaults.
#pragma once

#include <memory>

#include "core/error.h"
#include "core/memory.h"
#include "geometry/curves.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "scene/scene_description.h"

namespace prism {

struct ShapeFactoryContext {
    const SceneDescription &desc;
    Diagnostics &diag;
    Precision precision;
    // Charged, before each is allocated, with every triangle mesh the factory makes (kept) and
    // what it reads or builds it from (PLY files; checked, not kept), as `shape "type"` at the
    // shape's location. Null: a budget of the default limit for each shape alone.
    MemoryBudget *budget = nullptr;
};

struct ShapeGeometry {
    std::unique_ptr<AnalyticShape> analytic;
    std::unique_ptr<TriangleMesh> mesh;
    std::unique_ptr<CurveSet> curves;  // "curve": Embree's native curves
    bool Empty() const { return !analytic && !mesh && !curves; }
};

// Returns empty geometry (after a warning) for shapes Prism skips; throws SceneError for
// invalid parameters and MemoryBudgetError when a mesh does not fit the budget.
ShapeGeometry CreateShapeGeometry(const ShapeDesc &s, const Transform &renderFromObject,
                                  const ShapeFactoryContext &ctx);

}  // namespace prism
