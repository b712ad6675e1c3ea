// Registers an analytic shape as Embree user geometry (internal to src/geometry). The callbacks
// handle N-wide packets (valid masks, SOA accessors) so rtcIntersect4/8/16 work as well as
// rtcIntersect1; intersect and occluded share the shape's single root routine, so visibility
// and shadows agree.
#pragma once

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "geometry/shape.h"

namespace prism {

// Creates, commits and attaches a one-primitive user geometry whose callbacks forward to the
// shape's root routine in the given precision. Returns the geomID.
// `mask` is the Embree geometry mask (which ray kinds see the shape).
unsigned AttachUserGeometry(RTCDevice device, RTCScene scene, const AnalyticShape *shape,
                            Precision precision, unsigned mask);

// For each listed shape T (shape_list.inc): attaches `shape` with T's root routine called
// directly (no virtual dispatch per candidate) if it is a T, else returns
// RTC_INVALID_GEOMETRY_ID. Defined in T's .cpp by PRISM_USER_GEOMETRY(T).
template <typename T>
unsigned AttachShape(RTCDevice device, RTCScene scene, const AnalyticShape &shape,
                     Precision precision, unsigned mask);
#define PRISM_SHAPE(T, name) \
    class T;                 \
    template <>              \
    unsigned AttachShape<T>(RTCDevice, RTCScene, const AnalyticShape &, Precision, unsigned);
#include "geometry/shape_list.inc"
#undef PRISM_SHAPE

// The intersect context Accel passes to rtcIntersect*: Embree hands it to the callbacks, which
// record there the object-space hit of the last analytic hit accepted for each ray (indexed by
// RTCRay::id, top-level shapes only), so Accel::Interaction need not run the root routine again.
struct HitContext {
    RTCIntersectContext ctx;  // first: Embree sees only this part
    ObjectHit *objectHits = nullptr;
    unsigned *objectGeom = nullptr;  // geomID of each recorded hit
    unsigned numRays = 0;            // entries of both arrays (0: nothing is recorded)
};

namespace user_geometry_detail {

// Moving shapes (AnalyticShape::Motion) have one box per Embree time step.
template <typename S, bool Moving>
inline void BoundsFunc(const RTCBoundsFunctionArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    Bounds3f b = Moving ? shape->RenderBoundsAtStep(int(args->timeStep)) : shape->RenderBounds();
    RTCBounds *o = args->bounds_o;
    o->lower_x = b.pMin.x;
    o->lower_y = b.pMin.y;
    o->lower_z = b.pMin.z;
    o->upper_x = b.pMax.x;
    o->upper_y = b.pMax.y;
    o->upper_z = b.pMax.z;
}

// [validate hook] Shapes outside the list below (test-only intersectors, e.g. the broken
// sphere that `prism validate`'s tests must catch) are attached as AnalyticShape and reached
// through the virtual Intersect: one indirect call per candidate, fine for them.
// A moving shape's routine runs with its transform interpolated at the ray's time.
template <typename S, typename Real, bool Moving>
inline bool RootRoutine(const S *shape, const Vec3f &o, const Vec3f &d, float tnear, float tfar,
                        float time, ObjectHit *hit) {
    constexpr Precision precision =
        std::is_same_v<Real, float> ? Precision::Float : Precision::Double;
    if constexpr (std::is_same_v<S, AnalyticShape>) {
        if constexpr (Moving)
            return shape->IntersectAt(o, d, tnear, tfar, precision, time, hit);
        else
            return shape->Intersect(o, d, tnear, tfar, precision, hit);
    } else if constexpr (Moving) {
        return shape->template IntersectRenderWith<Real>(
            shape->template ObjectFromRenderAt<Real>(time), o, d, tnear, tfar, hit);
    } else {
        return shape->template IntersectRender<Real>(o, d, tnear, tfar, hit);
    }
}

// The shared root routine for lane i of an N-wide ray packet: true with the float t of the
// nearest valid hit inside the lane's (tnear, tfar). A shape with a cut-out for this kind of ray
// (`test`, geometry/alpha.h) skips the hits the test rejects and tries the next root beyond.
template <typename S, typename Real, bool Moving>
inline bool LaneHit(const S *shape, RTCRayN *rays, unsigned N, unsigned i, float *tHit,
                    ObjectHit *hit, const AlphaTest *test = nullptr) {
    Vec3f o(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i));
    Vec3f d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i));
    float tnear = RTCRayN_tnear(rays, N, i), tfar = RTCRayN_tfar(rays, N, i);
    float time = Moving ? RTCRayN_time(rays, N, i) : 0.f;
    // A quartic has at most four roots: a few more tries than that end the search.
    for (int tries = 0; tries < 8; ++tries) {
        if (!RootRoutine<S, Real, Moving>(shape, o, d, tnear, tfar, time, hit)) return false;
        float t = float(hit->t);
        *tHit = t;
        if (!(t > tnear && t < tfar)) return false;  // rounding to float may leave the interval
        if (!test) return true;
        SurfaceInteraction si = shape->Interaction(*hit, d, NeedUV, time);
        if (test->Keeps(si.uv, si.p, o, d, 0)) return true;
        // Past this root (whose double t may lie just above its float rounding).
        tnear = std::nextafter(t, std::numeric_limits<float>::infinity());
    }
    return false;
}

