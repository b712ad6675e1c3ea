// The integrator interface and the one camera sample every pass draws.
//
// An Integrator is created from the scene's Integrator directive by its own Create (beside its
// class; the list is integrator_list.inc) and held by the RenderScene. The one tile driver
// (render/renderer.h) hands it a tile at a time: its RenderTile fills the radiance of every
// camera sample of the tile (TileSamples), and the driver adds them to the film and derives
// the AOVs from them. RenderTile's default traces each camera sample's ray through Li; the
// Whitted/distribution kernel overrides it with its packet path.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "geometry/ray.h"
#include "image/bounds2.h"
#include "render/camera.h"
#include "render/halton.h"
#include "render/ray_counters.h"
#include "render/sampler.h"
#include "render/sobol_sampler.h"

namespace prism {

// Consecutive invisible-interface ("none" material) crossings allowed before a ray is dropped,
// in every integrator; guards against stacks of coincident surfaces without changing any real
// scene.
inline constexpr int MaxPassThrough = 256;

class EffectSet;
class FrameContext;
class Params;
struct Image;
struct PixelSamples;
struct RenderScene;

// The sampler of a render: samples per pixel, the seed mixed into every pattern (0 for a
// render; each pass of a progressive render has its own) and the pattern the path
// integrators draw their dimensions from. Progressive passes change this, not the scene.
struct SamplerSettings {
    int spp = 1;
    uint32_t seed = 0;
    SamplePattern pattern = SamplePattern::Stratified;
    // The Sobol patterns': pixels lie within 2^log2Res squared (the full film's resolution
    // rounded up to a power of two), and how their points are randomised.
    uint8_t log2Res = 0;
    SobolScramble scramble = SobolScramble::Owen;
    // The Halton pattern's film tiling and randomisation.
    HaltonFrame halton;
    // The global Sobol pattern's film sequence and randomisation.
    SobolFrame sobol;
    // One sample per pixel sits at the pixel centre, except in the later passes of a
    // progressive render, whose pattern seeds differ.
    bool JitterFilm() const { return !centres && (spp > 1 || seed != 0); }
    // pbrt-v4's Option "disablepixeljitter": every sample at its pixel's centre.
    bool centres = false;
};

// Where on the film, on the lens and in the shutter one camera sample lies.
struct CameraSample {
    Vec2f pFilm;
    Vec2f uLens{0.5f, 0.5f};
    float time = 0;
};

// The samples of camera sample `sample` of `spp` of pixel (x, y) as `sampler` draws them: its
// pattern, seed, Sobol and Halton settings (render/light_sampling.h).
PixelSamples PixelSamplesOf(const SamplerSettings &sampler, int x, int y, uint32_t sample,
                            uint32_t spp, const TraceSettings &trace = {});

// The camera samples of a render. Every pass that traces camera rays (the integrators' tiles,
// the AOVs, bench's ceiling) draws them here, so they trace the same rays by construction.
// Film, lens and time are stratified over the pixel's samples (correlated multi-jittered).
class CameraSampler {
  public:
    CameraSampler(const RenderScene &scene, const SamplerSettings &sampler);

    // The pattern seeds of pixel (x, y), computed once for all its samples; none are needed
    // without jitter, lens or motion (Seeded false: a sample is the pixel centre).
    struct Seeds {
        uint32_t film = 0, lens = 0, time = 0;
    };
    bool Seeded() const { return jitter_ || lens_ || motion_; }
    Seeds PixelSeeds(int x, int y) const {
        Seeds s;
        if (jitter_) s.film = PatternSeed(x, y, FilmPurpose, sampler_.seed);
        if (lens_) s.lens = PatternSeed(x, y, LensPurpose, sampler_.seed);
        if (motion_) s.time = PatternSeed(x, y, TimePurpose, sampler_.seed);
        return s;
    }
    // Sample s of pixel (x, y).
    CameraSample Sample(int x, int y, uint32_t s, const Seeds &seeds) const {
        if (fromPattern_) return PatternSample(x, y, s);
        CameraSample cs;
        cs.pFilm = FilmPosition(x, y, jitter_ ? cmj_.Sample(s, seeds.film) : Vec2f(0.5f, 0.5f));
        if (lens_) cs.uLens = cmj_.Sample(s, seeds.lens);
        if (motion_) cs.time = cmj_.Sample(s, seeds.time).x;
        return cs;
    }
    Ray GenerateRay(const CameraSample &cs) const {
        return camera_.GenerateRay(cs.pFilm, cs.uLens, cs.time);
    }
    // The radiance weight of the sample's ray (Camera::RayWeight: 1 but for a lens system).
    float RayWeight(const CameraSample &cs) const { return camera_.RayWeight(cs.pFilm, cs.uLens); }
    bool HasRayWeights() const { return camera_.HasRayWeights(); }
    // The ray's differentials (pbrt-v3: scaled by max(1/8, 1/sqrt(spp))).
    RayDifferential GenerateDifferential(const Ray &ray, const CameraSample &cs) const {
        return camera_.GenerateDifferential(ray, cs.pFilm, cs.uLens, cs.time, diffScale_);
    }

