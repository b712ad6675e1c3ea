// The full description of a closest hit, computed once after traversal (phase 2).
#pragma once

#include <cstdint>

#include "core/vecmath.h"
#include "geometry/ray.h"

namespace prism {

struct SurfaceInteraction {
    Vec3f p;        // render-space hit point
    Vec3f pError;   // conservative absolute error of p, per component
    Vec3f n;        // unit geometric normal, pbrt orientation (not turned toward the ray)
    Vec3f ns;       // unit shading normal, in n's hemisphere
    Vec3f dpdu, dpdv;
    Vec2f uv;
    Vec3f wo;       // unit direction back along the incoming ray
    float t = 0;    // ray parameter in units of the incoming ray's direction
    int shape = -1; // index of the shape in the render scene
    int prim = 0;   // primitive within the shape (triangle index; 0 for analytic shapes)
    int instanceShape = -1;  // for hits inside an instance: the shape within the prototype

    Ray SpawnRay(const Vec3f &d) const {
        return {OffsetRayOrigin(p, pError, n, d), d, Infinity};
    }
    // A shadow ray toward pTo that stops (1 - ShadowEpsilon) of the way there.
    Ray SpawnRayTo(const Vec3f &pTo) const {
        Vec3f o = OffsetRayOrigin(p, pError, n, pTo - p);
        return {o, pTo - o, 1 - ShadowEpsilon};
    }
};

}  // namespace prism
