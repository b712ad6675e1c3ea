#include "render/volpath_integrator.h"

#include "render/medium_tracking.h"
#include "render/path_vertex.h"
#include "render/render_scene.h"

namespace prism {

namespace {
// The pattern purpose of a path's medium random stream (distances, ratio tracking).
constexpr uint32_t VolPathPurpose = 0x766f6c70;
}  // namespace

// Integrator "volpath" (integrator_list.inc), read by path's reader (path_integrator.cpp).
// Parameters:
//   maxdepth             integer  5          the longest path (--maxdepth wins)
//   rrthreshold          float    1          Russian roulette below this throughput, after the
//                                            third bounce
//   lightsamplestrategy  string   "spatial"  uniform | power | spatial (the light BVH)
//   lightsampler         string   "bvh"      pbrt-v4's: uniform | power | bvh | exhaustive (as
//                                            bvh, a warning); wins over lightsamplestrategy
//   regularize           bool     false      pbrt-v4's: after a non-specular bounce, surfaces
//                                            smoother than alpha 0.3 are roughened (alpha
//                                            doubled, within [0.1, 0.3]): biased, but it finds
//                                            caustics of small lights
std::unique_ptr<Integrator> CreateVolPathIntegrator(const IntegratorInputs &in) {
    return std::make_unique<VolPathIntegrator>(ReadPathParams(in));
}

IntegratorTraits VolPathIntegrator::Traits() const {
    IntegratorTraits t = PathIntegrator::Traits();
    t.media = true;
    return t;
}

RGB VolPathIntegrator::Li(const RenderScene &scene, const Ray &cameraRay, const PixelSamples &ps,
                          RayCounters &counters, RGB *direct) const {
    PathState path;
    path.regularize = params_.regularize;
    path.subsurface = params_.subsurface;
    RGB &L = path.L, &beta = path.beta;
    Ray ray = cameraRay;
    int medium = scene.cameraMedium;  // the medium the current ray travels in
    Vec3f from = ray.o;               // where that medium segment begins
    int passes = 0;
    bool directDone = false;
    // Medium sampling draws as many numbers as delta and ratio tracking need: one stream per
    // camera sample, a pure function of the pixel and sample.
    MediumSampler sampler((uint64_t(PatternSeed(ps.x, ps.y, VolPathPurpose, ps.passSeed)) << 32) ^
                          ps.SampleNumber());
    for (int bounces = 0;; ++bounces) {
        // Intersect, then sample the medium up to the hit.
        SurfaceInteraction si;
        const bool found = scene.accel->Intersect(ray, &si);
        bool scattered = false;
        MediumInteraction mi;
        if (medium >= 0) {
            beta *= scene.media[size_t(medium)]->Sample(
                MediumSegment(ray, from, found ? &si.p : nullptr), sampler, &mi, &scattered);
            if (beta.IsBlack()) break;
        }
        if (scattered) {
            // A scattering event in the medium: direct lighting through the phase function,
            // then a direction from it.
            if (bounces >= ps.trace.maxDepth) break;
            const Medium &m = *scene.media[size_t(medium)];
            SurfaceInteraction at;
            at.p = mi.p;
            at.wo = -Normalize(ray.d);
            at.time = ray.time;
            const PhaseScatter phase{m.Phase()};
            L += beta * SampleOneLightWith(scene, chooser_, at, phase, ps, bounces, counters,
                                           MediaVisibility{scene, nullptr, medium, sampler});
            Vec3f wi;
            m.Phase().Sample_p(at.wo, &wi, ps.Get2D(VertexDim(bounces, DimBsdf)));
            ray = at.SpawnRay(wi, scene.offset);  // from the point itself (no normal)
            from = ray.o;
            path.specularBounce = false;
            path.anyNonSpecular = true;
            passes = 0;
            counters.reflection++;
            if (bounces == 0 && direct) {
                *direct = L;
                directDone = true;
            }
        } else {
            const ShapeInfo *info = found ? &scene.Info(si) : nullptr;
            // Emission that no light sample covered: seen by the camera, or after a delta
            // bounce (beta holds the transmittance of the media on the way).
            if (bounces == 0 || path.specularBounce)
                AddUnsampledEmission(scene, ray, found ? &si : nullptr, info, path);
            if (!found || bounces >= ps.trace.maxDepth) break;
            const Material &mat = scene.materials[size_t(info->material)];
            if (mat.IsPassThrough()) {
                // A boundary (or any surface without a BSDF): continue in the medium beyond it,
                // without counting a bounce.
                if (++passes > MaxPassThrough) break;
                medium = MediumAfter(*info, si, ray.d, medium);
                ray = si.SpawnRay(ray.d, scene.offset);
                from = si.p;
                counters.passThrough++;
                --bounces;
                continue;
            }
            passes = 0;
            const RayDifferential *diff = bounces == 0 && ray.o == cameraRay.o ? ps.diff : nullptr;
            Vec3f wi;
            const bool more =
                SurfaceVertex(scene, chooser_, si, mat, ps, bounces, diff,
                              MediaVisibility{scene, info, medium, sampler}, path, &wi, counters);
            if (bounces == 0 && direct) {
                *direct = L;
                directDone = true;
            }
            if (!more) break;
            // (A subsurface material moved si to where the light leaves, maybe another shape.)
            info = &scene.Info(si);
            medium = MediumAfter(*info, si, wi, medium);
            ray = si.SpawnRay(wi, scene.offset);
            from = si.p;
        }
        // Russian roulette (pbrt-v3: after the third bounce, below rrthreshold).
        if (!SurvivesRoulette(beta, path.etaScale, params_.rrThreshold, bounces, ps)) break;
    }
    if (direct && !directDone) *direct = L;
    return L;
}

}  // namespace prism
