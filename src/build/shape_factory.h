// Shape directives → geometry (an analytic shape or a triangle mesh), with pbrt-v3's
// parameter names and defaults.
#pragma once

#include <memory>

#include "core/error.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "scene/scene_description.h"

namespace prism {

struct ShapeFactoryContext {
    const SceneDescription &desc;
    Diagnostics &diag;
    Precision precision;
    uint64_t maxMemory = 0;  // bytes, for PLY meshes (0: the default budget)
};

struct ShapeGeometry {
    std::unique_ptr<AnalyticShape> analytic;
    std::unique_ptr<TriangleMesh> mesh;
};

// Returns empty geometry (after a warning) for shapes Prism skips; throws SceneError for
// invalid parameters.
ShapeGeometry CreateShapeGeometry(const ShapeDesc &s, const Transform &renderFromObject,
                                  const ShapeFactoryContext &ctx);

}  // namespace prism
