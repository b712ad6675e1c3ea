// Registers an analytic shape as Embree user geometry (internal to src/geometry).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/shape.h"

namespace prism {

// Creates, commits and attaches a one-primitive user geometry whose callbacks forward to the
// shape's root routine in the given precision. Returns the geomID.
// `mask` is the Embree geometry mask (which ray kinds see the shape).
unsigned AttachUserGeometry(RTCDevice device, RTCScene scene, const AnalyticShape *shape,
                            Precision precision, unsigned mask);

}  // namespace prism
