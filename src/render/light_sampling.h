// Direct lighting with multiple importance sampling, shared by the path and directlighting
// integrators (pbrt-v3 integrator.cpp: UniformSampleAllLights, UniformSampleOneLight,
// EstimateDirect), and the per-dimension sample stream they draw from.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "geometry/interaction.h"
#include "render/halton.h"
#include "render/light_bvh.h"
#include "render/sampler.h"
#include "render/sobol_sampler.h"

namespace prism {

struct BSDF;
struct RenderScene;
struct RayCounters;
class Light;

// The power heuristic with exponent 2 (Veach): the weight of a sample drawn nf times from the
// density fPdf against ng times from gPdf.
inline float PowerHeuristic(int nf, float fPdf, int ng, float gPdf) {
    const float f = float(nf) * fPdf, g = float(ng) * gPdf;
    if (std::isinf(f * f)) return 1;
    return f * f + g * g > 0 ? (f * f) / (f * f + g * g) : 0.f;
}

// Samples of one camera sample, a pure function of (pixel, sample index, dimension), so images
// do not depend on the thread count or tile order. Each dimension is its own correlated
// multi-jittered pattern over the pixel's spp samples (render/sampler.h), seeded per pixel and
// dimension: pbrt's "stratified" sampler padded per dimension, which stands in for pbrt's
// low-discrepancy samplers (docs/INTEGRATORS.md shows it converges as fast).
struct PixelSamples {
    int x = 0, y = 0;
    uint32_t sample = 0, spp = 1;
    SamplePattern pattern = SamplePattern::Stratified;
    uint32_t passSeed = 0;  // SamplerSettings::seed: differs between progressive passes
    TraceSettings trace;    // the render's (TileContext::trace)
    // The camera ray's differentials where a texture filters (RenderScene::differentials),
    // else null; read at the first hit only (pbrt-v3's path tracer drops them after it).
    const RayDifferential *diff = nullptr;

    // The Sobol patterns' film size (pixels within 2^log2Res squared) and randomisation
    // (SamplerSettings).
    uint8_t log2Res = 0;
    SobolScramble scramble = SobolScramble::Owen;
    // The Halton pattern's film tiling and randomisation (SamplerSettings::halton).
    const HaltonFrame *halton = nullptr;
    // The pixel's first Halton point, computed at the first draw (a pure function of x, y and
    // the frame, which a PixelSamples does not change; not to be set).
    mutable uint64_t haltonPixel_ = ~uint64_t(0);
    // The global Sobol pattern's film sequence (SamplerSettings::sobol), and the index of this
    // camera sample's point, computed at the first draw (not to be set).
    const SobolFrame *sobol = nullptr;
    mutable uint64_t sobolIndex_ = ~uint64_t(0);

    Vec2f Get2D(uint32_t dim) const { return Get2D(dim, 0, 1); }
    // Sample k of n of this camera sample (strategy "all": n light samples stratified over
    // spp × n).
    Vec2f Get2D(uint32_t dim, uint32_t k, uint32_t n) const {
        const uint32_t i = sample * n + k;
        if (pattern == SamplePattern::ZSobol)
            return ZSobolSample2D(x, y, i, spp * n, log2Res, dim, passSeed, scramble);
        if (pattern == SamplePattern::Halton && HaltonDim(dim, true) != NoHaltonDim)
            return HaltonGet2D(dim, i, n);
        if (pattern == SamplePattern::Sobol && HaltonDim(dim, true) != NoHaltonDim)
            return SobolGet2D(dim, i, n);
        const uint32_t seed = PatternSeed(x, y, 0x32446d00u + dim, PatternPassSeed());
        switch (pattern) {
            case SamplePattern::Independent:
                return {HashFloat(i, seed), HashFloat(i, seed ^ 0x9e3779b9u)};
            case SamplePattern::ZeroTwo:
                return Sample02(PermuteIndex(i, spp * n, seed), seed * 0x68bc21ebu,
                                seed * 0x02e5be93u);
            case SamplePattern::PaddedSobol:
                return PaddedSobolSample2D(i, spp * n, seed, scramble);
            default:
                return CMJSample(i, spp * n, seed);
        }
    }
    float Get1D(uint32_t dim) const {
        if (pattern == SamplePattern::ZSobol)
            return ZSobolSample1D(x, y, sample, spp, log2Res, dim, passSeed, scramble);
        if (pattern == SamplePattern::Halton) {
            const uint32_t h = HaltonDim(dim, false);
            if (h != NoHaltonDim)
                return HaltonSample(*Halton(), HaltonIndex(sample, 1), h, passSeed);
        }
        if (pattern == SamplePattern::Sobol) {
            const uint32_t h = HaltonDim(dim, false);
            if (h != NoHaltonDim) return Sobol()->Sample(SobolIndex(sample, 1), h, passSeed);
        }
        const uint32_t seed = PatternSeed(x, y, 0x31446d00u + dim, PatternPassSeed());
        if (pattern == SamplePattern::Independent) return HashFloat(sample, seed);
        if (pattern == SamplePattern::PaddedSobol)
            return PaddedSobolSample1D(sample, spp, seed, scramble);
        const uint32_t stratum = PermuteIndex(sample, spp, seed);
        if (pattern == SamplePattern::ZeroTwo) return Sample02(stratum, seed * 0x68bc21ebu, 0).x;
        const float u = (float(stratum) + HashFloat(sample, seed * 0x68bc21ebu)) / float(spp);
        return std::min(u, 0x1.fffffep-1f);
    }

