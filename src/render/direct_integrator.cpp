#include "render/direct_integrator.h"

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/differentials.h"
#include "render/kernel.h"
#include "render/render_scene.h"
#include "render/sample_tile.h"

namespace prism {

namespace {
constexpr int MaxPassThroughSurfaces = 256;
}  // namespace

RGB DirectLightingIntegrator::Li(const Ray &rayIn, const PixelSamples &ps, int depth,
                                 RayCounters &counters) const {
    Ray ray = rayIn;
    SurfaceInteraction si;
    const ShapeInfo *info = nullptr;
    for (int pass = 0;; ++pass) {
        if (!scene_.accel->Intersect(ray, &si)) {
            RGB L;
            for (const auto &light : scene_.lights) L += light->Le(ray);
            return L;
        }
        info = &scene_.Info(si);
        if (!scene_.materials[size_t(info->material)].IsPassThrough()) break;
        if (pass >= MaxPassThroughSurfaces) return RGB(0);
        ray = si.SpawnRay(ray.d, scene_.offset);
        counters.passThrough++;
    }
    const Material &mat = scene_.materials[size_t(info->material)];
    RGB L;
    if (info->areaLight >= 0)
        L += static_cast<const DiffuseAreaLight &>(*scene_.lights[size_t(info->areaLight)])
                 .L(si, si.wo);
    if (mat.PerturbsShading()) mat.PerturbShading(si);
    TextureContext tc{si.uv, si.p, si.uv1};
    // The camera ray's footprint at its first hit (not behind pass-through surfaces).
    if (depth == 0 && ps.diff && ray.o == rayIn.o) ComputeDifferentials(si, *ps.diff, &tc);
    if (mat.HasEmission()) L += mat.Emitted(tc);
    BSDF bsdf = mat.GetBSDF(si, tc);
    bsdf.MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
    if (!scene_.lights.empty() && bsdf.HasNonSpecular()) {
        if (scene_.directAllLights)
            L += SampleAllLights(scene_, si, bsdf, ps, depth, counters);
        else
            L += SampleOneLight(scene_, chooser_, si, bsdf, ps, depth, counters);
    }
    // Delta reflection and transmission (pbrt-v3 SpecularReflect / SpecularTransmit).
    if (depth + 1 < scene_.maxDepth) {
        Vec3f wi;
        RGB weight;
        for (int part = 0; part < bsdf.NumParts(); ++part) {
            if (bsdf.SampleSpecularReflection(part, si.wo, &wi, &weight)) {
                counters.reflection++;
                L += weight * Li(si.SpawnRay(wi, scene_.offset), ps, depth + 1, counters);
            }
            if (bsdf.SampleSpecularTransmission(part, si.wo, &wi, &weight)) {
                counters.refraction++;
                L += weight * Li(si.SpawnRay(wi, scene_.offset), ps, depth + 1, counters);
            }
        }
    }
    return L;
}

void RenderTileDirect(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &,
                      FilmTile *tile) {
    RenderTileWith<DirectLightingIntegrator>(scene, tb, rc, tile);
}

}  // namespace prism
