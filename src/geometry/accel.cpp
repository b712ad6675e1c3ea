#include "geometry/accel.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "core/check.h"
#include "geometry/sphere.h"
#include "geometry/user_geometry.h"

namespace prism {

namespace {

// Device errors are collected (not printed from the callback) so they can be raised as
// exceptions at the call that caused them.
struct DeviceErrors {
    std::mutex mutex;
    std::string last;
};

void DeviceErrorCallback(void *user, RTCError code, const char *str) {
    auto *errors = static_cast<DeviceErrors *>(user);
    std::lock_guard<std::mutex> lock(errors->mutex);
    errors->last = std::string("Embree error ") + std::to_string(int(code)) + ": " +
                   (str ? str : "(no message)");
}

// One Embree device per process: devices are heavyweight and thread-safe.
struct Device {
    RTCDevice device = nullptr;
    DeviceErrors errors;
    Device() {
        // No "threads=N" here: on a TBB build it installs a process-wide global_control
        // (docs/SHAPES.md E4). Threads are limited by the application instead.
        device = rtcNewDevice(nullptr);
        if (!device) throw std::runtime_error("cannot create Embree device");
        rtcSetDeviceErrorFunction(device, DeviceErrorCallback, &errors);
    }
    ~Device() { rtcReleaseDevice(device); }
    void ThrowIfError(const char *what) {
        std::lock_guard<std::mutex> lock(errors.mutex);
        if (!errors.last.empty()) {
            std::string msg = std::string(what) + ": " + errors.last;
            errors.last.clear();
            throw std::runtime_error(msg);
        }
    }
};

Device &GetDevice() {
    static Device device;
    return device;
}

void InitRay(const Ray &r, RTCRay *ray, unsigned mask) {
    ray->org_x = r.o.x;
    ray->org_y = r.o.y;
    ray->org_z = r.o.z;
    ray->dir_x = r.d.x;
    ray->dir_y = r.d.y;
    ray->dir_z = r.d.z;
    ray->tnear = r.tMin;
    ray->tfar = r.tMax;
    ray->time = r.time;
    ray->mask = mask;  // CameraRays or ShadowRays; a zero mask would hit nothing
    ray->id = 0;
    ray->flags = 0;
}

// Embree's interpolation of a moving instance's step matrices at `time`, in double.
Transform InstanceTransformAt(const std::vector<Matrix4> &steps, float time) {
    const int n = int(steps.size());
    float ft = time * float(n - 1);
    int seg = std::clamp(int(std::floor(ft)), 0, n - 2);
    double f = double(ft - float(seg));
    Matrix4 m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            m.m[i][j] = (1 - f) * steps[size_t(seg)].m[i][j] + f * steps[size_t(seg) + 1].m[i][j];
    Matrix4 inv;
    if (!m.Inverse(&inv)) return Transform(steps[size_t(seg)]);
    return Transform(m, inv);
}

void InitRay16(const Ray &r, int i, unsigned mask, RTCRay16 *ray) {
    ray->org_x[i] = r.o.x;
    ray->org_y[i] = r.o.y;
    ray->org_z[i] = r.o.z;
    ray->dir_x[i] = r.d.x;
    ray->dir_y[i] = r.d.y;
    ray->dir_z[i] = r.d.z;
    ray->tnear[i] = r.tMin;
    ray->tfar[i] = r.tMax;
    ray->time[i] = r.time;
    ray->mask[i] = mask;
    ray->id[i] = unsigned(i);
    ray->flags[i] = 0;
}

// A mesh's cut-outs, the user data of its Embree geometry.
struct MeshAlpha {
    const TriangleMesh *mesh;
    ShapeAlpha alpha;
};

// Embree's intersection (Shadow false) and occlusion (true) filter for a mesh with cut-outs:
// rejects the candidate hits its AlphaTest does not keep. Embree passes the candidate's
// distance as the ray's tfar.
template <bool Shadow>
void MeshAlphaFilter(const RTCFilterFunctionNArguments *args) {
    const auto *ma = static_cast<const MeshAlpha *>(args->geometryUserPtr);
    const AlphaTest *test = Shadow ? ma->alpha.shadow.get() : ma->alpha.camera.get();
    if (!test) return;
    const unsigned N = args->N;
    RTCRayN *ray = args->ray;
    RTCHitN *hit = args->hit;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Vec3f o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        Vec3f d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        const unsigned prim = RTCHitN_primID(hit, N, i);
        Vec2f uv = ma->mesh->UVAt(prim, RTCHitN_u(hit, N, i), RTCHitN_v(hit, N, i), test->uvSet);
        Vec3f p = o + d * RTCRayN_tfar(ray, N, i);
        if (!test->Keeps(uv, p, o, d, prim)) args->valid[i] = 0;
    }
}

}  // namespace