    // The camera sample's number in the whole render: a progressive render's Halton passes
    // continue the earlier passes' samples (their seed stays), so the random streams drawn
    // beside the patterns (volpath's medium sampling) are keyed by it, not by `sample`.
    uint64_t SampleNumber() const {
        if (pattern == SamplePattern::Halton) return Halton()->firstSample + sample;
        return pattern == SamplePattern::Sobol ? Sobol()->firstSample + sample : sample;
    }

  private:
    // The per-dimension patterns' seed: the pass's, and under Halton (whose passes keep the
    // seed and continue the sequence) the pass's first sample too, so the dimensions Halton
    // leaves to them are drawn anew in every pass.
    uint32_t PatternPassSeed() const {
        uint64_t first = 0;
        if (pattern == SamplePattern::Halton && halton) first = halton->firstSample;
        if (pattern == SamplePattern::Sobol && sobol) first = sobol->firstSample;
        return first == 0 ? passSeed : passSeed ^ uint32_t(MixBits64(first));
    }
    // Halton: the film's point i of this pixel, and its dimensions h and h + 1 (the position
    // in the pixel for h = 0, moved by the pass's seed in later passes of a progressive render).
    // (Without a frame, as for a 1 x 1 film.)
    const HaltonFrame *Halton() const {
        static const HaltonFrame single;
        return halton ? halton : &single;
    }
    // Point i of n per camera sample (Get2D's k of n).
    uint64_t HaltonIndex(uint32_t i, uint32_t n) const {
        const HaltonFrame &h = *Halton();
        if (haltonPixel_ == ~uint64_t(0)) haltonPixel_ = h.PixelIndex(x, y);
        return haltonPixel_ + (h.firstSample * n + i) * h.stride;
    }
    // Sobol: the film's point i of n of this pixel per camera sample, and its dimensions h and
    // h + 1 (the position in the pixel for h = 0), as Halton's.
    const SobolFrame *Sobol() const {
        static const SobolFrame single;
        return sobol ? sobol : &single;
    }
    uint64_t SobolIndex(uint32_t i, uint32_t n) const {
        const SobolFrame &f = *Sobol();
        const uint64_t point = f.firstSample * n + i;
        if (n != 1) return f.Index(x, y, point);
        if (sobolIndex_ == ~uint64_t(0)) sobolIndex_ = f.Index(x, y, point);
        return sobolIndex_;
    }
    Vec2f SobolGet2D(uint32_t dim, uint32_t i, uint32_t n) const {
        const uint64_t index = SobolIndex(i, n);
        const uint32_t h = HaltonDim(dim, true);
        if (h == 0) return Sobol()->PixelOffset(index, x, y);
        return {Sobol()->Sample(index, h, passSeed), Sobol()->Sample(index, h + 1, passSeed)};
    }
    Vec2f HaltonGet2D(uint32_t dim, uint32_t i, uint32_t n) const {
        const uint64_t index = HaltonIndex(i, n);
        const uint32_t h = HaltonDim(dim, true);
        if (h == 0) return Halton()->PixelOffset(index, passSeed);
        return {HaltonSample(*Halton(), index, h, passSeed),
                HaltonSample(*Halton(), index, h + 1, passSeed)};
    }
};

// The dimensions one path vertex draws (16 per bounce from PathDimBase).
enum PathDim : uint32_t {
    PathDimBase = 16,
    PathDimsPerBounce = 16,
    DimLightChoice = 0,  // 1-D
    DimLight = 1,        // 2-D: the point on the light
    DimScatter = 2,      // 2-D: the BSDF sample of direct lighting
    DimScatterLobe = 3,  // 1-D: its lobe
    DimBsdf = 4,         // 2-D: the BSDF sample that continues the path
    DimBsdfLobe = 5,     // 1-D: its lobe
    DimRoulette = 6,     // 1-D: Russian roulette
    // A subsurface vertex (render/subsurface.h): the probe's axis, channel and hit (1-D), its
    // radius and angle (2-D), and the exit's light and BSDF samples, which draw dimensions
    // DimLightChoice .. DimBsdfLobe shifted by DimSubsurfaceExit.
    DimSubsurface = 7,
    DimSubsurfaceProbe = 8,
    DimSubsurfaceExit = 9,
};
static_assert(DimSubsurfaceExit + DimBsdfLobe < PathDimsPerBounce);
inline uint32_t VertexDim(int bounce, uint32_t d) {
    return PathDimBase + uint32_t(bounce) * PathDimsPerBounce + d;
}

// pbrt-v3's Russian roulette: after the third bounce, a path whose throughput (with the
// refraction scaling etaScale undone) is below `threshold` ends with probability
// max(0.05, 1 - throughput), or goes on with beta divided by the survival probability.
// Returns false when the path ends.
inline bool SurvivesRoulette(RGB &beta, float etaScale, float threshold, int bounces,
                             const PixelSamples &ps) {
    const float b = (beta * etaScale).MaxComponent();
    if (!(b < threshold) || bounces <= 3) return true;
    const float q = std::max(0.05f, 1 - b);
    if (ps.Get1D(VertexDim(bounces, DimRoulette)) < q) return false;
    beta = beta / (1 - q);
    return true;
}

// The path's next direction, sampled from the BSDF (pbrt-v3 PathIntegrator): beta takes the
// sample's weight, specularBounce and etaScale (the refraction scaling Russian roulette undoes)
// follow it, and the ray is counted as a reflection or a refraction. False when the BSDF gives
// no sample: the path ends.
bool SampleNextDirection(const BSDF &bsdf, const Vec3f &wo, const PixelSamples &ps, int bounces,
                         RGB &beta, bool &specularBounce, float &etaScale, Vec3f *wi,
                         RayCounters &counters, uint32_t dimShift = 0);

// Fills scene.lightPower (each light's power, for LightChoice::Power) once the lights and
// shapes are built.
void ComputeLightPower(RenderScene &scene);
// The sphere bounding the scene's shapes (the radius ComputeLightPower uses), where distant
// and infinite lights start the rays they emit (render/light.h Light::SampleLe).
struct SceneSphere;
SceneSphere BoundingSphere(const RenderScene &scene);

// How the integrators choose the light of a one-light direct-lighting sample: uniformly, in
// proportion to the lights' power, or from the light BVH (render/light_bvh.h: by each light's
// and each emissive triangle's importance at the shading point; pbrt-v4's "bvh", the path
// integrators' default, and what pbrt-v3's "spatial" is rendered with).
enum class LightChoice { Uniform, Power, BVH };

class LightChooser {
  public:
    LightChooser() = default;  // no lights
    LightChooser(const RenderScene &scene, LightChoice choice);
    // A light for the point p with unit normal n (zero in a medium), by u in [0,1): under BVH
    // maybe one triangle of an emissive mesh; otherwise Choose's light whole.
    LightPick Pick(float u, const Vec3f &p, const Vec3f &n) const {
        if (bvh_) return bvh_->Sample(u, p, n);
        LightPick pick;
        pick.light = Choose(u, &pick.prob);
        return pick;
    }
    // A light without a shading point (light tracing: by power under BVH), and its
    // probability; -1 when there are no lights.
    int Choose(float u, float *prob) const;
    // The probability with which Choose picks light i.
    float Prob(int i) const;
    const LightBVH *Bvh() const { return bvh_.get(); }
    // "lights: chosen by the light BVH (N parts, depth D; K from infinitely far)", "... by
    // power", "... uniformly"; empty without lights.
    std::string Summary() const;

