// The rays a render traced, by kind: counted per thread and summed at the end (the counters
// that prove a scene simulates only the effects it calls for).
#pragma once

#include <cstdint>

namespace prism {

// Rays traced, by kind. Per thread, summed at the end.
struct RayCounters {
    uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0, passThrough = 0;
    // Rays sampled from glossy lobes (DistributionIntegrator; 0 with WhittedIntegrator).
    uint64_t glossy = 0;
    // Probe rays that find where subsurface light leaves (render/subsurface.h).
    uint64_t subsurface = 0;
    // Secondary rays not traced because of the ray-weight cutoff (not part of Total()).
    uint64_t cutoff = 0;
    // Secondary rays not traced because their camera sample's ray tree reached its budget
    // (render/ray_tree.h; not part of Total()).
    uint64_t treeBudget = 0;
    // Lens samples drawn for camera rays (depth of field; not rays, not part of Total()).
    uint64_t lensSamples = 0;
    uint64_t Total() const {
        return camera + shadow + reflection + refraction + passThrough + glossy + subsurface;
    }
    RayCounters &operator+=(const RayCounters &o) {
        camera += o.camera;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        passThrough += o.passThrough;
        glossy += o.glossy;
        subsurface += o.subsurface;
        cutoff += o.cutoff;
        treeBudget += o.treeBudget;
        lensSamples += o.lensSamples;
        return *this;
    }
};

}  // namespace prism
