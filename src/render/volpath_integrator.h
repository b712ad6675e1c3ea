// pbrt-v3's "volpath" integrator (integrators/volpath.cpp): the path tracer of
// render/path_integrator.h with participating media. Each segment of the path samples its
// medium (Medium::Sample: analytic for homogeneous media, delta tracking for grids); a
// scattering event in the medium is a path vertex whose direct lighting (one light, MIS
// between the light and the Henyey–Greenstein phase function) and continuation (phase-function
// sampling) replace the BSDF's; light samples and the MIS rays toward lights carry the
// transmittance of the media and invisible boundaries they cross (render/medium_tracking.h).
// Russian roulette as in "path". docs/MEDIA.md.
#pragma once

#include "image/bounds2.h"
#include "render/light_sampling.h"
#include "render/whitted.h"

namespace prism {

class FilmTile;
struct RenderScene;
struct TileScratch;

class VolPathIntegrator {
  public:
    explicit VolPathIntegrator(const RenderScene &scene) : scene_(scene), chooser_(scene) {}
    // Radiance along a camera ray (starting in the camera's medium) for the camera sample ps.
    RGB Li(const Ray &ray, const PixelSamples &ps, RayCounters &counters) const;

  private:
    const RenderScene &scene_;
    LightChooser chooser_;
};

// Renders the pixels tb of one tile with the volumetric path tracer (Integrator "volpath").
void RenderTileVolPath(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &buf,
                       FilmTile *tile);

}  // namespace prism
