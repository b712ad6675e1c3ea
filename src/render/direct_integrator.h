// pbrt-v3's "directlighting" integrator (integrators/directlighting.cpp): emission, direct
// lighting with multiple importance sampling of light and BSDF samples (render/light_sampling.h)
// from every light ("strategy" "all", each light with its "nsamples") or from one light chosen
// per sample ("one"), and recursion on the delta reflection and transmission lobes up to
// maxdepth. docs/PATH.md.
#pragma once

#include "geometry/interaction.h"
#include "image/bounds2.h"
#include "render/light_sampling.h"
#include "render/whitted.h"

namespace prism {

class FilmTile;
struct RenderScene;
struct TileScratch;

class DirectLightingIntegrator {
  public:
    explicit DirectLightingIntegrator(const RenderScene &scene) : scene_(scene), chooser_(scene) {}
    // Radiance along a ray; depth counts delta bounces (camera rays are depth 0).
    RGB Li(const Ray &ray, const PixelSamples &ps, int depth, RayCounters &counters) const;
    // A camera ray's radiance (depth 0).
    RGB Li(const Ray &ray, const PixelSamples &ps, RayCounters &counters) const {
        return Li(ray, ps, 0, counters);
    }

  private:
    const RenderScene &scene_;
    LightChooser chooser_;
};

// Renders the pixels tb of one tile with the directlighting integrator.
void RenderTileDirect(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &buf,
                      FilmTile *tile);

}  // namespace prism
