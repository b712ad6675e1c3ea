// The one tile driver. Every render (`prism render`, batch, progressive passes, prism-mpi's
// FrameTiles, bench's ceiling pass) runs its tiles through ForEachTile, and every shading pass
// through TileDriver: the scene's integrator fills a tile's camera samples (render/integrator.h),
// the driver applies the film scale and the sample clamp, adds the samples to the film tile and
// hands them to the AOVs. With pbrt's default box filter each tile is resolved straight into the
// image by its thread (image/film.h TiledFilm::ResolvesTiles); other filters reach across
// tiles, which are then merged in a fixed order. Either way the image is identical for any
// thread count.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "image/image.h"
#include "render/integrator.h"
#include "render/render_scene.h"

namespace prism {

// Tiles are squares of this many pixels (the last row and column may be smaller); the memory
// estimate of the film (core/memory.h EstimateFilmBytes) and bench's ceiling pass use it.
inline constexpr int RenderTileSize = 16;
// Camera rays are traced in packets of RenderPacketW x RenderPacketH pixels at one sample
// index (bench's ceiling pass traces the same packets).
inline constexpr int RenderPacketW = 4, RenderPacketH = 4;

class AovFrame;

struct RenderStats {
    double renderSeconds = 0;
    int spp = 0;  // samples per pixel rendered (all passes of a progressive render)
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;
    std::optional<Vec2i> firstNonFinitePixel;
    bool cancelled = false;  // the cancel flag was raised: the image is incomplete
    // Progressive renders: the time limit ran out before the first pass finished (cancelled
    // is set too: there is no image).
    bool timedOut = false;
    uint32_t kernelMask = 0;  // the kernel that ran (render/kernel.h KernelMaskName)
    // With scene.estimateNoise: the estimated variance of the image, summed over its pixels
    // and channels (image/film.h FilmTile::NoiseVariance), and how many pixels it covers.
    double noiseVariance = 0;
    uint64_t noisePixels = 0;
    // Progressive renders (render/progressive.h): the samples per pixel of each pass.
    std::vector<int> passSpp;
};

// The relative standard error of `img` estimated from stats' noise variance:
// sqrt(noise variance / sum of the squared pixel values), the quantity --target-error and
// `prism study` call relative RMSE, predicted against the converged image. nullopt when no
// pixel has samples in both halves (1 spp) or the image is black.
std::optional<double> RelativeStandardError(const Image &img, const RenderStats &stats);

// Called with the fraction done (0..1), from a single thread.
using ProgressFn = std::function<void(double fraction)>;

// How one render runs, beside the scene.
struct RenderOptions {
    SamplerSettings sampler;  // usually the scene's (RenderScene::sampler)
    // Depth and cutoff (empty: the scene's, RenderScene::trace): the studies render their
    // references deeper without touching the scene.
    std::optional<TraceSettings> trace;
    ProgressFn progress;
    // Polled between tiles and inside them before every camera packet (TileDriver::RenderTile);
    // once it reads true the remaining work is skipped and stats->cancelled is set.
    const volatile int *cancel = nullptr;
    AovFrame *aovs = nullptr;  // the AOVs, computed from this render's own tiles
    // Whole-frame integrators (FrameContext::Intermediate): an image of the frame so far, to
    // be written as the output is (sppm's "imagewritefrequency"). Called from the rendering
    // thread between passes; empty: none are written.
    std::function<void(const Image &)> intermediate;
};

Image Render(const RenderScene &scene, const RenderOptions &options, RenderStats *stats);
// With the scene's sampler and no AOVs.
Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress = {},
             const volatile int *cancel = nullptr);

// The one parallel loop over tiles [begin, end): TBB workers take tile indices in order from a
// shared counter (so tiles finish nearly in index order), with denormals flushed to zero in
// every worker as Embree recommends; per-thread state goes in the caller's
// tbb::enumerable_thread_specific. body(t) runs once per tile. Stops taking tiles once
// *cancel reads true; returns how many tiles ran.
int ForEachTile(int begin, int end, const std::function<void(int t)> &body,
                const volatile int *cancel = nullptr);

// What Render() hands a whole-frame integrator (Integrator::RendersWholeFrame): the scene,
// the render's sampler and trace settings, and the conventions of the tile path. Its
// parallel loops run through ForEach (ForEachTile with the render's cancel flag and a ray
// counter per worker); the film's tiles (TilePixels) are the tile driver's, so work per tile
// is the same partition whatever the thread count. Thread-safe where marked.
class FrameContext {
  public:
    FrameContext(const RenderScene &scene, const RenderOptions &options);
    ~FrameContext();

