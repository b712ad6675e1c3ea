#include "render/medium_tracking.h"

#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

bool IntersectTr(const RenderScene &scene, Ray ray, int medium, bool infinite,
                 MediumSampler &sampler, RayCounters &counters, SurfaceInteraction *hit, RGB *tr,
                 int *mediumAtHit) {
    const Vec3f target = ray.o + ray.d;  // finite rays run to o + d (SpawnRayTo)
    Vec3f from = ray.o;
    for (int pass = 0;; ++pass) {
        const bool found = scene.accel->Intersect(ray, hit);
        if (medium >= 0) {
            *tr *= scene.media[size_t(medium)]->Tr(
                MediumSegment(ray, from, found ? &hit->p : nullptr), sampler);
            if (tr->IsBlack()) return false;
        }
        if (!found) return false;
        const ShapeInfo &shape = scene.Info(*hit);
        if (!scene.materials[size_t(shape.material)].IsPassThrough()) {
            if (mediumAtHit) *mediumAtHit = medium;
            return true;
        }
        if (pass >= MaxMediumCrossings) {
            *tr = RGB(0);
            return false;
        }
        medium = MediumAfter(shape, *hit, ray.d, medium);
        from = hit->p;
        counters.passThrough++;
        ray = infinite ? hit->SpawnRay(ray.d, scene.offset) : hit->SpawnRayTo(target, scene.offset);
    }
}

RGB ShadowTransmittance(const RenderScene &scene, const Ray &ray, int medium, bool infinite,
                        MediumSampler &sampler, RayCounters &counters) {
    if (!scene.accel->Occluded(ray))
        return medium >= 0 ? scene.media[size_t(medium)]->Tr(ray, sampler) : RGB(1);
    SurfaceInteraction hit;
    RGB tr(1);
    if (IntersectTr(scene, ray, medium, infinite, sampler, counters, &hit, &tr)) return RGB(0);
    return tr;
}

int MediumAtInfinity(const RenderScene &scene) {
    int medium = scene.cameraMedium;
    if (scene.media.empty() || !scene.accel) return medium;  // nothing to cross
    // Any direction does, in a scene whose interfaces agree; this one meets no axis-aligned
    // wall edge-on.
    Ray ray{Vec3f(0, 0, 0), Normalize(Vec3f(0.301f, 0.512f, 0.805f))};
    SurfaceInteraction hit;
    for (int crossings = 0; crossings < 100000 && scene.accel->Intersect(ray, &hit); ++crossings) {
        medium = MediumAfter(scene.Info(hit), hit, ray.d, medium);
        ray = hit.SpawnRay(ray.d, scene.offset);
    }
    return medium;
}

}  // namespace prism
