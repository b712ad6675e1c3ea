#include "render/path_integrator.h"

#include <optional>
#include <string>

#include "core/params.h"
#include "render/effects.h"
#include "render/path_vertex.h"
#include "render/render_scene.h"

namespace prism {

namespace {

// The light choice a name gives (a --light-sampler value, or a lightsampler or
// lightsamplestrategy parameter's), if it names one.
std::optional<LightChoice> LightChoiceNamed(const std::string &s) {
    if (s == "uniform") return LightChoice::Uniform;
    if (s == "power") return LightChoice::Power;
    if (s == "bvh" || s == "spatial") return LightChoice::BVH;
    return std::nullopt;
}

}  // namespace

PathParams ReadPathParams(const IntegratorInputs &in) {
    const Params &p = in.params;
    PathParams pp;
    pp.rrThreshold = p.Float("rrthreshold", 1.f);
    if (!(pp.rrThreshold >= 0)) throw SceneError(in.loc, "rrthreshold must be a number >= 0");
    // pbrt-v3's "lightsamplestrategy" (uniform | power | spatial) and pbrt-v4's "lightsampler"
    // (uniform | power | bvh | exhaustive): pbrt-v3's default "spatial" (a distribution per
    // voxel from the lights' contributions there) and pbrt-v4's "bvh" are both the light BVH,
    // which weighs each light and emissive triangle by its importance at the shading point.
    const char *name = p.Has("lightsampler") ? "lightsampler" : "lightsamplestrategy";
    const std::string lss = p.String(name, "bvh");
    const std::optional<LightChoice> named = LightChoiceNamed(lss);
    pp.lightChoice = named.value_or(LightChoice::BVH);
    if (lss == "exhaustive")
        p.Warn(p.Loc(name),
               "lightsampler \"exhaustive\" is rendered with the light BVH "
               "(\"bvh\"), which chooses by the same importance");
    else if (!named)
        p.Warn(p.Loc(name),
               std::string(name) + " " + Quote(lss) + " is unknown; using the light BVH (\"bvh\")");
    // pbrt-v4's: roughen near-specular surfaces after the first non-specular bounce.
    pp.regularize = p.Bool("regularize", false);
    // --light-sampler wins over the file.
    if (!in.lightSampler.empty())
        pp.lightChoice = LightChoiceNamed(in.lightSampler).value_or(pp.lightChoice);
    // The one effect of the path integrators that no material or light turns on.
    in.effects.Enable(Effect::IndirectIllumination, in.why, in.whyLoc);
    p.WarnUnread(
        "Prism's path integrators read maxdepth, rrthreshold, lightsamplestrategy, "
        "lightsampler and regularize");
    return pp;
}

// Integrator "path" (integrator_list.inc). Parameters:
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
std::unique_ptr<Integrator> CreatePathIntegrator(const IntegratorInputs &in) {
    PathParams pp = ReadPathParams(in);
    pp.subsurface = in.pbrtVersion != 4;
    return std::make_unique<PathIntegrator>(pp);
}

IntegratorTraits PathIntegrator::Traits() const {
    IntegratorTraits t;
    t.samplePatterns = true;
    t.roughGlass = true;
    t.directAov = true;
    t.subsurface = params_.subsurface;
    return t;
}

void PathIntegrator::Prepare(const RenderScene &scene) {
    chooser_ = LightChooser(scene, params_.lightChoice);
}

RGB PathIntegrator::Li(const RenderScene &scene, const Ray &cameraRay, const PixelSamples &ps,
                       RayCounters &counters, RGB *direct) const {
    PathState path;
    path.regularize = params_.regularize;
    path.subsurface = params_.subsurface;
    Ray ray = cameraRay;
    int passes = 0;
    bool directDone = false;
    for (int bounces = 0;; ++bounces) {
        SurfaceInteraction si;
        const bool found = scene.accel->Intersect(ray, &si);
        const ShapeInfo *info = found ? &scene.Info(si) : nullptr;
        if (bounces == 0 || path.specularBounce)
            AddUnsampledEmission(scene, ray, found ? &si : nullptr, info, path);
        if (!found || bounces >= ps.trace.maxDepth) break;
        const Material &mat = scene.materials[size_t(info->material)];
        if (mat.IsPassThrough()) {
            // pbrt: a surface without a BSDF continues the ray without counting a bounce.
            if (++passes > MaxPassThrough) break;
            ray = si.SpawnRay(ray.d, scene.offset);
            counters.passThrough++;
            --bounces;
            continue;
        }
        passes = 0;
        // The first hit's footprint (not behind pass-through surfaces: their continued rays
        // carry no differentials, as in the Whitted kernel).
        const RayDifferential *diff = bounces == 0 && ray.o == cameraRay.o ? ps.diff : nullptr;
        Vec3f wi;
        const bool more = SurfaceVertex(scene, chooser_, si, mat, ps, bounces, diff,
                                        NoMediaVisibility{}, path, &wi, counters);
        if (bounces == 0 && direct) {
            *direct = path.L;
            directDone = true;
        }
        if (!more) break;
        ray = si.SpawnRay(wi, scene.offset);
        // Russian roulette (pbrt-v3: after the third bounce, below rrthreshold).
        if (!SurvivesRoulette(path.beta, path.etaScale, params_.rrThreshold, bounces, ps)) break;
    }
    if (direct && !directDone) *direct = path.L;
    return path.L;
}

}  // namespace prism
