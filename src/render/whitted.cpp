#include "render/whitted.h"

#include "render/kernel.h"

namespace prism {

// The general kernel without glossy rays.
using WhittedKernel = Kernel<KernelAll & ~uint32_t(KernelGlossy)>;

RGB WhittedIntegrator::Li(const Ray &ray, int depth, RayCounters &counters,
                          const SampleContext &sc) const {
    return WhittedKernel(scene_, false).Li(ray, depth, counters, sc);
}

RGB WhittedIntegrator::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                                const SampleContext &sc) const {
    return WhittedKernel(scene_, false).LiCamera(ray, hit, counters, sc);
}

}  // namespace prism
