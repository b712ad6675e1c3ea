// pbrt-v3's "path" integrator (integrators/path.cpp): a unidirectional path tracer. At each
// path vertex it intersects, adds emission where no light sample covered it (the camera ray and
// rays after delta bounces), estimates direct lighting from one light with multiple importance
// sampling (render/light_sampling.h), samples the BSDF to continue the path, and applies Russian
// roulette after the third bounce where the throughput is below "rrthreshold". Shading goes
// through the materials' BSDFs (render/bsdf.h) as in the Whitted kernel; alpha cut-outs are
// decided by the BVH (geometry/alpha.h). docs/PATH.md.
#pragma once

#include "geometry/interaction.h"
#include "image/bounds2.h"
#include "render/light_sampling.h"
#include "render/whitted.h"

namespace prism {

class FilmTile;
struct RenderScene;
struct TileScratch;

class PathIntegrator {
  public:
    explicit PathIntegrator(const RenderScene &scene) : scene_(scene), chooser_(scene) {}
    // Radiance along a camera ray for the camera sample ps.
    RGB Li(const Ray &ray, const PixelSamples &ps, RayCounters &counters) const;

  private:
    const RenderScene &scene_;
    LightChooser chooser_;
};

// Renders the pixels tb of one tile with the path integrator (renderer.cpp's tile function for
// Integrator "path").
void RenderTilePath(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &buf,
                    FilmTile *tile);

}  // namespace prism