  private:
    std::vector<double> cdf_;  // empty: uniform
    int n_ = 0;
    std::shared_ptr<const LightBVH> bvh_;
};

// pbrt-v3 EstimateDirect: one light sample (weighted against the BSDF's density by the power
// heuristic) plus, for lights that rays can hit, one BSDF sample (weighted against the light's
// density). f is the BSDF's non-delta lobes (its delta lobes carry no direct light).
RGB EstimateDirect(const RenderScene &scene, const SurfaceInteraction &si, const BSDF &bsdf,
                   int lightIndex, Vec2f uLight, Vec2f uScatter, float uLobe,
                   RayCounters &counters);

// pbrt-v3 UniformSampleOneLight: one light, chosen by `chooser`, divided by its probability.
RGB SampleOneLight(const RenderScene &scene, const LightChooser &chooser,
                   const SurfaceInteraction &si, const BSDF &bsdf, const PixelSamples &ps,
                   int bounce, RayCounters &counters);

// pbrt-v3 UniformSampleAllLights: every light with its own sample count ("nsamples"), the
// samples stratified over the pixel's samples × that count.
RGB SampleAllLights(const RenderScene &scene, const SurfaceInteraction &si, const BSDF &bsdf,
                    const PixelSamples &ps, int depth, RayCounters &counters);

}  // namespace prism
