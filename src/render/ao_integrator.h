// pbrt-v3's "ambientocclusion" integrator (integrators/ao.cpp; "ao" for short). At the first
// surface a camera ray shades (through "none" materials) it casts nsamples rays over the
// hemisphere of the geometric normal turned toward the viewer, cosine-weighted or uniform, and
// returns the estimate of the integral of visibility times cos(theta) over that hemisphere, as
// pbrt-v3 does: pi where nothing occludes, 0 for a ray that misses; in a file read by pbrt-v4's
// rules that over pi (1 where nothing occludes), as pbrt-v4 does. Occluders farther than
// maxDistance do not count (pbrt-v4's "maxdistance"). Materials and lights play no part.
#pragma once

#include "render/integrator.h"

namespace prism {

class AOIntegrator : public Integrator {
  public:
    AOIntegrator(bool cosSample, int nSamples, float maxDistance = Infinity, float scale = 1)
        : cosSample_(cosSample), nSamples_(nSamples), maxDistance_(maxDistance), scale_(scale) {}
    const char *Name() const override { return "ambientocclusion"; }
    IntegratorTraits Traits() const override;
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;

  private:
    bool cosSample_;
    int nSamples_;
    float maxDistance_, scale_;
};

}  // namespace prism
