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

#include <memory>

#include "render/whitted.h"

namespace prism {

// The lobe width (Trowbridge–Reitz alpha) from which area lights reach glossy lobes through
// light samples rather than glossy rays.
inline constexpr float GlossyLightSampleAlpha = 0.2f;

// Glossy rays per glossy lobe at the first glossy bounce of a path (1 deeper down), unless the
// Integrator's "glossysamples" or --glossy-samples says otherwise; and the most it may say.
inline constexpr int DefaultGlossySamples = 8;
inline constexpr int MaxGlossySamples = 1024;

// How a hit's glossy lobes are sampled.
enum class GlossyRays {
    None,         // no glossy rays: light samples through every non-delta lobe (Whitted)
    Environment,  // glossy rays bring back infinite lights; area lights by light samples
    AllLights,    // glossy rays bring back infinite and area lights
};

class DistributionIntegrator : public WhittedIntegrator {
  public:
    explicit DistributionIntegrator(int glossySamples)
        : WhittedIntegrator(KernelParams{true, glossySamples, 0}) {}
    const char *Name() const override { return "distribution"; }
};

// The distribution kernel as a value, for tests: the general kernel with glossy rays. emitted
// false: the emission of the first surface hit is left out (glossy rays).
class DistributionTracer {
  public:
    explicit DistributionTracer(const RenderScene &scene, int glossySamples = 8)
        : scene_(scene), glossySamples_(glossySamples) {}
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc = {},
           bool emitted = true) const;
    RGB LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                 const SampleContext &sc = {}) const;

  private:
    KernelParams Args() const;  // glossy rays, the scene's trace settings

    const RenderScene &scene_;
    int glossySamples_;
};

}  // namespace prism