template <typename S, typename Real, bool Moving>
inline void IntersectFunc(const RTCIntersectFunctionNArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN *rays = RTCRayHitN_RayN(args->rayhit, N);
    RTCHitN *hits = RTCRayHitN_HitN(args->rayhit, N);
    const auto *hc = reinterpret_cast<const HitContext *>(args->context);
    const bool record = args->context->instID[0] == RTC_INVALID_GEOMETRY_ID;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        float t;
        ObjectHit hit;
        if (!LaneHit<S, Real, Moving>(shape, rays, N, i, &t, &hit, shape->Alpha().camera.get()))
            continue;
        RTCRayN_tfar(rays, N, i) = t;
        if (unsigned id = RTCRayN_id(rays, N, i); record && id < hc->numRays) {
            hc->objectHits[id] = hit;
            hc->objectGeom[id] = args->geomID;
        }
        // Ng is not computed here: shading geometry is built once, after traversal.
        RTCHitN_Ng_x(hits, N, i) = 0;
        RTCHitN_Ng_y(hits, N, i) = 0;
        RTCHitN_Ng_z(hits, N, i) = 0;
        RTCHitN_u(hits, N, i) = 0;
        RTCHitN_v(hits, N, i) = 0;
        RTCHitN_primID(hits, N, i) = args->primID;
        RTCHitN_geomID(hits, N, i) = args->geomID;
        RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
    }
}

template <typename S, typename Real, bool Moving>
inline void OccludedFunc(const RTCOccludedFunctionNArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN *rays = args->ray;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        float t;
        ObjectHit hit;
        if (LaneHit<S, Real, Moving>(shape, rays, N, i, &t, &hit, shape->Alpha().shadow.get()))
            RTCRayN_tfar(rays, N, i) = -std::numeric_limits<float>::infinity();
    }
}

template <typename S, bool Moving>
inline void SetCallbacks(RTCGeometry geom, Precision precision) {
    rtcSetGeometryBoundsFunction(geom, BoundsFunc<S, Moving>, nullptr);
    if (precision == Precision::Double) {
        rtcSetGeometryIntersectFunction(geom, IntersectFunc<S, double, Moving>);
        rtcSetGeometryOccludedFunction(geom, OccludedFunc<S, double, Moving>);
    } else {
        rtcSetGeometryIntersectFunction(geom, IntersectFunc<S, float, Moving>);
        rtcSetGeometryOccludedFunction(geom, OccludedFunc<S, float, Moving>);
    }
}

template <typename S>
inline unsigned Attach(RTCDevice device, RTCScene scene, const S *shape, Precision precision,
                       unsigned mask) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, const_cast<S *>(shape));
    if (shape->Motion()) {
        rtcSetGeometryTimeStepCount(geom, unsigned(shape->MotionTimeSteps()));
        SetCallbacks<S, true>(geom, precision);
    } else {
        SetCallbacks<S, false>(geom, precision);
    }
    rtcSetGeometryMask(geom, mask);
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return id;
}

}  // namespace user_geometry_detail

#define PRISM_USER_GEOMETRY(T)                                                            \
    template <>                                                                           \
    unsigned AttachShape<T>(RTCDevice device, RTCScene scene, const AnalyticShape &shape, \
                            Precision precision, unsigned mask) {                         \
        const T *t = dynamic_cast<const T *>(&shape);                                     \
        return t ? user_geometry_detail::Attach(device, scene, t, precision, mask)        \
                 : RTC_INVALID_GEOMETRY_ID;                                               \
    }

}  // namespace prism
