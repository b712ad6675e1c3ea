#include "render/mlt_integrator.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/memory.h"
#include "core/params.h"
#include "image/image.h"
#include "render/bdpt_vertex.h"
#include "render/effects.h"
#include "render/medium_tracking.h"
#include "render/mlt_sampler.h"
#include "render/render_scene.h"
#include "render/renderer.h"

namespace prism {

// Integrator "mlt" (integrator_list.inc). Parameters (pbrt-v3's):
//   maxdepth              integer  5       the longest path, in bounces (--maxdepth wins)
//   bootstrapsamples      integer  100000  independent paths (each of every depth) that
//                                          estimate the mean luminance and pick the chains'
//                                          starts
//   chains                integer  1000    Markov chains
//   mutationsperpixel     integer  100     proposals per pixel, over all chains (--spp wins)
//   largestepprobability  float    0.3     the share of proposals that draw a new state
//   sigma                 float    0.01    the standard deviation of the small steps
//   regularize            bool     false   pbrt-v4's: as bdpt's
std::unique_ptr<Integrator> CreateMltIntegrator(const IntegratorInputs &in) {
    const Params &p = in.params;
    MltParams mp;
    const int boot = p.Int("bootstrapsamples", 100000);
    if (boot < 1 || boot > (1 << 26))
        throw SceneError(p.Loc("bootstrapsamples"), "bootstrapsamples " + std::to_string(boot) +
                                                        " out of range (1 to 67108864)");
    mp.bootstrapSamples = boot;
    mp.chains = p.Int("chains", 1000);
    if (mp.chains < 1 || mp.chains > (1 << 24))
        throw SceneError(p.Loc("chains"),
                         "chains " + std::to_string(mp.chains) + " out of range (1 to 16777216)");
    mp.mutationsPerPixel = p.Int("mutationsperpixel", 100);
    if (in.spp > 0) mp.mutationsPerPixel = in.spp;
    if (mp.mutationsPerPixel < 1 || mp.mutationsPerPixel > (1 << 20))
        throw SceneError(p.Loc("mutationsperpixel"), "mutationsperpixel " +
                                                         std::to_string(mp.mutationsPerPixel) +
                                                         " out of range (1 to 1048576)");
    mp.largeStepProbability = p.Float("largestepprobability", 0.3f);
    if (!(mp.largeStepProbability >= 0 && mp.largeStepProbability <= 1))
        throw SceneError(p.Loc("largestepprobability"), "largestepprobability must lie in [0, 1]");
    mp.sigma = p.Float("sigma", 0.01f);
    if (!(mp.sigma > 0) || !std::isfinite(mp.sigma))
        throw SceneError(p.Loc("sigma"), "sigma must be a finite number > 0");
    mp.regularize = p.Bool("regularize", false);
    in.effects.Enable(Effect::IndirectIllumination, in.why, in.whyLoc);
    p.WarnUnread(
        "Prism's mlt reads maxdepth, bootstrapsamples, chains, mutationsperpixel, "
        "largestepprobability, sigma and regularize");
    return std::make_unique<MltIntegrator>(mp, in.loc);
}

IntegratorTraits MltIntegrator::Traits() const {
    IntegratorTraits t;
    t.roughGlass = true;
    t.media = true;
    return t;
}

void MltIntegrator::Prepare(const RenderScene &scene) {
    chooser_ = LightChooser(scene, LightChoice::Power);
    sphere_ = BoundingSphere(scene);
    infinityMedium_ = MediumAtInfinity(scene);
    if (scene.camera) camera_ = CameraImportance(*scene.camera, scene.pixelBounds);
    if (scene.camera && !camera_.Supported())
        throw SceneError(loc_, "Integrator \"mlt\" needs a perspective camera (as in pbrt-v3)");
}

RGB MltIntegrator::Li(const RenderScene &, const Ray &, const PixelSamples &, RayCounters &,
                      RGB *direct) const {
    if (direct) *direct = RGB(0);
    return RGB(0);
}

namespace {

// The dimensions a state draws beside bdpt's (which start at 16).
enum MltDim : uint32_t { MltDimStrategy = 0, MltDimFilm = 1, MltDimLens = 2, MltDimTime = 3 };

uint64_t Mix(uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    return h;
}
// The seed of bootstrap state k, and of chain i's own decisions.
uint64_t StateSeed(uint64_t k, uint32_t seed) { return Mix(k * 0x9E3779B97F4A7C15ULL + seed); }
uint64_t ChainSeed(uint64_t i, uint32_t seed) {
    return Mix((i + 1) * 0xD1B54A32D192ED03ULL ^ (uint64_t(seed) << 32));
}

// What the chains weigh states by: the luminance (0 for nothing or a non-finite path).
float Weight(const RGB &L) {
    const float y = L.Luminance();
    return std::isfinite(y) && y > 0 ? y : 0.f;
}

struct Splat {
    uint32_t pixel;
    RGB L;
};

}  // namespace

RGB MltIntegrator::PathRadiance(const FrameContext &frame, const MltSampler &sampler, int depth,
                                Vec2f *raster, RayCounters &rc) const {
    const RenderScene &scene = frame.scene;
    // The strategy: s light and t camera vertices, s + t = depth + 2, each as likely. Depth 0
    // too has two (pbrt-v3 takes only s = 0 there, which drops the share MIS gives light
    // tracing of a light the camera sees).
    const int nStrategies = depth + 2;
    const int s =
        std::min(int(sampler.Get1D(MltDimStrategy) * float(nStrategies)), nStrategies - 1);
    const int t = nStrategies - s;
    const Bounds2i &pb = frame.Pixels();
    const Vec2f u = sampler.Get2D(MltDimFilm);
    Vec2f pFilm(float(pb.pMin.x) + u.x * float(pb.Width()),
                float(pb.pMin.y) + u.y * float(pb.Height()));
    pFilm.x = std::min(pFilm.x, NextFloatDown(float(pb.pMax.x)));
    pFilm.y = std::min(pFilm.y, NextFloatDown(float(pb.pMax.y)));
    const Vec2f uLens = sampler.Get2D(MltDimLens);
    const float time = sampler.Get1D(MltDimTime);
    const Ray ray = scene.camera->GenerateRay(pFilm, uLens, time);
    std::optional<RayDifferential> diff;
    if (scene.differentials) {
        const float scale = std::max(0.125f, 1 / std::sqrt(float(params_.mutationsPerPixel)));
        diff = scene.camera->GenerateDifferential(ray, pFilm, uLens, time, scale);
    }
    thread_local std::vector<BdptVertex> cameraPath, lightPath;
    // The subpaths have exactly t and s vertices: bdpt's walks with depths to match.
    const BdptContext cameraCtx{scene, chooser_,           camera_,        sphere_,
                                t - 2, params_.regularize, infinityMedium_};
    CameraSubpath(cameraCtx, ray, sampler, diff ? &*diff : nullptr, cameraPath, rc);
    if (int(cameraPath.size()) != t) return RGB(0);
    // A light sample (s = 1, t > 1) draws its own light: no light subpath, which a light may
    // not emit along the direction drawn (a projection light's cone outside its frustum).
    lightPath.clear();
    if (s > 1 || (s == 1 && t == 1)) {
        const BdptContext lightCtx{scene, chooser_,           camera_,        sphere_,
                                   s - 1, params_.regularize, infinityMedium_};
        LightSubpath(lightCtx, sampler, lightPath, rc);
        if (int(lightPath.size()) != s) return RGB(0);
    }
    *raster = pFilm;
    const RGB c = ConnectStrategy(cameraCtx, lightPath, cameraPath, s, t, sampler, raster, rc);
    return c * float(nStrategies);
}

Image MltIntegrator::RenderFrame(const FrameContext &frame) const {
    const RenderScene &scene = frame.scene;
    const Bounds2i &pb = frame.Pixels();
    const int64_t nPixels = pb.Area();
    const int nDepths = std::max(frame.trace.maxDepth, 0) + 1;
    const uint32_t seed = frame.sampler.seed;
    const auto black = [&] {
        frame.SetProgress(1);
        return frame.MakeImage([](int, int) { return RGB(0); });
    };
    if (!scene.camera || scene.lights.empty() || nPixels <= 0) return black();
    const int64_t nBoot = params_.bootstrapSamples;
    const int64_t total = int64_t(params_.mutationsPerPixel) * nPixels;
    const int nChains = params_.chains;
    // Chains run in batches whose splats are held until they are summed in chain order; the
    // batch size depends on the parameters alone, never on the thread count.
    const int64_t perChain = (total / nChains + 1) * 2 * int64_t(sizeof(Splat));
    const int batch = int(std::clamp<int64_t>((int64_t(64) << 20) / perChain, 1, nChains));
    {
        MemoryBudget budget(scene.memoryLimit);
        budget.Charge(std::min(scene.memoryCommitted, budget.Limit()), "scene");
        budget.Check(uint64_t(nBoot * nDepths) * (sizeof(float) + sizeof(double)) +
                         uint64_t(nPixels) * 3 * sizeof(double) + uint64_t(batch * perChain),
                     "mlt's bootstrap weights, splat sums and chain splats");
    }

    // The bootstrap: for every sample one independent state per depth.
    std::vector<float> weights(size_t(nBoot * nDepths));
    frame.ForEach(0, int(nBoot), [&](int i, RayCounters &rc) {
        for (int depth = 0; depth < nDepths; ++depth) {
            const size_t k = size_t(i) * size_t(nDepths) + size_t(depth);
            MltSampler sampler(StateSeed(k, seed), params_.sigma);
            sampler.StartIteration(true);
            Vec2f raster;
            weights[k] = Weight(PathRadiance(frame, sampler, depth, &raster, rc));
        }
    });
    if (frame.Cancelled()) return black();
    std::vector<double> cdf(weights.size());
    double sum = 0;
    for (size_t k = 0; k < weights.size(); ++k) cdf[k] = sum += weights[k];
    if (!(sum > 0)) return black();
    const double b = sum / double(nBoot);
    frame.SetProgress(0.1);

    std::vector<double> acc(size_t(nPixels) * 3, 0.0);
    const int w = pb.Width(), h = pb.Height();
    const auto chain = [&](int i, std::vector<Splat> &out, RayCounters &rc) {
        const auto add = [&](Vec2f p, const RGB &L) {
            const int x = std::clamp(int(std::floor(p.x)) - pb.pMin.x, 0, w - 1);
            const int y = std::clamp(int(std::floor(p.y)) - pb.pMin.y, 0, h - 1);
            const uint32_t pixel = uint32_t(y) * uint32_t(w) + uint32_t(x);
            if (!out.empty() && out.back().pixel == pixel)
                out.back().L += L;
            else
                out.push_back({pixel, L});
        };
        PCG32 rng(ChainSeed(uint64_t(i), seed), 0x63686169u);
        // The start: a bootstrap state drawn in proportion to its luminance, made again.
        const double uStart = rng.UniformDouble() * sum;
        size_t k = size_t(std::upper_bound(cdf.begin(), cdf.end(), uStart) - cdf.begin());
        k = std::min(k, cdf.size() - 1);
        const int depth = int(k % size_t(nDepths));
        MltSampler sampler(StateSeed(k, seed), params_.sigma);
        sampler.StartIteration(true);
        Vec2f pCur;
        RGB Lc = PathRadiance(frame, sampler, depth, &pCur, rc);
        sampler.Accept();
        float yc = Weight(Lc);
        if (!(yc > 0)) return;
        const int64_t n = (int64_t(i) + 1) * total / nChains - int64_t(i) * total / nChains;
        for (int64_t j = 0; j < n; ++j) {
            if ((j & 1023) == 0 && frame.Cancelled()) return;
            sampler.StartIteration(rng.Uniform() < params_.largeStepProbability);
            Vec2f pProp;
            const RGB Lp = PathRadiance(frame, sampler, depth, &pProp, rc);
            const float yp = Weight(Lp);
            const float a = std::min(1.f, yp / yc);
            // Both states, each weighted by its share of this step (Veach's expected values).
            if (a > 0) add(pProp, Lp * (a / yp));
            if (a < 1) add(pCur, Lc * ((1 - a) / yc));
            if (rng.Uniform() < a) {
                pCur = pProp, Lc = Lp, yc = yp;
                sampler.Accept();
            } else {
                sampler.Reject();
            }
        }
    };
    std::vector<std::vector<Splat>> splats(static_cast<size_t>(batch));
    for (int first = 0; first < nChains && !frame.Cancelled(); first += batch) {
        const int count = std::min(batch, nChains - first);
        frame.ForEach(0, count, [&](int j, RayCounters &rc) {
            splats[size_t(j)].clear();
            chain(first + j, splats[size_t(j)], rc);
        });
        if (frame.Cancelled()) break;
        for (int j = 0; j < count; ++j)
            for (const Splat &sp : splats[size_t(j)]) {
                double *a = &acc[size_t(sp.pixel) * 3];
                a[0] += sp.L.r, a[1] += sp.L.g, a[2] += sp.L.b;
            }
        frame.SetProgress(0.1 + 0.9 * double(first + count) / nChains);
    }
    frame.SetSamplesPerPixel(params_.mutationsPerPixel);
    frame.SetProgress(1);
    const double scale = b / params_.mutationsPerPixel;
    return frame.MakeImage([&](int x, int y) {
        const double *a = &acc[(size_t(y - pb.pMin.y) * size_t(w) + size_t(x - pb.pMin.x)) * 3];
        return RGB(float(a[0] * scale), float(a[1] * scale), float(a[2] * scale));
    });
}

}  // namespace prism
