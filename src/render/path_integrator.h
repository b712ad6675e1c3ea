// pbrt-v3's "path" integrator (integrators/path.cpp): a unidirectional path tracer. At each
// path vertex it intersects, adds emission where no light sample covered it (the camera ray and
// rays after delta bounces), estimates direct lighting from one light with multiple importance
// sampling (render/light_sampling.h), samples the BSDF to continue the path, and applies Russian
// roulette after the third bounce where the throughput is below "rrthreshold". The surface
// vertex is render/path_vertex.h's, shared with volpath; alpha cut-outs are decided by the BVH
// (geometry/alpha.h). docs/INTEGRATORS.md.
#pragma once

#include "render/integrator.h"
#include "render/light_sampling.h"

namespace prism {

struct PathParams {
    float rrThreshold = 1;  // "rrthreshold": Russian roulette below this throughput
    LightChoice lightChoice = LightChoice::BVH;  // "lightsamplestrategy", "lightsampler"
    bool regularize = false;                     // pbrt-v4's "regularize" (BSDF::Regularize)
    // Follows light through subsurface materials: volpath, and path in a pbrt-v3 file
    // (pbrt-v4's path renders their interface alone).
    bool subsurface = true;
};
// Reads path's and volpath's shared parameters (context: the integrator's name, for messages).
PathParams ReadPathParams(const IntegratorInputs &in);

class PathIntegrator : public Integrator {
  public:
    explicit PathIntegrator(const PathParams &params) : params_(params) {}
    const char *Name() const override { return "path"; }
    IntegratorTraits Traits() const override;
    void Prepare(const RenderScene &scene) override;
    // How the shadow rays' lights are chosen (LightChooser::Summary).
    std::string Summary() const override { return chooser_.Summary(); }
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps, RayCounters &rc,
           RGB *direct) const override;

  protected:
    PathParams params_;
    LightChooser chooser_;
};

}  // namespace prism
