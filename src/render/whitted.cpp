#include "render/whitted.h"

#include "core/params.h"
#include "render/light_sampling.h"
#include "render/render_scene.h"

namespace prism {

namespace {
// The general kernel without glossy rays.
using WhittedKernel = Kernel<KernelGeneral>;
KernelParams TracerParams(const RenderScene &scene) {
    KernelParams p;
    p.effects = KernelAll & ~uint32_t(KernelGlossy);
    p.trace = scene.trace;
    return p;
}
}  // namespace

// Integrator "whitted" (integrator_list.inc). Parameters:
//   maxdepth  integer  5  the longest specular path (read by the scene assembly for every
//                         integrator; --maxdepth wins)
std::unique_ptr<Integrator> CreateWhittedIntegrator(const IntegratorInputs &in) {
    in.params.WarnUnread("Prism's Whitted integrator reads only maxdepth");
    return std::make_unique<WhittedIntegrator>();
}

IntegratorTraits WhittedIntegrator::Traits() const {
    IntegratorTraits t;
    t.media = true;
    t.effectKernel = true;
    t.glossyRays = params_.glossyRays;
    t.roughGlass = params_.glossyRays;
    // With glossy rays, lights reach glossy lobes through either light samples or glossy rays:
    // the kernel without glossy rays would not give the beauty's direct part.
    t.directAov = !params_.glossyRays;
    return t;
}

uint32_t WhittedIntegrator::KernelMask(const RenderScene &scene, const TraceSettings &trace) const {
    return scene.allEffects ? KernelAllFor(scene) : KernelMaskFor(scene, trace);
}

RGB WhittedIntegrator::Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                          RayCounters &rc, RGB *direct) const {
    KernelParams p = params_;
    p.seed = ps.passSeed;
    p.trace = ps.trace;
    SampleContext sc{ps.x, ps.y, ps.sample, ps.spp};
    sc.diff = ps.diff;
    RawHit hit;
    if (!scene.accel->IntersectRaw(ray, &hit)) hit.shape = -1;
    rc.camera++;
    const uint32_t mask = KernelMask(scene, ps.trace);
    p.effects = mask;
    RGB L = mask & KernelMedia ? Kernel<KernelMediaMask>(scene, p).LiCamera(ray, hit, rc, sc)
                               : Kernel<KernelGeneral>(scene, p).LiCamera(ray, hit, rc, sc);
    if (direct) *direct = KernelDirectLiCamera(scene, p, ray, hit, rc, sc);
    return L;
}

void WhittedIntegrator::RenderTile(const TileContext &ctx, TileSamples &out,
                                   RayCounters &rc) const {
    KernelParams p = params_;
    p.seed = ctx.sampler.seed;
    p.effects = ctx.kernelMask;
    p.trace = ctx.trace;
    KernelRenderTile(ctx.kernelMask)(ctx, p, out, rc);
}

RGB WhittedTracer::Li(const Ray &ray, int depth, RayCounters &counters,
                      const SampleContext &sc) const {
    return WhittedKernel(scene_, TracerParams(scene_)).Li(ray, depth, counters, sc);
}

RGB WhittedTracer::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                            const SampleContext &sc) const {
    return WhittedKernel(scene_, TracerParams(scene_)).LiCamera(ray, hit, counters, sc);
}

}  // namespace prism
