// pbrt-v3's Whitted integrator (integrators/whitted.cpp): emitted light, one shadow-tested
// sample per light for the non-specular lobes, and recursion on the specular reflection and
// transmission lobes up to maxdepth. The shading code is the kernel of render/kernel.h, which
// is specialized per effect set; this header keeps the ray counters and the sample context.
#pragma once

#include <cstdint>

#include "core/color.h"
#include "geometry/accel.h"
#include "geometry/interaction.h"
#include "geometry/ray.h"

namespace prism {

struct RenderScene;

// Rays traced, by kind. Per thread, summed at the end.
struct RayCounters {
    uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0, passThrough = 0;
    // Rays sampled from glossy lobes (DistributionIntegrator; 0 with WhittedIntegrator).
    uint64_t glossy = 0;
    // Secondary rays not traced because of the ray-weight cutoff (not part of Total()).
    uint64_t cutoff = 0;
    // Lens samples drawn for camera rays (depth of field; not rays, not part of Total()).
    uint64_t lensSamples = 0;
    uint64_t Total() const {
        return camera + shadow + reflection + refraction + passThrough + glossy;
    }
    RayCounters &operator+=(const RayCounters &o) {
        camera += o.camera;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        passThrough += o.passThrough;
        glossy += o.glossy;
        cutoff += o.cutoff;
        lensSamples += o.lensSamples;
        return *this;
    }
};

// Identifies the camera sample being traced, so that light samples form stratified patterns
// across the pixel's samples and are a pure function of (pixel, sample); and carries the
// throughput of the path down to the ray being traced (for the ray-weight cutoff).
struct SampleContext {
    int x = 0, y = 0;
    uint32_t sample = 0, spp = 1;
    RGB beta = RGB(1);         // product of the specular weights from the camera to this ray
    bool afterGlossy = false;  // a glossy bounce lies between the camera and this ray
    // The ray's differentials (RenderScene::differentials), or null: unfiltered lookups.
    const RayDifferential *diff = nullptr;
    int medium = -1;  // the medium the ray starts in (RenderScene::media; -1: none)
};

// The Whitted integrator as a value (tests, `prism trace`): the general kernel (render/kernel.h)
// without glossy rays. The renderer runs the kernel specialized for the scene instead.
class WhittedIntegrator {
  public:
    static constexpr bool Glossy = false;  // traces no glossy rays (pbrt-v3's "whitted")
    explicit WhittedIntegrator(const RenderScene &scene) : scene_(scene) {}
    // Radiance along a ray; depth counts specular bounces (camera rays are depth 0).
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc = {}) const;
    // The same for a camera ray whose closest hit is already known (hit.shape < 0: a miss),
    // e.g. from a packet traced through Accel::IntersectPacket.
    RGB LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                 const SampleContext &sc = {}) const;

  protected:
    const RenderScene &scene_;
};

}  // namespace prism
