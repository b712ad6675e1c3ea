// Embree user-geometry attachment for every analytic shape: the shapes on the list first
// (their own root routines, resolved once here), then any other AnalyticShape through the
// virtual Intersect.
#include "geometry/user_geometry.h"

namespace prism {

unsigned AttachUserGeometry(RTCDevice device, RTCScene scene, const AnalyticShape *shape,
                            Precision precision, unsigned mask) {
#define PRISM_SHAPE(T, name)                                                  \
    if (unsigned id = AttachShape<T>(device, scene, *shape, precision, mask); \
        id != RTC_INVALID_GEOMETRY_ID)                                        \
        return id;
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE
    // [validate hook] test-only intersectors (e.g. the broken sphere `prism validate`'s tests
    // must catch): one indirect call per candidate, fine for them.
    return user_geometry_detail::Attach(device, scene, shape, precision, mask);
}

}  // namespace prism
