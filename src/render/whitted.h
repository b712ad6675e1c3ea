// pbrt-v3's Whitted integrator (integrators/whitted.cpp): emitted light, one shadow-tested
// sample per light for the non-specular lobes, and recursion on the specular reflection and
// transmission lobes up to maxdepth. The shading code is the kernel of render/kernel.h,
// specialized per effect set and traced in packets; Prism's "distribution" integrator
// (render/distribution_integrator.h) is the same kernel with glossy rays.
#pragma once

#include <cstdint>

#include "render/kernel.h"

namespace prism {

class WhittedIntegrator : public Integrator {
  public:
    explicit WhittedIntegrator(const KernelParams &params = {}) : params_(params) {}
    const char *Name() const override { return "whitted"; }
    IntegratorTraits Traits() const override;
    uint32_t KernelMask(const RenderScene &scene, const TraceSettings &trace) const override;
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;
    void RenderTile(const TileContext &ctx, TileSamples &out, RayCounters &rc) const override;

  protected:
    KernelParams params_;
};

// The general kernel without glossy rays as a value, for tests and `prism trace`: the radiance
// along one ray (depth counts specular bounces; camera rays are depth 0), or along a camera
// ray whose closest hit is known (hit.shape < 0: a miss).
class WhittedTracer {
  public:
    explicit WhittedTracer(const RenderScene &scene) : scene_(scene) {}
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc = {}) const;
    RGB LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                 const SampleContext &sc = {}) const;

  private:
    const RenderScene &scene_;
};

}  // namespace prism
