#include "render/integrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "image/image.h"
#include "render/light_sampling.h"
#include "render/render_scene.h"

namespace prism {

CameraSampler::CameraSampler(const RenderScene &scene, const SamplerSettings &sampler)
    : camera_(*scene.camera),
      sampler_(sampler),
      spp_(uint32_t(sampler.spp)),
      cmj_(uint32_t(sampler.spp)),
      fromPattern_(DrawsCameraDims(sampler.pattern)),
      jitter_(sampler.JitterFilm()),
      lens_(scene.features.lens),
      motion_(scene.features.effects.Has(Effect::MotionBlur)),
      differentials_(scene.differentials),
      diffScale_(std::max(.125f, 1 / std::sqrt(float(sampler.spp)))) {}

PixelSamples PixelSamplesOf(const SamplerSettings &sampler, int x, int y, uint32_t sample,
                            uint32_t spp, const TraceSettings &trace) {
    PixelSamples ps{x, y, sample, spp, sampler.pattern, sampler.seed, trace};
    ps.log2Res = sampler.log2Res;
    ps.scramble = sampler.scramble;
    ps.halton = &sampler.halton;
    ps.sobol = &sampler.sobol;
    return ps;
}

CameraSample CameraSampler::PatternSample(int x, int y, uint32_t s) const {
    const PixelSamples ps = PixelSamplesOf(sampler_, x, y, s, spp_);
    CameraSample cs;
    cs.pFilm = FilmPosition(x, y, jitter_ ? ps.Get2D(0) : Vec2f(0.5f, 0.5f));
    if (motion_) cs.time = ps.Get1D(1);
    if (lens_) cs.uLens = ps.Get2D(2);
    return cs;
}

void TileSamples::Reset(const Bounds2i &b, uint32_t samples) {
    bounds = b;
    spp = samples;
    const size_t n = size_t(b.pMax.x - b.pMin.x) * size_t(b.pMax.y - b.pMin.y) * samples;
    if (L.size() < n) L.resize(n);
    if (wantPositions && pFilm.size() < n) pFilm.resize(n);
    if (wantDirect && direct.size() < n) direct.resize(n);
    splats.clear();
}

void Integrator::RenderTile(const TileContext &ctx, TileSamples &out, RayCounters &rc) const {
    const CameraSampler &camera = ctx.camera;
    const uint32_t spp = out.spp;
    const Bounds2i &tb = out.bounds;
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
        for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
            const CameraSampler::Seeds seeds = camera.PixelSeeds(x, y);
            for (uint32_t s = 0; s < spp; ++s) {
                if (ctx.Cancelled()) return;
                const CameraSample cs = camera.Sample(x, y, s, seeds);
                if (camera.Lens()) rc.lensSamples++;
                const Ray ray = camera.GenerateRay(cs);
                rc.camera++;
                PixelSamples ps = PixelSamplesOf(ctx.sampler, x, y, s, spp, ctx.trace);
                RayDifferential rd;
                if (camera.Differentials()) {
                    rd = camera.GenerateDifferential(ray, cs);
                    ps.diff = &rd;
                }
                const size_t i = out.Index(x, y, s);
                out.L[i] = TileSample(ctx.scene, ray, ps, rc,
                                      out.wantDirect ? &out.direct[i] : nullptr, &out.splats);
                if (out.wantPositions) out.pFilm[i] = cs.pFilm;
            }
        }
}

Image Integrator::RenderFrame(const FrameContext &) const {
    // Render() calls it only when RendersWholeFrame() says so: a programming error.
    throw std::logic_error(std::string("integrator ") + Name() + " renders tiles, not frames");
}

// The Create functions of integrator_list.inc, each defined beside its class.
#define PRISM_INTEGRATOR(name, create) std::unique_ptr<Integrator> create(const IntegratorInputs &);
#include "render/integrator_list.inc"
#undef PRISM_INTEGRATOR

namespace {

struct Registered {
    const char *name;
    std::unique_ptr<Integrator> (*create)(const IntegratorInputs &);
};

constexpr Registered Integrators[] = {
#define PRISM_INTEGRATOR(name, create) {name, &create},
#include "render/integrator_list.inc"
#undef PRISM_INTEGRATOR
};

}  // namespace

std::unique_ptr<Integrator> CreateIntegrator(const std::string &name, const IntegratorInputs &in) {
    for (const Registered &r : Integrators)
        if (name == r.name) return r.create(in);
    return nullptr;
}

const std::vector<std::string> &IntegratorNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const Registered &r : Integrators) v.push_back(r.name);
        return v;
    }();
    return names;
}

}  // namespace prism
