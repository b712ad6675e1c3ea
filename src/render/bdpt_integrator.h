// pbrt-v3's "bdpt" integrator (Veach's bidirectional path tracing): per camera sample a camera
// subpath and a light subpath, every connection strategy (s, t) of their prefixes — s = 0 the
// camera path hitting a light, s = 1 a light sample (next-event estimation), t = 1 light
// tracing onto the film (TileSamples splats) — weighted by multiple importance sampling
// (the balance heuristic, as pbrt-v3). Subpaths and connections: render/bdpt_vertex.h.
// In participating media the subpaths scatter at medium vertices and connections carry the
// transmittance between their ends (pbrt-v3's bdpt with media). docs/INTEGRATORS.md.
#pragma once

#include "render/bdpt_camera.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/light_sampling.h"

namespace prism {

class BdptIntegrator : public Integrator {
  public:
    BdptIntegrator(LightChoice choice, bool regularize, const FileLoc &loc)
        : choice_(choice), regularize_(regularize), loc_(loc) {}
    const char *Name() const override { return "bdpt"; }
    IntegratorTraits Traits() const override;
    void Prepare(const RenderScene &scene) override;
    // One camera sample without light tracing (t = 1), which lands on other pixels: only
    // TileSample gives those (as splats).
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;
    RGB TileSample(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                   RayCounters &rc, RGB *direct, std::vector<SampleSplat> *splats) const override;

  private:
    // The radiance of one camera sample; light tracing's contributions go to *splats (none
    // when it is null).
    RGB Sample(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
               std::vector<SampleSplat> *splats) const;

    LightChoice choice_;
    bool regularize_;
    FileLoc loc_;
    LightChooser chooser_;
    CameraImportance camera_;
    SceneSphere sphere_;
    int infinityMedium_ = -1;  // MediumAtInfinity
};

}  // namespace prism
