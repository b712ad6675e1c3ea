// The full description of a closest hit, computed once after traversal (phase 2).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/vecmath.h"
#include "geometry/ray.h"

namespace prism {

// What a hit's material reads beyond p, n, ns, wo and t (Material::SurfaceNeeds, set per shape
// with Accel::SetSurfaceNeeds). Shapes skip what is not asked for and leave it zero: uv for
// textures that are not constant, dpdu/dpdv for a tangent frame (anisotropic roughness). A
// zero dpdu makes BSDF::SetFrame fall back to CoordinateSystem(ns), which only rotates the
// frame about ns and so changes no isotropic BSDF beyond float rounding.
enum SurfaceNeeds : unsigned { NeedNone = 0, NeedUV = 1, NeedDpdu = 2, NeedAll = 3 };

// A render-space hit point computed in double, as float: *p, and *pError = errW (the double
// computation's bound) plus the exact rounding to float plus one float ulp of headroom.
// OpaqueFloat keeps the rounding the second term measures (core/vecmath.h).
inline void RoundHitPoint(const Vec3d &pW, const Vec3d &errW, Vec3f *p, Vec3f *pError) {
    *p = OpaqueFloat(pW);
    auto bound = [](double w, double err, float f) {
        return float(err + std::abs(double(f) - w) + std::abs(w) * MachineEpsilon<float>());
    };
    *pError =
        Vec3f(bound(pW.x, errW.x, p->x), bound(pW.y, errW.y, p->y), bound(pW.z, errW.z, p->z));
}

struct SurfaceInteraction {
    Vec3f p;                 // render-space hit point
    Vec3f pError;            // conservative absolute error of p, per component
    Vec3f n;                 // unit geometric normal, pbrt orientation (not turned toward the ray)
    Vec3f ns;                // unit shading normal, in n's hemisphere
    Vec3f dpdu, dpdv;        // zero unless NeedDpdu
    Vec2f uv;                // zero unless NeedUV
    Vec2f uv1;               // second texture coordinate set (meshes' "uv1"; else uv), as uv
    Vec3f wo;                // unit direction back along the incoming ray
    float t = 0;             // ray parameter in units of the incoming ray's direction
    int shape = -1;          // index of the shape in the render scene
    int prim = 0;            // primitive within the shape (triangle index; 0 for analytic shapes)
    int instanceShape = -1;  // for hits inside an instance: the shape within the prototype
    float time = 0;          // the incoming ray's time (Ray::time), inherited by spawned rays

    Ray SpawnRay(const Vec3f &d) const {
        return {OffsetRayOrigin(p, pError, n, d), d, Infinity, 0, time};
    }
    // A shadow ray toward pTo that stops (1 - ShadowEpsilon) of the way there.
    Ray SpawnRayTo(const Vec3f &pTo) const {
        Vec3f o = OffsetRayOrigin(p, pError, n, pTo - p);
        return {o, pTo - o, 1 - ShadowEpsilon, 0, time};
    }
    // The same with the offset method of the render (RenderScene::offset; the default
    // RayOffset gives exactly the rays above).
    Ray SpawnRay(const Vec3f &d, const RayOffset &off) const {
        return {SpawnOrigin(p, pError, n, d, off), d, Infinity, 0, time};
    }
    // (Always inlined: the kernels spawn a shadow ray per light and hit, and GCC 12 otherwise
    // keeps it out of line in some of them.)
    [[gnu::always_inline]] Ray SpawnRayTo(const Vec3f &pTo, const RayOffset &off) const {
        Vec3f o = SpawnOrigin(p, pError, n, pTo - p, off);
        return {o, pTo - o, 1 - ShadowEpsilon, 0, time};
    }
};

}  // namespace prism
