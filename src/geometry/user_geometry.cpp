// One templated registration for every analytic shape. The callbacks handle N-wide packets
// (valid masks, SOA accessors) so rtcIntersect4/8/16 work as well as rtcIntersect1; intersect
// and occluded share the shape's single root routine, so visibility and shadows agree.
#include "geometry/user_geometry.h"

#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/hyperboloid.h"
#include "geometry/paraboloid.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"

namespace prism {

namespace {

template <typename S>
void BoundsFunc(const RTCBoundsFunctionArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    Bounds3f b = shape->WorldBounds();
    RTCBounds *o = args->bounds_o;
    o->lower_x = b.pMin.x; o->lower_y = b.pMin.y; o->lower_z = b.pMin.z;
    o->upper_x = b.pMax.x; o->upper_y = b.pMax.y; o->upper_z = b.pMax.z;
}

template <typename S, typename Real>
void IntersectFunc(const RTCIntersectFunctionNArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN *rays = RTCRayHitN_RayN(args->rayhit, N);
    RTCHitN *hits = RTCRayHitN_HitN(args->rayhit, N);
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Vec3f o(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i));
        Vec3f d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i));
        float tnear = RTCRayN_tnear(rays, N, i);
        float &tfar = RTCRayN_tfar(rays, N, i);
        ObjectHit hit;
        if (!shape->template IntersectWorld<Real>(o, d, tnear, tfar, &hit)) continue;
        float t = float(hit.t);
        if (!(t > tnear && t < tfar)) continue;  // rounding to float left the interval
        tfar = t;
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

template <typename S, typename Real>
void OccludedFunc(const RTCOccludedFunctionNArguments *args) {
    const auto *shape = static_cast<const S *>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN *rays = args->ray;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Vec3f o(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i));
        Vec3f d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i));
        float tnear = RTCRayN_tnear(rays, N, i);
        float &tfar = RTCRayN_tfar(rays, N, i);
        ObjectHit hit;
        if (!shape->template IntersectWorld<Real>(o, d, tnear, tfar, &hit)) continue;
        float t = float(hit.t);
        if (!(t > tnear && t < tfar)) continue;
        tfar = -std::numeric_limits<float>::infinity();
    }
}

template <typename S>
unsigned Attach(RTCDevice device, RTCScene scene, const S *shape, Precision precision) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, const_cast<S *>(shape));
    rtcSetGeometryBoundsFunction(geom, BoundsFunc<S>, nullptr);
    if (precision == Precision::Double) {
        rtcSetGeometryIntersectFunction(geom, IntersectFunc<S, double>);
        rtcSetGeometryOccludedFunction(geom, OccludedFunc<S, double>);
    } else {
        rtcSetGeometryIntersectFunction(geom, IntersectFunc<S, float>);
        rtcSetGeometryOccludedFunction(geom, OccludedFunc<S, float>);
    }
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return id;
}

}  // namespace

unsigned AttachUserGeometry(RTCDevice device, RTCScene scene, const AnalyticShape *shape,
                            Precision precision) {
    // The concrete type is resolved once here so the callbacks call the root routine
    // directly (no virtual dispatch per candidate).
    if (auto *s = dynamic_cast<const Sphere *>(shape)) return Attach(device, scene, s, precision);
#define PRISM_ATTACH_SHAPE(T) \
    if (auto *s = dynamic_cast<const T *>(shape)) return Attach(device, scene, s, precision);
#include "geometry/shape_list.inc"
#undef PRISM_ATTACH_SHAPE
    throw std::logic_error(std::string("no user-geometry registration for shape ") + shape->Name());
}

}  // namespace prism