    uint32_t Spp() const { return spp_; }
    bool Lens() const { return lens_; }  // lens samples are drawn (depth of field)
    bool Motion() const { return motion_; }
    // Camera rays carry differentials (some texture filters: RenderScene::differentials).
    bool Differentials() const { return differentials_; }

  private:
    // The camera dimensions of the Sobol and Halton patterns (pbrt-v4 draws the film position,
    // time and lens sample from its sampler first): PixelSamples dimensions 0 to 2, which no
    // vertex uses (render/light_sampling.h PathDimBase).
    CameraSample PatternSample(int x, int y, uint32_t s) const;

    const Camera &camera_;
    SamplerSettings sampler_;
    uint32_t spp_;
    CMJPattern cmj_;
    bool fromPattern_, jitter_, lens_, motion_, differentials_;
    float diffScale_;
};

// Radiance a camera sample adds to some pixel of the film other than through its own film
// position: light tracing (the bidirectional integrator's t = 1 strategies). The film adds it
// unfiltered, divided by the samples per pixel (pbrt-v3 Film::AddSplat).
struct SampleSplat {
    Vec2i pixel;  // the pixel it lands in (in the crop window)
    Vec2i from;   // the pixel of the camera sample that traced it
    RGB L;
};

// The camera samples of one tile as an integrator fills them, pixel by pixel, each pixel's
// samples in order (Index).
struct TileSamples {
    Bounds2i bounds;
    uint32_t spp = 1;
    std::vector<RGB> L;          // the radiance of each sample, as Li returns it
    std::vector<Vec2f> pFilm;    // each sample's film position, when wantPositions
    std::vector<RGB> direct;     // its direct part (Integrator::Li), when wantDirect
    bool wantPositions = false;  // the film's filter reaches beyond a sample's pixel
    bool wantDirect = false;     // the direct/indirect AOVs are rendered
    // Splats (Traits().splats), in the order the tile's samples made them: pixel by pixel,
    // each pixel's samples in order. Reset empties it.
    std::vector<SampleSplat> splats;