    const RenderScene &scene;
    const SamplerSettings &sampler;
    const TraceSettings trace;  // RenderOptions::trace, else the scene's

    // The crop window and its RenderTileSize tiles, row by row.
    const Bounds2i &Pixels() const { return scene.pixelBounds; }
    int NumTiles() const { return nx_ * ny_; }
    Bounds2i TilePixels(int t) const;
    // body(i, rays) for every i in [begin, end), in parallel (ForEachTile), with the calling
    // worker's ray counters; stops taking work once the render is cancelled.
    void ForEach(int begin, int end,
                 const std::function<void(int i, RayCounters &rays)> &body) const;
    bool Cancelled() const { return options_.cancel && *options_.cancel; }
    // The fraction done (0..1), reported to RenderOptions::progress. Any thread.
    void SetProgress(double fraction) const;
    // The samples per pixel stats report (sppm: its iterations done).
    void SetSamplesPerPixel(int spp) const { spp_ = spp; }
    int SamplesPerPixel() const { return spp_; }
    // The crop window's image with pixel(x, y) (crop pixel coordinates of the full image) times
    // the film scale, filled in parallel; non-finite pixels are counted for the stats and
    // written as 0, as the film does.
    Image MakeImage(const std::function<RGB(int x, int y)> &pixel) const;
    // RenderOptions::intermediate, when there is one.
    bool WantsIntermediate() const { return bool(options_.intermediate); }
    void Intermediate(const Image &img) const;

    // For Render(): the counters summed, and the non-finite pixels of the last MakeImage.
    RayCounters Rays() const;
    uint64_t NonFinitePixels() const { return nonFinite_; }
    std::optional<Vec2i> FirstNonFinitePixel() const { return firstNonFinite_; }
    double Progress() const;

  private:
    struct Workers;
    const RenderOptions &options_;
    int nx_ = 0, ny_ = 0;
    std::unique_ptr<Workers> workers_;
    mutable int spp_ = 0;
    mutable uint64_t nonFinite_ = 0;
    mutable std::optional<Vec2i> firstNonFinite_;
};

// The per-tile work of one shading render: the scene's integrator fills the camera samples of
// a tile, the film scale and clamp are applied, and the samples go to the film tile and the
// AOVs. Immutable: RenderTile runs on any worker.
class TileDriver {
  public:
    TileDriver(const RenderScene &scene, const SamplerSettings &sampler, const TraceSettings &trace,
               AovFrame *aovs);
    uint32_t KernelMask() const { return context_.kernelMask; }
    // Renders tile t (pixels tb) into `tile` (reset by the caller), with buf as scratch.
    // With a cancel flag it is read before every camera packet (RenderPacketW x
    // RenderPacketH pixels, all their samples): once it reads true the tile is abandoned
    // and false returned (`tile` is then incomplete and must not be merged).
    bool RenderTile(int t, const Bounds2i &tb, FilmTile *tile, TileSamples &buf, RayCounters &rc,
                    const volatile int *cancel = nullptr) const;

  private:
    const RenderScene &scene_;
    SamplerSettings sampler_;
    TraceSettings trace_;
    CameraSampler camera_;
    TileContext context_;
    AovFrame *aovs_;
};

// A frame rendered tile by tile by a caller that hands the tiles out itself (prism-mpi: tiles
// rendered on other processes). Rendering every tile with RenderTile and merging them with
// MergeNext in index order gives exactly Render()'s image: the same tiles, kernel, samples and
// merge order.
class FrameTiles {
  public:
    explicit FrameTiles(const RenderScene &scene);
    ~FrameTiles();

    int NumTiles() const;
    uint32_t KernelMask() const { return kernelMask_; }
    // Renders tiles [begin, end) in parallel (TBB) into tiles[0 .. end - begin), adding their
    // rays to *rays; the vector is resized and its buffers reused. With a cancel flag it is
    // read as Render reads it (between tiles and before every camera packet): returns false
    // once it read true, the tiles incomplete.
    bool RenderTiles(int begin, int end, std::vector<FilmTile> *tiles, RayCounters *rays,
                     const volatile int *cancel = nullptr) const;
    // Prepares `tile` (bounds, filter, zeroed sums) for tile t: a receiver fills its sums with
    // FilmTile::Sums() before merging.
    void ResetTile(int t, FilmTile *tile) const;
    // Merges the next tile in index order (NextTile()).
    void MergeNext(const FilmTile &tile);
    int NextTile() const;
    // After the last merge: the image, with stats' non-finite sample counts and kernel set.
    Image Finish(RenderStats *stats);

  private:
    const RenderScene &scene_;
    TileDriver driver_;
    uint32_t kernelMask_;
    std::unique_ptr<TiledFilm> film_;
};

}  // namespace prism
