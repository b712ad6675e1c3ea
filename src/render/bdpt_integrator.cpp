#include "render/bdpt_integrator.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/params.h"
#include "render/bdpt_vertex.h"
#include "render/effects.h"
#include "render/medium_tracking.h"
#include "render/render_scene.h"

namespace prism {

// Integrator "bdpt" (integrator_list.inc). Parameters:
//   maxdepth             integer  5        the longest path, in bounces (--maxdepth wins)
//   lightsamplestrategy  string   "power"  uniform | power | spatial (as power, a warning):
//                                          the light of each light subpath and light sample
//   visualizestrategies  bool     false    pbrt-v3's per-strategy images: ignored (a warning)
//   visualizeweights     bool     false    the same, weighted: ignored (a warning)
//   regularize           bool     false    pbrt-v4's: after a subpath's first non-specular
//                                          bounce, its surfaces' near-specular lobes are
//                                          roughened (docs/INTEGRATORS.md "Regularization")
std::unique_ptr<Integrator> CreateBdptIntegrator(const IntegratorInputs &in) {
    const Params &p = in.params;
    const std::string lss = p.String("lightsamplestrategy", "power");
    LightChoice choice = LightChoice::Power;
    if (lss == "uniform") {
        choice = LightChoice::Uniform;
    } else if (lss == "spatial") {
        // A light subpath starts without a shading point to weigh the lights for.
        p.Warn(p.Loc("lightsamplestrategy"),
               "lightsamplestrategy \"spatial\" is rendered as \"power\" by bdpt (its light "
               "subpaths start without a point to weigh the lights for)");
    } else if (lss != "power") {
        p.Warn(p.Loc("lightsamplestrategy"),
               "lightsamplestrategy " + Quote(lss) + " is unknown; using \"power\"");
    }
    for (const char *name : {"visualizestrategies", "visualizeweights"})
        if (p.Bool(name, false))
            p.Warn(p.Loc(name),
                   std::string(name) + " is ignored: Prism writes the one image of all strategies");
    in.effects.Enable(Effect::IndirectIllumination, in.why, in.whyLoc);
    const bool regularize = p.Bool("regularize", false);
    p.WarnUnread(
        "Prism's bdpt reads maxdepth, lightsamplestrategy, visualizestrategies, "
        "visualizeweights and regularize");
    return std::make_unique<BdptIntegrator>(choice, regularize, in.loc);
}

IntegratorTraits BdptIntegrator::Traits() const {
    IntegratorTraits t;
    t.samplePatterns = true;
    t.roughGlass = true;
    t.splats = true;
    t.media = true;
    return t;
}

void BdptIntegrator::Prepare(const RenderScene &scene) {
    chooser_ = LightChooser(scene, choice_);
    sphere_ = BoundingSphere(scene);
    infinityMedium_ = MediumAtInfinity(scene);
    if (scene.camera) camera_ = CameraImportance(*scene.camera, scene.pixelBounds);
    if (scene.camera && !camera_.Supported())
        throw SceneError(loc_, "Integrator \"bdpt\" needs a perspective camera (as in pbrt-v3)");
}

RGB BdptIntegrator::Sample(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                           RayCounters &rc, std::vector<SampleSplat> *splats) const {
    thread_local std::vector<BdptVertex> cameraPath, lightPath;
    const size_t capacity = size_t(ps.trace.maxDepth) + 3;
    if (cameraPath.capacity() < capacity) cameraPath.reserve(capacity);
    if (lightPath.capacity() < capacity) lightPath.reserve(capacity);
    const BdptContext ctx{scene,       chooser_,       camera_, sphere_, ps.trace.maxDepth,
                          regularize_, infinityMedium_};
    const BdptPixelSamples samples(ps);
    CameraSubpath(ctx, ray, samples, ps.diff, cameraPath, rc);
    LightSubpath(ctx, samples, lightPath, rc);
    RGB L;
    const int nc = int(cameraPath.size()), nl = int(lightPath.size());
    for (int t = 1; t <= nc; ++t) {
        if (t == 1 && !splats) continue;
        // s = 1 samples its light itself (ConnectStrategy), with or without a light subpath.
        for (int s = 0; s <= std::max(nl, 1); ++s) {
            const int depth = s + t - 2;
            if (depth < 0 || depth > ps.trace.maxDepth) continue;
            Vec2f raster;
            const RGB c = ConnectStrategy(ctx, lightPath, cameraPath, s, t, samples, &raster, rc);
            if (c.IsBlack()) continue;
            if (t > 1) {
                L += c;
            } else {
                const Vec2i pixel(int(std::floor(raster.x)), int(std::floor(raster.y)));
                splats->push_back({pixel, Vec2i(ps.x, ps.y), c});
            }
        }
    }
    return L;
}

RGB BdptIntegrator::Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                       RayCounters &rc, RGB *direct) const {
    const RGB L = Sample(scene, ray, ps, rc, nullptr);
    if (direct) *direct = L;
    return L;
}

RGB BdptIntegrator::TileSample(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                               RayCounters &rc, RGB *direct,
                               std::vector<SampleSplat> *splats) const {
    const RGB L = Sample(scene, ray, ps, rc, splats);
    if (direct) *direct = L;
    return L;
}

}  // namespace prism