    size_t Index(int x, int y, uint32_t s) const {
        return (size_t(y - bounds.pMin.y) * size_t(bounds.pMax.x - bounds.pMin.x) +
                size_t(x - bounds.pMin.x)) *
                   spp +
               s;
    }
    // Sizes the buffers for tile b (reused from tile to tile).
    void Reset(const Bounds2i &b, uint32_t samples);
};

// What a render passes to an integrator's tile.
struct TileContext {
    const RenderScene &scene;
    const SamplerSettings &sampler;
    const TraceSettings &trace;
    const CameraSampler &camera;
    uint32_t kernelMask = 0;  // Integrator::KernelMask, chosen once per render
    // The render's cancel flag (or null): a RenderTile reads it at least once per camera
    // sample, or per packet of one sample in RenderPacketW x RenderPacketH pixels (the
    // kernel's), and returns once it reads true,
    // leaving the tile incomplete (the driver then drops it). Cancelled() reads it.
    const volatile int *cancel = nullptr;
    bool Cancelled() const { return cancel && *cancel; }
};

// What the rest of Prism asks of an integrator, beside rendering.
struct IntegratorTraits {
    // Sampler "random" and "02sequence" are drawn as pbrt-v3 draws them (PixelSamples); false:
    // the stratified patterns of the kernel.
    bool samplePatterns = false;
    bool media = false;         // renders participating media (else: a warning, as pbrt-v3)
    bool roughGlass = false;    // renders rough glass rough (Whitted follows its delta lobes)
    bool directAov = false;     // Li's direct part is exact (the direct and indirect AOVs)
    bool effectKernel = false;  // runs the kernel specialized per effect set (render/kernel.h)
    bool glossyRays = false;    // traces glossy rays (Integrator "distribution")
    // Follows light through subsurface materials (else their interface alone, as pbrt-v3).
    bool subsurface = false;
    // Its tiles splat radiance onto other pixels (TileSamples::splats): the film then merges
    // tiles in order (their splats reach any pixel), never resolves them in place.
    bool splats = false;
};

class Integrator {
  public:
    virtual ~Integrator() = default;
    virtual const char *Name() const = 0;
    virtual IntegratorTraits Traits() const = 0;
    // Called once the scene is built (the lights exist): per-scene state such as the light
    // choice. The integrator is immutable during a render.
    virtual void Prepare(const RenderScene &scene) {}
    // What Prepare chose for the scene that the render summary should say ("lights: ..."),
    // or empty.
    virtual std::string Summary() const { return {}; }
    // The effect kernel a render of `scene` runs (render/kernel.h), chosen once per render; 0
    // for integrators without one.
    virtual uint32_t KernelMask(const RenderScene &scene, const TraceSettings &trace) const {
        return 0;
    }

    // The radiance along camera ray `ray` of camera sample ps. *direct, when not null, gets its
    // direct part: emission and direct lighting at the first surface (or medium) vertex.
    virtual RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                   RayCounters &rc, RGB *direct) const = 0;
    // One camera sample of a tile, the default RenderTile's step: Li. An integrator whose
    // samples also land on other pixels (light tracing) adds those to *splats.
    virtual RGB TileSample(const RenderScene &scene, const Ray &ray, const PixelSamples &ps,
                           RayCounters &rc, RGB *direct, std::vector<SampleSplat> *splats) const {
        return Li(scene, ray, ps, rc, direct);
    }
    // Fills out's radiance for every camera sample of tile out.bounds: by default each
    // sample's camera ray (CameraSampler) through TileSample. Stops early once
    // ctx.Cancelled().
    virtual void RenderTile(const TileContext &ctx, TileSamples &out, RayCounters &rc) const;

    // Whole-frame integrators (sppm; mlt) are not a sum of independent camera samples:
    // their passes share state across the frame (photons, visible points, Markov chains).
    // For them Render() calls RenderFrame instead of its tile loop, and RenderFrame makes the
    // image, running its parallel loops through frame.ForEach (render/renderer.h
    // FrameContext: the film's tiles, the cancel flag, progress, ray counters, intermediate
    // images). Such an integrator's Li and RenderTile are not called by Render.
    virtual bool RendersWholeFrame() const { return false; }
    // The crop window's image (FrameContext::MakeImage applies the film scale).
    virtual Image RenderFrame(const FrameContext &frame) const;
};

// What an integrator's Create reads.
struct IntegratorInputs {
    const Params &params;   // the Integrator directive's (or none's: every default)
    FileLoc loc;            // the directive (invalid: the scene names no Integrator)
    int glossySamples = 0;  // --glossy-samples (0: the file's)
    // --spp (0: the file's). Integrators whose effort per pixel is not a sample count read it
    // as theirs: sppm's iterations, mlt's mutations per pixel.
    int spp = 0;
    // The scene's effects: an integrator enables what it simulates of its own (path: indirect
    // illumination), with `why` (at whyLoc) as the reason.
    EffectSet &effects;
    std::string why;
    FileLoc whyLoc;
    int pbrtVersion = 3;  // the pbrt rules the file is read by (scene/pbrt_version.h)
    // --light-sampler ("bvh", "power", "uniform"; "": the parameters'), for the integrators
    // that choose one light per shadow ray.
    std::string lightSampler;
};

// The integrator registered as `name` (integrator_list.inc), or null when none is.
std::unique_ptr<Integrator> CreateIntegrator(const std::string &name, const IntegratorInputs &in);
// The registered names, in list order.
const std::vector<std::string> &IntegratorNames();

}  // namespace prism
