#include "render/whitted.h"

#include "render/area_light.h"
#include "render/distribution_integrator.h"
#include "render/render_scene.h"
#include "render/sampler.h"

namespace prism {

namespace {
// Consecutive invisible-interface crossings allowed before a ray is dropped; guards against
// stacks of coincident "none" surfaces without changing any real scene.
constexpr int MaxPassThrough = 256;
}  // namespace

RGB WhittedIntegrator::Escaped(const Ray &ray) const {
    RGB L;
    for (const auto &light : scene_.lights) L += light->Le(ray);
    return L;
}

RGB WhittedIntegrator::Li(const Ray &ray, int depth, RayCounters &counters,
                          const SampleContext &sc) const {
    SurfaceInteraction si;
    if (!scene_.accel->Intersect(ray, &si)) return Escaped(ray);
    return Shade(*this, ray, si, depth, counters, sc);
}

RGB WhittedIntegrator::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                                const SampleContext &sc) const {
    if (hit.shape < 0) return Escaped(ray);
    return Shade(*this, ray, scene_.accel->Interaction(ray, hit), 0, counters, sc);
}

bool WhittedIntegrator::AboveCutoff(const RGB &beta) const {
    return !(scene_.rayCutoff > 0 && !(beta.MaxComponent() * scene_.filmScale > scene_.rayCutoff));
}

template <class Integrator>
RGB WhittedIntegrator::Shade(const Integrator &integrator, const Ray &rayIn, SurfaceInteraction si,
                             int depth, RayCounters &counters, const SampleContext &sc,
                             bool emitted) const {
    Ray ray = rayIn;
    const Material *mat = nullptr;
    const ShapeInfo *shape = nullptr;
    for (int pass = 0;; ++pass) {
        shape = &scene_.Info(si);
        mat = &scene_.materials[size_t(shape->material)];
        if (!mat->IsPassThrough()) break;
        if (pass >= MaxPassThrough) return RGB(0);
        // pbrt: a surface without a BSDF continues the ray without counting a bounce.
        ray = si.SpawnRay(ray.d, scene_.offset);
        counters.passThrough++;
        if (!scene_.accel->Intersect(ray, &si)) return Escaped(ray);
    }

    TextureContext tc{si.uv, si.p};
    BSDF bsdf = mat->GetBSDF(si, tc);
    // Distribution: rough glass becomes glossy, and glossy rays sample the glossy lobes; the
    // lights those rays bring back are not light-sampled through them (GlossyRays).
    GlossyRays glossy = GlossyRays::None;
    if constexpr (Integrator::Glossy) glossy = integrator.PrepareGlossy(bsdf, depth);
    const Vec3f &wo = si.wo;
    RGB L;
    // Emission of an area light seen directly or through specular paths.
    if (shape->areaLight >= 0 && (!Integrator::Glossy || emitted))
        L += static_cast<const DiffuseAreaLight &>(*scene_.lights[size_t(shape->areaLight)])
                 .L(si.n, wo);

    // Direct lighting through the non-specular lobes: one shadow ray per delta light, and a
    // stratified set of shadow rays per area or environment light (distribution ray tracing).
    if (bsdf.HasNonSpecular()) {
        const bool hasDiffuse = glossy != GlossyRays::None && bsdf.HasDiffuse();
        for (size_t j = 0; j < scene_.lights.size(); ++j) {
            const Light &light = *scene_.lights[j];
            int n = light.NumSamples();
            // Delta lights ignore u: the stratified pattern (a hash chain) only where it is used.
            const bool usesSample = light.UsesSample();
            // Whether this light reaches the glossy lobes through glossy rays only.
            const bool byGlossyRays =
                usesSample && (glossy == GlossyRays::AllLights ||
                               (glossy == GlossyRays::Environment && !light.IsArea()));
            if (byGlossyRays && !hasDiffuse) continue;
            uint32_t seed =
                usesSample ? PatternSeed(sc.x, sc.y, uint32_t(2 + j * 131 + size_t(depth) * 7919))
                           : 0;
            RGB Lj;
            for (int k = 0; k < n; ++k) {
                Vec2f u = usesSample ? CMJSample(sc.sample * uint32_t(n) + uint32_t(k),
                                                 sc.spp * uint32_t(n), seed)
                                     : Vec2f(0.5f, 0.5f);
                LightSample ls;
                if (!light.SampleLi(si, u, &ls) || ls.Li.IsBlack() || !(ls.pdf > 0)) continue;
                RGB f = byGlossyRays ? bsdf.fDiffuse(wo, ls.wi) : bsdf.f(wo, ls.wi);
                if (f.IsBlack()) continue;
                Ray shadow = ls.infinite ? si.SpawnRay(ls.wi, scene_.offset)
                                         : si.SpawnRayTo(ls.pLight, scene_.offset);
                counters.shadow++;
                if (scene_.accel->Occluded(shadow)) continue;
                Lj += f * ls.Li * (AbsDot(ls.wi, bsdf.ns) / ls.pdf);
            }
            L += n == 1 ? Lj : Lj / float(n);
        }
    }

    AddSpecular(integrator, si, bsdf, depth, counters, sc, L);
    if constexpr (Integrator::Glossy)
        if (glossy != GlossyRays::None)
            integrator.AddGlossy(si, bsdf, glossy, depth, counters, sc, L);
    return L;
}

template <class Integrator>
void WhittedIntegrator::AddSpecular(const Integrator &integrator, const SurfaceInteraction &si,
                                    const BSDF &bsdf, int depth, RayCounters &counters,
                                    const SampleContext &sc, RGB &L) const {
    const Vec3f &wo = si.wo;
    // Specular recursion, for the delta lobes of every BSDF part (mix materials have several).
    if (depth + 1 < scene_.maxDepth) {
        Vec3f wi;
        RGB weight;
        // Traces the ray along wi unless the ray-weight cutoff drops it: the radiance it could
        // bring back is unknown, so a ray "can change the pixel by more than the cutoff" when its
        // throughput (max RGB component, times the Film's scale) exceeds the cutoff, as if it
        // brought back radiance 1 (pbrt-style ray weights; the pixel filter's share of the
        // sample is ignored). Cutoff 0 traces every ray, exactly as without the cutoff.
        auto trace = [&](uint64_t &kind) {
            SampleContext next = sc;
            next.beta = sc.beta * weight;
            if (!AboveCutoff(next.beta)) {
                counters.cutoff++;
                return;
            }
            kind++;
            L += weight * integrator.Li(si.SpawnRay(wi, scene_.offset), depth + 1, counters, next);
        };
        for (int part = 0; part < bsdf.NumParts(); ++part) {
            if (bsdf.SampleSpecularReflection(part, wo, &wi, &weight)) trace(counters.reflection);
            if (bsdf.SampleSpecularTransmission(part, wo, &wi, &weight)) trace(counters.refraction);
        }
    }
}

// The two integrators that share this kernel.
template RGB WhittedIntegrator::Shade(const WhittedIntegrator &, const Ray &, SurfaceInteraction,
                                      int, RayCounters &, const SampleContext &, bool) const;
template RGB WhittedIntegrator::Shade(const DistributionIntegrator &, const Ray &,
                                      SurfaceInteraction, int, RayCounters &, const SampleContext &,
                                      bool) const;

}  // namespace prism