struct Accel::Impl {
    AccelOptions options;
    RTCScene scene = nullptr;
    struct Entry {
        std::unique_ptr<TriangleMesh> mesh;
        std::unique_ptr<AnalyticShape> analytic;
        std::unique_ptr<CurveSet> curves;
        std::shared_ptr<const Accel> prototype;  // instances
        Transform renderFromInstance;
        // A moving instance: renderFromInstance at each Embree time step (evenly spaced over
        // the shutter), between which Embree interpolates the matrices linearly.
        std::vector<Matrix4> instanceSteps;
        unsigned needs = NeedAll;          // SurfaceNeeds of the shape's material
        std::unique_ptr<MeshAlpha> alpha;  // a mesh's cut-outs (the filters' user data)
    };
    std::vector<Entry> shapes;
    std::vector<int> shapeOfGeom;  // geomID -> shape index
    double buildSeconds = 0;
    bool committed = false;
    BvhQuality builtQuality = BvhQuality::Medium;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
    }

    // Records `entry` as the shape of Embree geometry `id`; returns its shape index.
    int Record(unsigned id, Entry entry);
    // Commits geom, attaches it to the scene (which keeps it; `what` names it in an Embree
    // error) and records `entry` as its shape.
    int Attach(Device &dev, RTCGeometry geom, const char *what, Entry entry);
};

Accel::Accel(const AccelOptions &options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    Device &dev = GetDevice();
    impl_->scene = rtcNewScene(dev.device);
    dev.ThrowIfError("rtcNewScene");
    rtcSetSceneFlags(impl_->scene, options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
}

Accel::~Accel() = default;

int Accel::Impl::Record(unsigned id, Entry entry) {
    if (shapeOfGeom.size() <= id) shapeOfGeom.resize(id + 1, -1);
    const int shape = int(shapes.size());
    shapeOfGeom[id] = shape;
    shapes.push_back(std::move(entry));
    return shape;
}

int Accel::Impl::Attach(Device &dev, RTCGeometry geom, const char *what, Entry entry) {
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    dev.ThrowIfError(what);
    return Record(id, std::move(entry));
}

int Accel::AddMesh(std::unique_ptr<TriangleMesh> mesh, unsigned mask, ShapeAlpha alpha) {
    PRISM_CHECK(!impl_->committed);
    Device &dev = GetDevice();
    RTCGeometry geom = rtcNewGeometry(dev.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // A moving mesh has one vertex buffer per time step (TriangleMesh::SetMotionSteps).
    const int steps = mesh->NumTimeSteps();
    if (steps > 1) rtcSetGeometryTimeStepCount(geom, unsigned(steps));
    for (int k = 0; k < steps; ++k)
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT3,
                                   mesh->PositionData(k), 0, 3 * sizeof(float),
                                   mesh->NumVertices());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh->IndexData(),
                               0, 3 * sizeof(uint32_t), mesh->NumTriangles());
    rtcSetGeometryMask(geom, mask);
    std::unique_ptr<MeshAlpha> cutouts;
    if (alpha.Any()) {
        cutouts = std::make_unique<MeshAlpha>(MeshAlpha{mesh.get(), std::move(alpha)});
        rtcSetGeometryUserData(geom, cutouts.get());
        if (cutouts->alpha.camera)
            rtcSetGeometryIntersectFilterFunction(geom, MeshAlphaFilter<false>);
        if (cutouts->alpha.shadow)
            rtcSetGeometryOccludedFilterFunction(geom, MeshAlphaFilter<true>);
    }
    Impl::Entry entry{std::move(mesh), nullptr, nullptr, nullptr, {}, {}};
    entry.alpha = std::move(cutouts);
    return impl_->Attach(dev, geom, "adding a triangle mesh", std::move(entry));
}

