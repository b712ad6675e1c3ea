// The equal-area mapping between the unit square and the unit sphere (Clarberg 2008, "Fast
// equal-area mapping of the (hemi)sphere using SIMD"): the square's centre is +z, its corners
// -z, and each diamond between the centre and the edge midpoints is one octant. Equal areas of
// the square are equal solid angles (4π per unit area), so a map stored this way needs no
// sin θ weighting to be sampled. pbrt-v4's environment maps (LightSource "infinite"
// "filename") are square images in this projection.
#pragma once

#include "core/vecmath.h"

namespace prism {

// p in [0, 1]² to a unit direction.
Vec3d EqualAreaSquareToSphere(Vec2d p);
// A unit direction to [0, 1]²; the inverse of EqualAreaSquareToSphere.
Vec2d EqualAreaSphereToSquare(const Vec3d &w);

}  // namespace prism
