// Registers an analytic shape as Embree user geometry (internal to src/geometry).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/shape.h"

namespace prism {

// Creates, commits and attaches a one-primitive user geometry whose callbacks forward to the
// shape's root routine in the given precision. Returns the geomID.
unsigned AttachUserGeometry(RTCDevice device, RTCScene scene, const AnalyticShape *shape,
                            Precision precision);

}  // namespace prism