int Accel::AddCurves(std::unique_ptr<CurveSet> curves, unsigned mask) {
    PRISM_CHECK(!impl_->committed);
    Device &dev = GetDevice();
    const RTCGeometryType type =
        curves->Type() == CurveType::Flat       ? RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE
        : curves->Type() == CurveType::Cylinder ? RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE
                                                : RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE;
    RTCGeometry geom = rtcNewGeometry(dev.device, type);
    const int steps = curves->NumTimeSteps();
    if (steps > 1) rtcSetGeometryTimeStepCount(geom, unsigned(steps));
    for (int k = 0; k < steps; ++k) {
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT4,
                                   curves->VertexData(k), 0, 4 * sizeof(float),
                                   curves->NumVertices());
        if (curves->Type() == CurveType::Ribbon)
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_NORMAL, unsigned(k), RTC_FORMAT_FLOAT3,
                                       curves->NormalData(k), 0, 3 * sizeof(float),
                                       curves->NumVertices());
    }
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, curves->IndexData(),
                               0, sizeof(uint32_t), curves->NumSegments());
    rtcSetGeometryTessellationRate(geom, float(curves->TessellationRate()));
    rtcSetGeometryMask(geom, mask);
    return impl_->Attach(dev, geom, "adding curves",
                         {nullptr, nullptr, std::move(curves), nullptr, {}, {}});
}

int Accel::AddInstance(std::shared_ptr<const Accel> prototype,
                       const Transform &renderFromInstance) {
    return AddInstance(std::move(prototype), AnimatedTransform(renderFromInstance));
}

int Accel::AddInstance(std::shared_ptr<const Accel> prototype,
                       const AnimatedTransform &renderFromInstance) {
    PRISM_CHECK(!impl_->committed);
    PRISM_CHECK(prototype && prototype->impl_->committed);
    Device &dev = GetDevice();
    RTCGeometry geom = rtcNewGeometry(dev.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, prototype->impl_->scene);
    std::vector<Matrix4> steps;
    if (renderFromInstance.MovesDuring(0, 1)) {
        int n = MotionTimeSteps(renderFromInstance);
        for (int k = 0; k < n; ++k)
            steps.push_back(renderFromInstance.InterpolateMatrix(double(k) / (n - 1)));
        rtcSetGeometryTimeStepCount(geom, unsigned(n));
    } else {
        steps.push_back(renderFromInstance.Interpolate(0).Matrix());
    }
    for (size_t k = 0; k < steps.size(); ++k) {
        float xfm[12];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) xfm[r * 4 + c] = float(steps[k].m[r][c]);
        rtcSetGeometryTransform(geom, unsigned(k), RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
    }
    const Transform first = renderFromInstance.Interpolate(0);
    return impl_->Attach(dev, geom, "adding an instance",
                         {nullptr, nullptr, nullptr, std::move(prototype), first,
                          steps.size() > 1 ? std::move(steps) : std::vector<Matrix4>{}});
}

int Accel::AddAnalytic(std::unique_ptr<AnalyticShape> shape, unsigned mask, ShapeAlpha alpha) {
    PRISM_CHECK(!impl_->committed);
    if (alpha.Any()) shape->SetAlpha(std::move(alpha));
    Device &dev = GetDevice();
    unsigned id =
        AttachUserGeometry(dev.device, impl_->scene, shape.get(), impl_->options.precision, mask);
    dev.ThrowIfError("adding an analytic shape");
    return impl_->Record(id, {nullptr, std::move(shape), nullptr, nullptr, {}, {}});
}

void Accel::Commit() {
    auto start = std::chrono::steady_clock::now();
    // Large meshes build with RTC_SCENE_FLAG_COMPACT: on the 1,000,002-triangle knot it halves
    // the peak memory of the build (131 -> 70 MB resident; Embree's default builder keeps large
    // temporaries) at no measurable render cost (0.60-0.69 s against 0.60-0.63 s for a
    // 1600x1200 frame, interleaved). Small scenes keep the default layout.
    const size_t triangles = NumTriangles();
    // Build quality by the work the BVH will serve. Measured on the 400k-triangle knot at
    // 1600x1200, 1 spp (interleaved, bench ceiling's scene): HIGH doubles the build
    // (0.12 -> 0.25 s) and saves 2-4% of the render (0.46 -> 0.45 s), LOW saves nothing and
    // renders 4% slower. HIGH wins once the render traces some 40 camera samples per triangle.
    BvhQuality q = impl_->options.quality;
    if (q == BvhQuality::Auto)
        q = triangles > 0 &&
                    impl_->options.expectedSamples >= HighQualitySamplesPerTriangle * triangles
                ? BvhQuality::High
                : BvhQuality::Medium;
    impl_->builtQuality = q;
    rtcSetSceneBuildQuality(impl_->scene, q == BvhQuality::Low    ? RTC_BUILD_QUALITY_LOW
                                          : q == BvhQuality::High ? RTC_BUILD_QUALITY_HIGH
                                                                  : RTC_BUILD_QUALITY_MEDIUM);
    if (triangles >= CompactBvhTriangles)
        rtcSetSceneFlags(impl_->scene,
                         RTCSceneFlags(rtcGetSceneFlags(impl_->scene) | RTC_SCENE_FLAG_COMPACT));
    rtcCommitScene(impl_->scene);
    GetDevice().ThrowIfError("building the BVH");
    impl_->buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    impl_->committed = true;
}

