// pbrt-v3's Whitted integrator (integrators/whitted.cpp): emitted light, one shadow-tested
// sample per light for the non-specular lobes, and recursion on the specular reflection and
// transmission lobes up to maxdepth.
#pragma once

#include <cstdint>

#include "core/color.h"
#include "geometry/ray.h"

namespace prism {

struct RenderScene;

// Rays traced, by kind. Per thread, summed at the end.
struct RayCounters {
    uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0, passThrough = 0;
    uint64_t Total() const { return camera + shadow + reflection + refraction + passThrough; }
    RayCounters &operator+=(const RayCounters &o) {
        camera += o.camera; shadow += o.shadow; reflection += o.reflection;
        refraction += o.refraction; passThrough += o.passThrough;
        return *this;
    }
};

// Identifies the camera sample being traced, so that light samples form stratified patterns
// across the pixel's samples and are a pure function of (pixel, sample).
struct SampleContext {
    int x = 0, y = 0;
    uint32_t sample = 0, spp = 1;
};

class WhittedIntegrator {
public:
    explicit WhittedIntegrator(const RenderScene &scene) : scene_(scene) {}
    // Radiance along a ray; depth counts specular bounces (camera rays are depth 0).
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc = {}) const;

private:
    const RenderScene &scene_;
};

}  // namespace prism
