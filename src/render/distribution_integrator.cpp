#include "render/distribution_integrator.h"

#include <string>

#include "core/params.h"
#include "render/render_scene.h"

namespace prism {

// Integrator "distribution" (a Prism extension; integrator_list.inc). Parameters:
//   maxdepth       integer  5  the longest specular or glossy path (--maxdepth wins)
//   glossysamples  integer  8  glossy rays per glossy lobe at the first glossy bounce (1
//                              deeper down), 1 to MaxGlossySamples; --glossy-samples wins
std::unique_ptr<Integrator> CreateDistributionIntegrator(const IntegratorInputs &in) {
    const int n = in.glossySamples > 0 ? in.glossySamples
                                       : in.params.Int("glossysamples", DefaultGlossySamples);
    if (n < 1 || n > MaxGlossySamples)
        throw SceneError(in.loc, "glossysamples " + std::to_string(n) + " out of range (1 to " +
                                     std::to_string(MaxGlossySamples) + ")");
    in.params.WarnUnread("Prism's distribution integrator reads only maxdepth and glossysamples");
    return std::make_unique<DistributionIntegrator>(n);
}

KernelParams DistributionTracer::Args() const {
    KernelParams p{true, glossySamples_, 0};
    p.trace = scene_.trace;
    return p;
}

RGB DistributionTracer::Li(const Ray &ray, int depth, RayCounters &counters,
                           const SampleContext &sc, bool emitted) const {
    return Kernel<KernelGeneral>(scene_, Args()).Li(ray, depth, counters, sc, emitted);
}

RGB DistributionTracer::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                                 const SampleContext &sc) const {
    return Kernel<KernelGeneral>(scene_, Args()).LiCamera(ray, hit, counters, sc);
}

}  // namespace prism