bool Accel::IntersectRaw(const Ray &r, RawHit *hit, unsigned mask) const {
    if (!TraceableRay(r)) return false;
    HitContext hc;
    rtcInitIntersectContext(&hc.ctx);
    unsigned objectGeom = RTC_INVALID_GEOMETRY_ID;
    hc.objectHits = &hit->object;
    hc.objectGeom = &objectGeom;
    hc.numRays = 1;
    alignas(16) RTCRayHit rh;
    InitRay(r, &rh.ray, mask);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &hc.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit->hasObject = rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID && objectGeom == rh.hit.geomID;
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        hit->shape = impl_->shapeOfGeom[rh.hit.instID[0]];
        const Accel &proto = *impl_->shapes[size_t(hit->shape)].prototype;
        hit->instanceShape = proto.impl_->shapeOfGeom[rh.hit.geomID];
    } else {
        hit->shape = impl_->shapeOfGeom[rh.hit.geomID];
        hit->instanceShape = -1;
    }
    hit->prim = int(rh.hit.primID);
    hit->t = rh.ray.tfar;
    hit->u = rh.hit.u;
    hit->v = rh.hit.v;
    return true;
}

void Accel::SetSurfaceNeeds(int shape, unsigned needs) {
    impl_->shapes[size_t(shape)].needs = needs;
}

SurfaceInteraction Accel::Interaction(const Ray &r, const RawHit &hit, unsigned extraNeeds) const {
    const Impl::Entry &e = impl_->shapes[hit.shape];
    const unsigned needs = e.needs | extraNeeds;
    if (e.prototype) {
        // Phase 2 in instance space, then back to render space. Normals use the inverse
        // transpose and flip when the instance transform swaps handedness, exactly as if the
        // prototype's shapes had been declared with the combined transform.
        std::optional<Transform> moved;  // a moving instance's transform at the ray's time
        if (!e.instanceSteps.empty()) moved = InstanceTransformAt(e.instanceSteps, r.time);
        const Transform &w = moved ? *moved : e.renderFromInstance;
        Transform instFromRender = w.Inverse();
        Ray ri{Vec3f(instFromRender.Point(Vec3d(r.o))), Vec3f(instFromRender.Vector(Vec3d(r.d))),
               r.tMax, r.tMin, r.time};
        RawHit sub = hit;
        sub.shape = hit.instanceShape;
        sub.instanceShape = -1;
        sub.hasObject = false;
        SurfaceInteraction s = e.prototype->Interaction(ri, sub);
        Vec3d pI(s.p);
        Vec3d pW = w.Point(pI);
        Vec3d errW = w.PointError(pI, Vec3d(s.pError), MachineEpsilon<float>());
        SurfaceInteraction si = s;
        RoundHitPoint(pW, errW, &si.p, &si.pError);
        bool flip = w.SwapsHandedness();
        Vec3f n = Vec3f(Normalize(w.Normal(Vec3d(s.n))));
        Vec3f ns = Vec3f(Normalize(w.Normal(Vec3d(s.ns))));
        si.n = flip ? -n : n;
        si.ns = flip ? -ns : ns;
        si.dpdu = Vec3f(w.Vector(Vec3d(s.dpdu)));
        si.dpdv = Vec3f(w.Vector(Vec3d(s.dpdv)));
        si.wo = Normalize(-r.d);
        si.t = hit.t;
        si.shape = hit.shape;
        si.instanceShape = hit.instanceShape;
        si.prim = hit.prim;
        si.time = r.time;
        return si;
    }
    if (e.curves)
        return e.curves->Interaction(size_t(hit.prim), hit.u, hit.v, hit.t, r.o, r.d, r.time,
                                     hit.shape);
    if (e.mesh) {
        // Built in the caller's result (no zero-filled or copied SurfaceInteraction: per hit).
        return e.mesh->Interaction(size_t(hit.prim), hit.u, hit.v, hit.t, r.d, needs, r.time,
                                   hit.shape);
    } else {
        // Phase 2: the callback's object-space hit (the root routine's full-precision result),
        // or, where it was not recorded (instances), the same root routine run again on the
        // winning shape: it finds the same root, as it did for the same ray in the callback.
        if (hit.hasObject)  // (the result's t is the float of the recorded t: hit.t)
            return e.analytic->Interaction(hit.object, r.d, needs, r.time, hit.shape, hit.prim);
        ObjectHit oh;
        if (!e.analytic->IntersectAt(r.o, r.d, r.tMin, r.tMax, impl_->options.precision, r.time,
                                     &oh)) {
            // Cannot happen for a deterministic routine; fall back to the float t.
            oh.t = hit.t;
            Vec3d pW = Vec3d(r.o) + Vec3d(r.d) * double(hit.t);
            const AnimatedTransform *motion = e.analytic->Motion();
            oh.p = (motion ? motion->Interpolate(r.time) : e.analytic->RenderFromObject())
                       .Inverse()
                       .Point(pW);
            oh.pError = Abs(oh.p) * 1e-6;
        }
        SurfaceInteraction si =
            e.analytic->Interaction(oh, r.d, needs, r.time, hit.shape, hit.prim);
        si.t = hit.t;
        return si;
    }
}

