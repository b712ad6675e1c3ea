#include "render/path_integrator.h"

#include <algorithm>

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/differentials.h"
#include "render/kernel.h"
#include "render/render_scene.h"
#include "render/sample_tile.h"

namespace prism {

namespace {
// Consecutive "none" surfaces a path may cross without a bounce (as the Whitted kernel).
constexpr int MaxPassThroughSurfaces = 256;
}  // namespace

RGB PathIntegrator::Li(const Ray &cameraRay, const PixelSamples &ps, RayCounters &counters) const {
    RGB L, beta(1);
    Ray ray = cameraRay;
    bool specularBounce = false;
    float etaScale = 1;  // radiance scaling by refraction, undone for Russian roulette
    int passes = 0;
    for (int bounces = 0;; ++bounces) {
        // Intersect.
        SurfaceInteraction si;
        const bool found = scene_.accel->Intersect(ray, &si);
        const ShapeInfo *info = found ? &scene_.Info(si) : nullptr;
        // Emission that no light sample covered: seen by the camera, or after a delta bounce.
        if (bounces == 0 || specularBounce) {
            if (!found) {
                for (const auto &light : scene_.lights) L += beta * light->Le(ray);
            } else if (info->areaLight >= 0) {
                L += beta *
                     static_cast<const DiffuseAreaLight &>(*scene_.lights[size_t(info->areaLight)])
                         .L(si, si.wo);
            }
        }
        if (!found || bounces >= scene_.maxDepth) break;
        const Material &mat = scene_.materials[size_t(info->material)];
        if (mat.IsPassThrough()) {
            // pbrt: a surface without a BSDF continues the ray without counting a bounce.
            if (++passes > MaxPassThroughSurfaces) break;
            ray = si.SpawnRay(ray.d, scene_.offset);
            counters.passThrough++;
            --bounces;
            continue;
        }
        passes = 0;
        if (mat.PerturbsShading()) mat.PerturbShading(si);
        TextureContext tc{si.uv, si.p, si.uv1};
        // The first hit's footprint (not behind pass-through surfaces: their continued rays
        // carry no differentials, as in the Whitted kernel).
        if (bounces == 0 && ps.diff && ray.o == cameraRay.o)
            ComputeDifferentials(si, *ps.diff, &tc);
        // Emission a material carries itself (glTF emissive textures; no light samples it).
        if (mat.HasEmission()) L += beta * mat.Emitted(tc);
        BSDF bsdf = mat.GetBSDF(si, tc);
        bsdf.MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
        // Direct lighting: one light, light and BSDF samples weighted by MIS.
        if (bsdf.HasNonSpecular())
            L += beta * SampleOneLight(scene_, chooser_, si, bsdf, ps, bounces, counters);
        // Sample the BSDF for the next direction.
        Vec3f wi;
        if (!SampleNextDirection(bsdf, si.wo, ps, bounces, beta, specularBounce, etaScale, &wi,
                                 counters))
            break;
        ray = si.SpawnRay(wi, scene_.offset);
        // Russian roulette (pbrt-v3: after the third bounce, below rrthreshold).
        if (!SurvivesRoulette(beta, etaScale, scene_.rrThreshold, bounces, ps)) break;
    }
    return L;
}

void RenderTilePath(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &,
                    FilmTile *tile) {
    RenderTileWith<PathIntegrator>(scene, tb, rc, tile);
}

}  // namespace prism
