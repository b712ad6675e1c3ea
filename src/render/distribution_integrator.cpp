#include "render/distribution_integrator.h"

#include <algorithm>

#include "render/bsdf.h"
#include "render/render_scene.h"
#include "render/sampler.h"

namespace prism {

RGB DistributionIntegrator::Li(const Ray &ray, int depth, RayCounters &counters,
                               const SampleContext &sc, bool emitted) const {
    SurfaceInteraction si;
    if (!scene_.accel->Intersect(ray, &si)) return Escaped(ray);
    return Shade(*this, ray, si, depth, counters, sc, emitted);
}

RGB DistributionIntegrator::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                                     const SampleContext &sc) const {
    if (hit.shape < 0) return Escaped(ray);
    return Shade(*this, ray, scene_.accel->Interaction(ray, hit), 0, counters, sc);
}

GlossyRays DistributionIntegrator::PrepareGlossy(BSDF &bsdf, int depth) const {
    if (!bsdf.MakeRoughSpecularGlossy() || depth + 1 >= scene_.maxDepth) return GlossyRays::None;
    for (int i = 0; i < bsdf.NumParts(); ++i) {
        const BxDFLobes &l = bsdf.Part(i);
        if (!bsdf.Weight(i).IsBlack() && l.HasGlossy() &&
            std::min(l.alphaX, l.alphaY) < GlossyLightSampleAlpha)
            return GlossyRays::AllLights;
    }
    return GlossyRays::Environment;
}

void DistributionIntegrator::AddGlossy(const SurfaceInteraction &si, const BSDF &bsdf,
                                       GlossyRays mode, int depth, RayCounters &counters,
                                       const SampleContext &sc, RGB &L) const {
    const bool emitted = mode == GlossyRays::AllLights;
    const uint32_t n = sc.afterGlossy ? 1u : uint32_t(scene_.glossySamples);
    // The rays below sample the pixel's samples × n further: the hits they reach stratify
    // their own samples over that larger set (while the count stays small).
    const bool refine = uint64_t(sc.spp) * n <= (1u << 24);
    for (int part = 0; part < bsdf.NumParts(); ++part) {
        if (bsdf.Weight(part).IsBlack() || !bsdf.Part(part).HasGlossy()) continue;
        // A stratified pattern over the pixel's samples × n, per pixel, depth and part.
        const uint32_t seed =
            PatternSeed(sc.x, sc.y, uint32_t(0x6c6f7373u + uint32_t(depth) * 977u + uint32_t(part)),
                        sc.afterGlossy ? 0x9e3779b9u : 0u);
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t index = sc.sample * n + k;
            Vec2f u = CMJSample(index, sc.spp * n, seed);
            float uc = HashFloat(index, seed ^ 0x5bd1e995u);
            Vec3f wi;
            RGB weight;
            if (!bsdf.SampleGlossy(part, si.wo, u, uc, &wi, &weight)) continue;
            if (n > 1) weight = weight / float(n);
            SampleContext next = sc;
            next.beta = sc.beta * weight;
            next.afterGlossy = true;
            if (refine) {
                next.sample = index;
                next.spp = sc.spp * n;
            }
            if (!AboveCutoff(next.beta)) {
                counters.cutoff++;
                continue;
            }
            counters.glossy++;
            L += weight * Li(si.SpawnRay(wi, scene_.offset), depth + 1, counters, next, emitted);
        }
    }
}

}  // namespace prism
