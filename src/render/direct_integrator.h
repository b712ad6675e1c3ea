// pbrt-v3's "directlighting" integrator (integrators/directlighting.cpp): emission, direct
// lighting with multiple importance sampling of light and BSDF samples (render/light_sampling.h)
// from every light ("strategy" "all", each light with its "nsamples") or from one light chosen
// per sample ("one"), and recursion on the delta reflection and transmission lobes up to
// maxdepth. docs/INTEGRATORS.md.
#pragma once

#include "render/integrator.h"
#include "render/light_sampling.h"

namespace prism {

class DirectLightingIntegrator : public Integrator {
  public:
    // allLights: strategy "all" (every light, its own sample count), else "one".
    explicit DirectLightingIntegrator(bool allLights) : allLights_(allLights) {}
    const char *Name() const override { return "directlighting"; }
    IntegratorTraits Traits() const override;
    void Prepare(const RenderScene &scene) override;
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;

  private:
    // Radiance along a ray; depth counts delta bounces (camera rays are depth 0), treeRays
    // is what the ray tree below the ray may still trace (render/ray_tree.h), diff the ray's
    // differentials or null (the camera ray's, then the specular rays', as pbrt-v3's
    // SpecularReflect/SpecularTransmit pass them on).
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, int depth,
           uint64_t treeRays, const RayDifferential *diff, RayCounters &counters,
           RGB *direct) const;

    bool allLights_;
    LightChooser chooser_;
};

}  // namespace prism