void Accel::NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp,
                              Vec3f *dn, int count) const {
    constexpr int MaxCount = 4;
    if (si.shape < 0 || size_t(si.shape) >= impl_->shapes.size() || count > MaxCount) {
        for (int i = 0; i < count; ++i) dn[i] = Vec3f();
        return;
    }
    const Impl::Entry &e = impl_->shapes[size_t(si.shape)];
    if (e.prototype) {
        // In instance space (W = renderFromInstance): the normal there is W^T n up to length,
        // tangents W^-1 dp; back in render space the unit normal is W^-T m_I / |W^-T m_I|, so
        // dn = (I - n n^T) W^-T dn_I / |W^-T m_I| (as AnalyticShape::NormalDerivatives).
        std::optional<Transform> moved;
        if (!e.instanceSteps.empty()) moved = InstanceTransformAt(e.instanceSteps, si.time);
        const Transform &w = moved ? *moved : e.renderFromInstance;
        const Transform instFromRender = w.Inverse();
        SurfaceInteraction sub = si;
        sub.p = Vec3f(instFromRender.Point(Vec3d(si.p)));
        sub.shape = si.instanceShape;
        sub.instanceShape = -1;
        const Vec3d nI = Normalize(instFromRender.Normal(Vec3d(n)));
        Vec3f dpI[MaxCount], dnI[MaxCount];
        for (int i = 0; i < count; ++i) dpI[i] = Vec3f(instFromRender.Vector(Vec3d(dp[i])));
        e.prototype->NormalDerivatives(sub, Vec3f(nI), dpI, dnI, count);
        const double len = Length(w.Normal(nI));
        const Vec3d nW(n);
        for (int i = 0; i < count; ++i) {
            const Vec3d d = w.Normal(Vec3d(dnI[i]));
            dn[i] = len > 0 ? Vec3f((d - nW * Dot(nW, d)) / len) : Vec3f();
        }
    } else if (e.mesh) {
        e.mesh->NormalDerivatives(size_t(si.prim), si, n, dp, dn, count);
    } else if (e.analytic) {
        e.analytic->NormalDerivatives(si, n, dp, dn, count);
    } else {
        // Curves: thinner than a footprint wherever differentials matter; taken as flat.
        for (int i = 0; i < count; ++i) dn[i] = Vec3f();
    }
}

void Accel::PrefetchHits(const RawHit *hits, int n) const {
    for (int i = 0; i < n; ++i) {
        if (hits[i].shape < 0) continue;
        const Impl::Entry &e = impl_->shapes[size_t(hits[i].shape)];
        if (e.mesh) e.mesh->Prefetch(size_t(hits[i].prim));
    }
}

bool Accel::Intersect(const Ray &r, SurfaceInteraction *si, unsigned mask) const {
    RawHit hit;
    if (!IntersectRaw(r, &hit, mask)) return false;
    *si = Interaction(r, hit);
    return true;
}

