// Prism's "distribution" integrator (a Prism extension to the pbrt format): Whitted plus glossy
// reflection and transmission by Cook's distribution ray tracing. Every glossy lobe (metal,
// plastic, uber, substrate, translucent and rough glass) is sampled with stratified rays from
// its Trowbridge–Reitz microfacet distribution, weighted by f·cos/pdf.
//
// Each light reaches a glossy lobe through exactly one of light samples and glossy rays (there
// is no multiple importance sampling yet): point, spot and distant lights, which no ray can
// hit, through light samples; infinite lights through glossy rays; area lights through glossy
// rays when the lobe is narrow (alpha < GlossyLightSampleAlpha, where light samples would
// rarely fall inside it: the limit alpha -> 0 is the mirror image) and through light samples
// when it is wide (where a glossy ray would rarely hit a small light), glossy rays then not
// counting the emission they hit first. A hit where no glossy ray is traced (the depth limit)
// shades as Whitted does. The code is the kernel of render/kernel.h (Kernel<K> with KernelGlossy).
#pragma once

#include "render/whitted.h"

namespace prism {

// The lobe width (Trowbridge–Reitz alpha) from which area lights reach glossy lobes through
// light samples rather than glossy rays.
inline constexpr float GlossyLightSampleAlpha = 0.2f;

// How a hit's glossy lobes are sampled.
enum class GlossyRays {
    None,         // no glossy rays: light samples through every non-delta lobe (Whitted)
    Environment,  // glossy rays bring back infinite lights; area lights by light samples
    AllLights,    // glossy rays bring back infinite and area lights
};

// The distribution integrator as a value: the general kernel (render/kernel.h) with glossy rays.
class DistributionIntegrator : public WhittedIntegrator {
  public:
    static constexpr bool Glossy = true;
    explicit DistributionIntegrator(const RenderScene &scene) : WhittedIntegrator(scene) {}
    // emitted false: the emission of the first surface hit is left out (glossy rays).
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc = {},
           bool emitted = true) const;
    RGB LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                 const SampleContext &sc = {}) const;
};

}  // namespace prism
