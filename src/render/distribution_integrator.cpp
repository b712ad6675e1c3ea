#include "render/distribution_integrator.h"

#include "render/kernel.h"

namespace prism {

RGB DistributionIntegrator::Li(const Ray &ray, int depth, RayCounters &counters,
                               const SampleContext &sc, bool emitted) const {
    return Kernel<KernelAll>(scene_, true).Li(ray, depth, counters, sc, emitted);
}

RGB DistributionIntegrator::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                                     const SampleContext &sc) const {
    return Kernel<KernelAll>(scene_, true).LiCamera(ray, hit, counters, sc);
}

}  // namespace prism
