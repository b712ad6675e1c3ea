// The tile-parallel render loop: TBB over tiles, each tile filtered into its own buffer. With
// pbrt's default box filter each tile is resolved straight into the image by its thread
// (image/film.h TiledFilm::ResolvesTiles); other filters reach across tiles, which are then
// merged in a fixed order. Either way the image is identical for any thread count.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "image/image.h"
#include "render/render_scene.h"
#include "render/whitted.h"

namespace prism {

// Tiles are squares of this many pixels (the last row and column may be smaller); the memory
// estimate of the film (core/memory.h EstimateFilmBytes) and bench's ceiling pass use it.
inline constexpr int RenderTileSize = 16;
// Camera rays are traced in packets of RenderPacketW x RenderPacketH pixels at one sample
// index (bench's ceiling pass traces the same packets).
inline constexpr int RenderPacketW = 4, RenderPacketH = 4;

struct RenderStats {
    double renderSeconds = 0;
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;
    std::optional<Vec2i> firstNonFinitePixel;
    bool cancelled = false;   // the cancel flag was raised: the image is incomplete
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

// `cancel`, when given, is polled between tiles; once it reads true the remaining tiles are
// skipped and stats->cancelled is set.
Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress = {},
             const volatile int *cancel = nullptr);

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
    // rays to *rays; the vector is resized and its buffers reused.
    void RenderTiles(int begin, int end, std::vector<FilmTile> *tiles, RayCounters *rays) const;
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
    uint32_t kernelMask_;
    std::unique_ptr<TiledFilm> film_;
};

}  // namespace prism
