#include "render/volpath_integrator.h"

#include <algorithm>

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/estimate_direct.h"
#include "render/medium_tracking.h"
#include "render/render_scene.h"
#include "render/sample_tile.h"

namespace prism {

namespace {
// Consecutive "none" surfaces a path may cross without a bounce (as the path integrator).
constexpr int MaxPassThroughSurfaces = 256;
// The pattern purpose of a path's medium random stream (distances, ratio tracking).
constexpr uint32_t VolPathPurpose = 0x766f6c70;
}  // namespace

RGB VolPathIntegrator::Li(const Ray &cameraRay, const PixelSamples &ps,
                          RayCounters &counters) const {
    RGB L, beta(1);
    Ray ray = cameraRay;
    int medium = scene_.cameraMedium;  // the medium the current ray travels in
    Vec3f from = ray.o;                // where that medium segment begins
    bool specularBounce = false;
    float etaScale = 1;  // radiance scaling by refraction, undone for Russian roulette
    int passes = 0;
    // Medium sampling draws as many numbers as delta and ratio tracking need: one stream per
    // camera sample, a pure function of the pixel and sample.
    MediumSampler sampler(
        (uint64_t(PatternSeed(ps.x, ps.y, VolPathPurpose, scene_.sampleSeed)) << 32) | ps.sample);
    for (int bounces = 0;; ++bounces) {
        // Intersect, then sample the medium up to the hit.
        SurfaceInteraction si;
        const bool found = scene_.accel->Intersect(ray, &si);
        bool scattered = false;
        MediumInteraction mi;
        if (medium >= 0) {
            beta *= scene_.media[size_t(medium)]->Sample(
                MediumSegment(ray, from, found ? &si.p : nullptr), sampler, &mi, &scattered);
            if (beta.IsBlack()) break;
        }
        if (scattered) {
            // A scattering event in the medium: direct lighting through the phase function,
            // then a direction from it.
            if (bounces >= scene_.maxDepth) break;
            const Medium &m = *scene_.media[size_t(medium)];
            SurfaceInteraction at;
            at.p = mi.p;
            at.wo = -Normalize(ray.d);
            at.time = ray.time;
            const PhaseScatter phase{m.Phase()};
            L += beta * SampleOneLightWith(scene_, chooser_, at, phase, ps, bounces, counters,
                                           MediaVisibility{scene_, nullptr, medium, sampler});
            Vec3f wi;
            m.Phase().Sample_p(at.wo, &wi, ps.Get2D(VertexDim(bounces, DimBsdf)));
            ray = at.SpawnRay(wi, scene_.offset);  // from the point itself (no normal)
            from = ray.o;
            specularBounce = false;
            passes = 0;
            counters.reflection++;
        } else {
            const ShapeInfo *info = found ? &scene_.Info(si) : nullptr;
            // Emission that no light sample covered: seen by the camera, or after a delta
            // bounce (beta holds the transmittance of the media on the way).
            if (bounces == 0 || specularBounce) {
                if (!found) {
                    for (const auto &light : scene_.lights) L += beta * light->Le(ray);
                } else if (info->areaLight >= 0) {
                    L += beta * static_cast<const DiffuseAreaLight &>(
                                    *scene_.lights[size_t(info->areaLight)])
                                    .L(si, si.wo);
                }
            }
            if (!found || bounces >= scene_.maxDepth) break;
            const Material &mat = scene_.materials[size_t(info->material)];
            if (mat.IsPassThrough()) {
                // A boundary (or any surface without a BSDF): continue in the medium beyond it,
                // without counting a bounce.
                if (++passes > MaxPassThroughSurfaces) break;
                medium = MediumAfter(*info, si, ray.d, medium);
                ray = si.SpawnRay(ray.d, scene_.offset);
                from = si.p;
                counters.passThrough++;
                --bounces;
                continue;
            }
            passes = 0;
            if (mat.PerturbsShading()) mat.PerturbShading(si);
            const TextureContext tc{si.uv, si.p};
            if (mat.HasEmission()) L += beta * mat.Emitted(tc);
            BSDF bsdf = mat.GetBSDF(si, tc);
            bsdf.MakeRoughSpecularGlossy();
            if (bsdf.HasNonSpecular())
                L += beta * SampleOneLightWith(scene_, chooser_, si, BsdfScatter{bsdf}, ps, bounces,
                                               counters,
                                               MediaVisibility{scene_, info, medium, sampler});
            Vec3f wi;
            if (!SampleNextDirection(bsdf, si.wo, ps, bounces, beta, specularBounce, etaScale, &wi,
                                     counters))
                break;
            medium = MediumAfter(*info, si, wi, medium);
            ray = si.SpawnRay(wi, scene_.offset);
            from = si.p;
        }
        // Russian roulette (pbrt-v3: after the third bounce, below rrthreshold).
        if (!SurvivesRoulette(beta, etaScale, scene_.rrThreshold, bounces, ps)) break;
    }
    return L;
}

void RenderTileVolPath(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &,
                       FilmTile *tile) {
    RenderTileWith<VolPathIntegrator>(scene, tb, rc, tile);
}

}  // namespace prism
