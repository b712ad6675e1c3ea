// What every shape on the list (shape_list.inc) provides, defined in the shape's own .cpp
// beside its class (pbrt-v4's Sphere::Create pattern), as explicit specializations:
//   CreateShape<T>     the shape from its pbrt parameters (defaults and checks as pbrt-v3);
//   CanonicalShape<T>  the instance `prism validate --shape NAME` tests;
//   AttachShape<T>     Embree user geometry calling T's root routine (PRISM_USER_GEOMETRY(T),
//                      geometry/user_geometry.h, one line at the end of the .cpp).
// To loop over the shapes, define PRISM_SHAPE(T, name) and include "geometry/shape_list.inc".
#pragma once

#include <memory>

#include "core/transform.h"
#include "geometry/shape.h"
#include "geometry/shape_params.h"

namespace prism {

template <typename T>
std::unique_ptr<AnalyticShape> CreateShape(const ShapeParams &params,
                                           const Transform &renderFromObject,
                                           bool reverseOrientation);
template <typename T>
std::unique_ptr<AnalyticShape> CanonicalShape(const Transform &renderFromObject);

#define PRISM_SHAPE(T, name)                                                                     \
    class T;                                                                                     \
    template <>                                                                                  \
    std::unique_ptr<AnalyticShape> CreateShape<T>(const ShapeParams &, const Transform &, bool); \
    template <>                                                                                  \
    std::unique_ptr<AnalyticShape> CanonicalShape<T>(const Transform &);
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE

}  // namespace prism
