// The ray-tracing acceleration structure: an Embree scene holding triangle meshes (native
// triangles, shared buffers) and analytic shapes (user geometry with our intersectors).
// Only src/geometry includes Embree; this header keeps it out (pimpl).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/curves.h"
#include "geometry/interaction.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"

namespace prism {

// Scenes with at least this many triangles are built with Embree's compact layout (accel.cpp).
inline constexpr size_t CompactBvhTriangles = 500000;
inline constexpr uint64_t HighQualitySamplesPerTriangle = 40;

// Embree's build quality; Auto picks MEDIUM, or HIGH when the render traces enough samples per
// triangle (HighQualitySamplesPerTriangle) for the slower build to pay for itself.
enum class BvhQuality { Auto, Low, Medium, High };

struct AccelOptions {
    Precision precision = Precision::Double;
    bool robust = false;  // RTC_SCENE_FLAG_ROBUST (watertight triangles, robust traversal)
    // RTC_BUILD_QUALITY_LOW, MEDIUM or HIGH (spatial splits); Auto chooses by expectedSamples.
    BvhQuality quality = BvhQuality::Auto;
    // Camera samples the render will trace (pixels x spp; 0: unknown). With Auto and at least
    // HighQualitySamplesPerTriangle per triangle the BVH is built with HIGH quality, else
    // MEDIUM: the slower build then pays for itself (accel.cpp).
    uint64_t expectedSamples = 0;
};

// Which queries see a shape (Embree geometry masks): camera and specular rays use
// CameraRays, shadow rays ShadowRays. pbrt's constant "alpha" 0 hides a shape from both,
// "shadowalpha" 0 from shadow rays only.
inline constexpr unsigned CameraRays = 1u, ShadowRays = 2u, AllRays = CameraRays | ShadowRays;

struct RawHit {
    int shape = -1;  // shape index (order of Add* calls); for instances, the instance's index
    int instanceShape = -1;  // for instance hits: the shape index within the prototype
    int prim = 0;
    float t = 0, u = 0, v = 0;
    // Analytic shapes outside instances: the root routine's object-space hit, recorded by the
    // Embree callback (Interaction then does not solve again).
    bool hasObject = false;
    ObjectHit object;
};

// The largest origin or direction component Embree accepts in a ray (its FLT_LARGE, 1.844e18:
// Embree asserts on larger ones); Prism's rays stay well below.
inline constexpr float MaxRayComponent = 1e18f;
// Whether Embree can trace `r`: finite, its origin's and direction's magnitudes summing to at
// most MaxRayComponent (a NaN or an infinity carries through the sum), a non-negative tMin and
// a tMax not below it; no branches, since every ray Embree traces is checked. Accel's queries
// treat any other ray as a miss (and as unoccluded); the assembly refuses a camera that would
// make one (assembly/camera_film.cpp).
inline bool TraceableRay(const Ray &r) {
    const float sum = std::abs(r.o.x) + std::abs(r.o.y) + std::abs(r.o.z) + std::abs(r.d.x) +
                      std::abs(r.d.y) + std::abs(r.d.z);
    return (sum <= MaxRayComponent) & (r.tMin >= 0) & (r.tMax >= r.tMin) & (r.time == r.time);
}

class Accel {
  public:
    explicit Accel(const AccelOptions &options = {});
    ~Accel();
    Accel(const Accel &) = delete;
    Accel &operator=(const Accel &) = delete;

    // Each returns the shape index. Call before Commit(). Meshes and analytic shapes that move
    // (TriangleMesh::SetMotionSteps, AnalyticShape::SetMotion) become Embree motion-blur
    // geometry; rays then carry their time (Ray::time).
    // `alpha` (geometry/alpha.h): cut-outs tested on each candidate hit (Embree filter
    // functions for meshes, the user-geometry callbacks for analytic shapes).
    int AddMesh(std::unique_ptr<TriangleMesh> mesh, unsigned mask = AllRays, ShapeAlpha alpha = {});
    int AddAnalytic(std::unique_ptr<AnalyticShape> shape, unsigned mask = AllRays,
                    ShapeAlpha alpha = {});
    // pbrt-v3 curves as Embree's native Bézier curves (geometry/curves.h; no cut-outs). A
    // curve set that moves gets Embree time steps (CurveSet::SetMotionSteps).
    int AddCurves(std::unique_ptr<CurveSet> curves, unsigned mask = AllRays);
    // An Embree instance of a committed prototype (pbrt ObjectInstance). Embree 3 allows one
    // instance level: prototypes hold meshes and analytic shapes only, and analytic shapes
    // apply their own object transform inside the instance.
    int AddInstance(std::shared_ptr<const Accel> prototype, const Transform &renderFromInstance);
    // A moving instance (motion blur): times are fractions of the shutter (Ray::time); Embree
    // interpolates the transform between evenly spaced time steps (MotionTimeSteps).
    int AddInstance(std::shared_ptr<const Accel> prototype,
                    const AnimatedTransform &renderFromInstance);
    // The surface data Interaction computes for hits on `shape` (SurfaceNeeds; default all).
    void SetSurfaceNeeds(int shape, unsigned needs);
    // Builds the BVH. Throws std::runtime_error with Embree's message on failure.
    void Commit();