bool Accel::Occluded(const Ray &r) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (!TraceableRay(r)) return false;
    alignas(16) RTCRay ray;
    InitRay(r, &ray, ShadowRays);
    rtcOccluded1(impl_->scene, &ctx, &ray);
    return ray.tfar < 0;
}

void Accel::Packet(const Ray *rays, int n, RawHit *hits, bool *occluded, bool check) const {
    PRISM_CHECK(n >= 0 && n <= 16);
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    unsigned objectGeom[16];
    ObjectHit objectHits[16];
    // Masked lanes still hold a finite ray, empty (tnear > tfar): without 16-wide kernels
    // (no AVX-512) Embree traces rtcIntersect16 as a ray stream, which takes a lane's
    // activity from its ray rather than from the mask (an untraceable lane 0 copied into the
    // padding tripped an assertion of Debian's Embree on an AVX2 machine).
    static const Ray inert{{0, 0, 0}, {0, 0, 1}, /*tMax=*/0.f, /*tMin=*/1.f};
    for (int i = 0; i < 16; ++i) {
        PRISM_DCHECK(i >= n || check || TraceableRay(rays[i]));
        valid[i] = i < n && (!check || TraceableRay(rays[i])) ? -1 : 0;
        InitRay16(valid[i] ? rays[i] : inert, i, CameraRays, &rh.ray);
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        objectGeom[i] = RTC_INVALID_GEOMETRY_ID;
    }
    HitContext hc;
    rtcInitIntersectContext(&hc.ctx);
    hc.objectHits = objectHits;
    hc.objectGeom = objectGeom;
    hc.numRays = 16;
    rtcIntersect16(valid, impl_->scene, &hc.ctx, &rh);
    RTCIntersectContext &ctx = hc.ctx;
    for (int i = 0; i < n; ++i) {
        RawHit &h = hits[i];
        h = RawHit{};
        if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        unsigned inst = rh.hit.instID[0][i];
        if (inst == RTC_INVALID_GEOMETRY_ID && objectGeom[i] == rh.hit.geomID[i]) {
            h.hasObject = true;
            h.object = objectHits[i];
        }
        if (inst != RTC_INVALID_GEOMETRY_ID) {
            h.shape = impl_->shapeOfGeom[inst];
            h.instanceShape =
                impl_->shapes[size_t(h.shape)].prototype->impl_->shapeOfGeom[rh.hit.geomID[i]];
        } else {
            h.shape = impl_->shapeOfGeom[rh.hit.geomID[i]];
        }
        h.prim = int(rh.hit.primID[i]);
        h.t = rh.ray.tfar[i];
        h.u = rh.hit.u[i];
        h.v = rh.hit.v[i];
    }
    if (occluded) {
        alignas(64) RTCRay16 ray;
        for (int i = 0; i < 16; ++i) InitRay16(valid[i] ? rays[i] : inert, i, ShadowRays, &ray);
        rtcOccluded16(valid, impl_->scene, &ctx, &ray);
        for (int i = 0; i < n; ++i) occluded[i] = ray.tfar[i] < 0;
    }
}

int Accel::NumShapes() const { return int(impl_->shapes.size()); }
const TriangleMesh *Accel::Mesh(int s) const { return impl_->shapes[s].mesh.get(); }
const AnalyticShape *Accel::Analytic(int s) const { return impl_->shapes[s].analytic.get(); }
const CurveSet *Accel::Curves(int s) const { return impl_->shapes[s].curves.get(); }

size_t Accel::NumCurveSegments() const {
    size_t n = 0;
    for (const Impl::Entry &e : impl_->shapes)
        if (e.curves) n += e.curves->NumSegments();
    return n;
}
double Accel::BuildSeconds() const { return impl_->buildSeconds; }
bool Accel::BuiltWithHighQuality() const { return impl_->builtQuality == BvhQuality::High; }
BvhQuality Accel::BuildQuality() const { return impl_->builtQuality; }
bool Accel::Robust() const { return rtcGetSceneFlags(impl_->scene) & RTC_SCENE_FLAG_ROBUST; }

size_t Accel::NumTriangles() const {
    size_t n = 0;
    for (const Impl::Entry &e : impl_->shapes)
        if (e.mesh) n += e.mesh->NumTriangles();
    return n;
}

}  // namespace prism
