// pbrt-v3's "volpath" integrator (integrators/volpath.cpp): the path tracer of
// render/path_integrator.h with participating media. Each segment of the path samples its
// medium (Medium::Sample: analytic for homogeneous media, delta tracking for grids); a
// scattering event in the medium is a path vertex whose direct lighting (one light, MIS
// between the light and the Henyey–Greenstein phase function) and continuation (phase-function
// sampling) replace the BSDF's; light samples and the MIS rays toward lights carry the
// transmittance of the media and invisible boundaries they cross (render/medium_tracking.h).
// Surface vertices are path's own (render/path_vertex.h), so without media volpath renders
// path's image bit for bit. Russian roulette as in "path". docs/INTEGRATORS.md.
#pragma once

#include "render/path_integrator.h"

namespace prism {

class VolPathIntegrator : public PathIntegrator {
  public:
    explicit VolPathIntegrator(const PathParams &params) : PathIntegrator(params) {}
    const char *Name() const override { return "volpath"; }
    IntegratorTraits Traits() const override;
    // A camera ray starts in the camera's medium.
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;
};

}  // namespace prism
