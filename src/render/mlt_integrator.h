// pbrt-v3's "mlt" integrator: Metropolis light transport in primary sample space (Kelemen et
// al. 2002) over the bidirectional path tracer's paths (render/bdpt_vertex.h). Each state of
// a Markov chain is a vector of uniform numbers (render/mlt_sampler.h) that a path of one
// depth is made from: the strategy (s, t), the film position, the camera and light subpaths
// and the connection, evaluated with bdpt's MIS-weighted ConnectStrategy. A bootstrap of
// independent paths estimates the mean luminance b and picks each chain's start in
// proportion to its luminance; the chains then splat every proposal, weighted by its
// acceptance probability, and the image is the splats times b / mutationsperpixel. A whole-
// frame integrator (Integrator::RendersWholeFrame): chain i's random numbers are a pure
// function of i and its splats are summed in chain order, so the image is the same for any
// thread count. Participating media are rendered as bdpt renders them. docs/INTEGRATORS.md.
#pragma once

#include <cstdint>

#include "render/bdpt_camera.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/light_sampling.h"

namespace prism {

class FrameContext;
class MltSampler;

struct MltParams {
    int64_t bootstrapSamples = 100000;  // "bootstrapsamples"
    int chains = 1000;                  // "chains"
    int mutationsPerPixel = 100;        // "mutationsperpixel"
    float largeStepProbability = 0.3f;  // "largestepprobability"
    float sigma = 0.01f;                // "sigma": the small steps' standard deviation
    bool regularize = false;            // pbrt-v4's "regularize" (BdptContext)
};

class MltIntegrator : public Integrator {
  public:
    MltIntegrator(const MltParams &params, const FileLoc &loc) : params_(params), loc_(loc) {}
    const char *Name() const override { return "mlt"; }
    IntegratorTraits Traits() const override;
    void Prepare(const RenderScene &scene) override;
    // Not a per-sample integrator: Render() calls RenderFrame. Li gives nothing.
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;
    bool RendersWholeFrame() const override { return true; }
    Image RenderFrame(const FrameContext &frame) const override;

    // The radiance of the path of `depth` bounces that sampler's state makes (one strategy,
    // times the number of strategies), and the raster position it lands on.
    RGB PathRadiance(const FrameContext &frame, const MltSampler &sampler, int depth, Vec2f *raster,
                     RayCounters &rc) const;

  private:
    MltParams params_;
    FileLoc loc_;
    LightChooser chooser_;
    CameraImportance camera_;
    SceneSphere sphere_;
    int infinityMedium_ = -1;  // MediumAtInfinity
};

}  // namespace prism