    // Closest hit in (0, ray.tMax), with full shading geometry (phase 2). `mask` is the
    // queries whose shapes it sees: CameraRays, or ShadowRays for light tracing's rays (bdpt's
    // light subpaths, sppm's photons), so that a shape that casts no shadow ("shadowalpha" 0)
    // lets the light through on every path, not only on shadow rays.
    bool Intersect(const Ray &ray, SurfaceInteraction *si, unsigned mask = CameraRays) const;
    // Closest hit, ids and t only.
    bool IntersectRaw(const Ray &ray, RawHit *hit, unsigned mask = CameraRays) const;
    // Any hit in (0, ray.tMax).
    bool Occluded(const Ray &ray) const;
    // Up to 16 rays at once through Embree's packet path (rtcIntersect16/rtcOccluded16 with
    // a valid mask), which exercises the N-wide user-geometry callbacks. hits[i].shape is -1
    // for a miss; occluded[i] (if given) receives the occlusion answer.
    void IntersectPacket(const Ray *rays, int n, RawHit *hits, bool *occluded = nullptr) const {
        Packet(rays, n, hits, occluded, true);
    }
    // The same for camera rays, which are not checked one by one (TraceableRay): the assembly
    // proved every ray the camera makes traceable (assembly/camera_film.cpp: its rays are
    // affine in the film and lens positions, and the extreme ones are checked). Checked in
    // debug builds.
    void IntersectCameraPacket(const Ray *rays, int n, RawHit *hits) const {
        Packet(rays, n, hits, nullptr, false);
    }
    // Full interaction for a raw hit (same ray). extraNeeds: surface data computed for a hit on
    // a top-level shape beyond its SurfaceNeeds (the AOVs' uv and tangents), without changing
    // what the render's own hits compute.
    SurfaceInteraction Interaction(const Ray &ray, const RawHit &hit,
                                   unsigned extraNeeds = 0) const;
    // Curvature at a hit this scene's Intersect or Interaction returned: the derivatives dn[i]
    // of its unit shading normal (before bump or normal maps) along the render-space tangent
    // vectors dp[i], oriented as the unit vector n (AnalyticShape::NormalDerivatives,
    // TriangleMesh::NormalDerivatives; instances through their transform). Computed from the
    // shape on request, for specular ray differentials (render/differentials.h).
    void NormalDerivatives(const SurfaceInteraction &si, const Vec3f &n, const Vec3f *dp, Vec3f *dn,
                           int count) const;
    // Prefetches the mesh data Interaction will read for these hits (a packet's hits, before
    // they are shaded one by one, so their cache misses overlap).
    void PrefetchHits(const RawHit *hits, int n) const;

    int NumShapes() const;
    size_t NumTriangles() const;  // of this scene's meshes (instances' prototypes not included)
    const TriangleMesh *Mesh(int shape) const;       // nullptr if analytic
    const AnalyticShape *Analytic(int shape) const;  // nullptr if mesh
    const CurveSet *Curves(int shape) const;         // nullptr unless curves
    size_t NumCurveSegments() const;                 // of this scene's curves (as NumTriangles)
    double BuildSeconds() const;
    bool BuiltWithHighQuality() const;  // after Commit(): whether the HIGH builder ran
    BvhQuality BuildQuality() const;    // after Commit(): Low, Medium or High (never Auto)
    bool Robust() const;                // whether Embree's scene has RTC_SCENE_FLAG_ROBUST

  private:
    void Packet(const Ray *rays, int n, RawHit *hits, bool *occluded, bool check) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace prism
