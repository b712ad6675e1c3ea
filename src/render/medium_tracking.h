// Rays through participating media and invisible boundaries, shared by the Whitted/distribution
// media kernel (render/kernel_media.h) and the volumetric path tracer: which medium a ray is in
// after each "none" surface it crosses (MediumAfter, render/render_scene.h), and the
// transmittance up to the first visible surface (pbrt-v3 Scene::IntersectTr and
// VisibilityTester::Tr).
#pragma once

#include "core/color.h"
#include "geometry/interaction.h"
#include "render/integrator.h"
#include "render/medium.h"

namespace prism {

struct RenderScene;
struct RayCounters;

// Consecutive invisible surfaces a ray may cross.
inline constexpr int MaxMediumCrossings = MaxPassThrough;

// The part of ray in a medium that begins at `from` (the previous boundary's hit point rather
// than the spawned ray's origin, which its offset moves ahead) and ends at `to` (hit) or runs
// to ray.tMax; the same direction, so its parameter measures distance as ray's does.
inline Ray MediumSegment(const Ray &ray, const Vec3f &from, const Vec3f *to) {
    Ray segment = ray;
    segment.o = from;
    const Vec3f end = to ? *to : ray.At(ray.tMax);
    segment.tMax =
        ray.tMax < Infinity || to ? Dot(end - from, ray.d) / Dot(ray.d, ray.d) : Infinity;
    return segment;
}

// pbrt-v3 Scene::IntersectTr: follows ray (starting in `medium`) through "none" surfaces,
// multiplying *tr by the transmittance of each medium segment, to the first visible surface
// (true, *hit set, *mediumAtHit the medium on the ray's side of it) or out of the scene (false;
// *tr then includes the last segment). `infinite` false: ray ends at ray.o + ray.d (as
// SurfaceInteraction::SpawnRayTo makes shadow rays), and continues toward that point after each
// crossing. Gives up (tr 0, false) after MaxMediumCrossings crossings.
bool IntersectTr(const RenderScene &scene, Ray ray, int medium, bool infinite,
                 MediumSampler &sampler, RayCounters &counters, SurfaceInteraction *hit, RGB *tr,
                 int *mediumAtHit = nullptr);

// pbrt-v3 VisibilityTester::Tr: the transmittance of a shadow ray that starts in `medium`, 0
// when a visible surface blocks it. Most shadow rays cross no surface: one occlusion test, then
// the medium's transmittance.
RGB ShadowTransmittance(const RenderScene &scene, const Ray &ray, int medium, bool infinite,
                        MediumSampler &sampler, RayCounters &counters);

// The medium a ray escaping the scene ends in: a straight line from the camera (the origin of
// render space) crossing every surface on its way, each MediumInterface changing the medium
// as a ray through it would; the camera's medium when nothing is in the way. Where the light
// of infinite and distant lights begins (pbrt-v3 starts it in vacuum whatever surrounds the
// scene, which lights a scene inside an unbounded medium through strategies that its camera
// paths, dying in that medium, never match).
int MediumAtInfinity(const RenderScene &scene);

}  // namespace prism
