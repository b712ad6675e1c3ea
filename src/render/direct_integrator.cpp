#include "render/direct_integrator.h"

#include "core/params.h"
#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/differentials.h"
#include "render/ray_tree.h"
#include "render/render_scene.h"

namespace prism {

// Integrator "directlighting" (integrator_list.inc). Parameters:
//   maxdepth  integer  5      the longest delta path (--maxdepth wins)
//   strategy  string   "all"  all: every light with its own "nsamples"; one: one light per
//                             sample, chosen uniformly
std::unique_ptr<Integrator> CreateDirectLightingIntegrator(const IntegratorInputs &in) {
    const Params &p = in.params;
    const std::string strategy = p.String("strategy", "all");
    // pbrt-v3: "Strategy \"...\" for direct lighting unknown. Using \"all\"."
    if (strategy != "all" && strategy != "one")
        p.Warn(p.Loc("strategy"), "strategy " + Quote(strategy) + " is unknown; using \"all\"");
    p.WarnUnread("Prism's directlighting integrator reads maxdepth and strategy");
    return std::make_unique<DirectLightingIntegrator>(strategy != "one");
}

IntegratorTraits DirectLightingIntegrator::Traits() const {
    IntegratorTraits t;
    t.samplePatterns = true;
    t.roughGlass = true;
    t.directAov = true;
    return t;
}

// pbrt-v3: strategy "one" picks lights uniformly.
void DirectLightingIntegrator::Prepare(const RenderScene &scene) {
    chooser_ = LightChooser(scene, LightChoice::Uniform);
}

RGB DirectLightingIntegrator::Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                                 RayCounters &rc, RGB *direct) const {
    return Li(scene, ray, ps, 0, kRayTreeBudget, ps.diff, rc, direct);
}

RGB DirectLightingIntegrator::Li(const RenderScene &scene, const Ray &rayIn, const PixelSamples &ps,
                                 int depth, uint64_t treeRays, const RayDifferential *diff,
                                 RayCounters &counters, RGB *direct) const {
    Ray ray = rayIn;
    SurfaceInteraction si;
    const ShapeInfo *info = nullptr;
    for (int pass = 0;; ++pass) {
        if (!scene.accel->Intersect(ray, &si)) {
            RGB L;
            for (const auto &light : scene.lights) L += light->Le(ray);
            if (direct) *direct = L;
            return L;
        }
        info = &scene.Info(si);
        if (!scene.materials[size_t(info->material)].IsPassThrough()) break;
        if (pass >= MaxPassThrough) {
            if (direct) *direct = RGB(0);
            return RGB(0);
        }
        ray = si.SpawnRay(ray.d, scene.offset);
        counters.passThrough++;
    }
    const Material &mat = scene.materials[size_t(info->material)];
    RGB L;
    if (info->areaLight >= 0)
        L += static_cast<const DiffuseAreaLight &>(*scene.lights[size_t(info->areaLight)])
                 .L(si, si.wo);
    if (mat.PerturbsShading()) mat.PerturbShading(si);
    TextureContext tc = SurfaceTextureContext(si);
    // The ray's footprint (not behind pass-through surfaces, whose continued rays carry no
    // differentials).
    if (diff && !(ray.o == rayIn.o)) diff = nullptr;
    if (diff) ComputeDifferentials(si, *diff, &tc);
    if (mat.HasEmission()) L += mat.Emitted(tc);
    BSDF bsdf = mat.GetBSDF(si, tc);
    bsdf.MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
    if (!scene.lights.empty() && bsdf.HasNonSpecular()) {
        if (allLights_)
            L += SampleAllLights(scene, si, bsdf, ps, depth, counters);
        else
            L += SampleOneLight(scene, chooser_, si, bsdf, ps, depth, counters);
    }
    if (direct) *direct = L;
    // Delta reflection and transmission (pbrt-v3 SpecularReflect / SpecularTransmit).
    // The rays of the delta lobes share the ray tree's budget evenly (render/ray_tree.h).
    if (depth + 1 < ps.trace.maxDepth) {
        struct SpecularRay {
            Vec3f wi;
            RGB weight;
            float eta;  // the part's (refraction)
            bool reflect;
        };
        SpecularRay rays[2 * BSDF::MaxParts];
        int n = 0;
        for (int part = 0; part < bsdf.NumParts(); ++part) {
            Vec3f wi;
            RGB weight;
            if (bsdf.SampleSpecularReflection(part, si.wo, &wi, &weight))
                rays[n++] = {wi, weight, 0.f, true};
            if (bsdf.SampleSpecularTransmission(part, si.wo, &wi, &weight))
                rays[n++] = {wi, weight, bsdf.Part(part).eta, false};
        }
        const RayTreeShare share = ShareRayTree(treeRays, uint64_t(n));
        // The surface's curvature across the footprint, once (render/differentials.h).
        NormalDifferentials dn;
        if (diff && n > 0 && share.traced > 0)
            dn = FootprintNormalDifferentials(*scene.accel, si, tc, bsdf.ns);
        for (int i = 0; i < n; ++i) {
            if (uint64_t(i) >= share.traced) {
                counters.treeBudget += uint64_t(n - i);
                break;
            }
            (rays[i].reflect ? counters.reflection : counters.refraction)++;
            RayDifferential rd;
            if (diff)
                rd = rays[i].reflect
                         ? ReflectDifferential(si, tc, *diff, bsdf.ns, dn, rays[i].wi)
                         : RefractDifferential(si, tc, *diff, bsdf.ns, dn, rays[i].wi, rays[i].eta);
            L += rays[i].weight * Li(scene, si.SpawnRay(rays[i].wi, scene.offset), ps, depth + 1,
                                     share.each, diff ? &rd : nullptr, counters, nullptr);
        }
    }
    return L;
}

}  // namespace prism
