#include "render/renderer.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "render/direct_integrator.h"
#include "render/kernel.h"
#include "render/path_integrator.h"
#include "render/volpath_integrator.h"

namespace prism {

namespace {

// Finished tiles wait here until every tile before them has been merged, so the film sums
// tiles in index order whatever the thread count. Workers take tile indices in order from an
// atomic counter, so only about one tile per thread waits at a time; tile buffers are recycled.
class TileMerger {
  public:
    explicit TileMerger(TiledFilm &film) : film_(film), ready_(size_t(film.NumTiles())) {}

    FilmTile *Acquire() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (free_.empty()) {
            pool_.push_back(std::make_unique<FilmTile>());
            return pool_.back().get();
        }
        FilmTile *t = free_.back();
        free_.pop_back();
        return t;
    }
    // Hands over tile t; merges every tile that is now next in order.
    void Submit(int t, FilmTile *tile) {
        std::lock_guard<std::mutex> lock(mutex_);
        ready_[size_t(t)] = tile;
        for (int n = film_.NextTile(); n < film_.NumTiles() && ready_[size_t(n)];
             n = film_.NextTile()) {
            film_.MergeNext(ready_[size_t(n)]);
            free_.push_back(ready_[size_t(n)]);
        }
    }
    // After the loop: merges what is left (tiles skipped by a cancel merge as empty).
    bool Flush() {
        bool complete = true;
        while (film_.NextTile() < film_.NumTiles()) {
            const FilmTile *tile = ready_[size_t(film_.NextTile())];
            complete &= tile != nullptr;
            film_.MergeNext(tile);
        }
        return complete;
    }

  private:
    TiledFilm &film_;
    std::mutex mutex_;
    std::vector<FilmTile *> ready_;
    std::vector<std::unique_ptr<FilmTile>> pool_;
    std::vector<FilmTile *> free_;
};

// The tile function of the scene's integrator: the path and directlighting integrators, or the
// Whitted/distribution kernel specialized for `mask`.
RenderTileFn TileFunction(const RenderScene &scene, uint32_t mask) {
    switch (scene.integrator) {
        case IntegratorKind::Path:
            return &RenderTilePath;
        case IntegratorKind::VolPath:
            return &RenderTileVolPath;
        case IntegratorKind::DirectLighting:
            return &RenderTileDirect;
        default:
            return KernelRenderTile(mask);
    }
}

}  // namespace

Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress,
             const volatile int *cancel) {
    auto start = std::chrono::steady_clock::now();
    TiledFilm film(scene.resolution, scene.pixelBounds, scene.filter, RenderTileSize);
    if (scene.estimateNoise) film.EnableNoiseEstimate();
    int nTiles = film.NumTiles();
    TileMerger merger(film);
    std::atomic<int> nextTile{0};
    tbb::enumerable_thread_specific<RayCounters> counters;
    tbb::enumerable_thread_specific<TileScratch> scratch;
    // pbrt's default box filter: each worker resolves its tiles straight into the image
    // (TiledFilm::ResolvesTiles), in a tile buffer of its own; other filters merge in order.
    const bool inPlace = film.EnableResolveInPlace();
    tbb::enumerable_thread_specific<FilmTile> ownTile;
    std::atomic<int> done{0};
    // The kernel is chosen here, once per render: the one specialized for the scene's effects
    // (render/kernel.h), or the general one for --effects all.
    const uint32_t kernelMask = scene.allEffects ? KernelAllFor(scene) : KernelMaskFor(scene);
    const RenderTileFn renderTile = TileFunction(scene, kernelMask);

    // Progress is reported from a helper thread so worker threads never block on output.
    std::mutex mutex;
    std::condition_variable cv;
    bool finished = false;
    std::thread reporter;
    if (progress) {
        reporter = std::thread([&] {
            std::unique_lock<std::mutex> lock(mutex);
            while (!cv.wait_for(lock, std::chrono::milliseconds(250), [&] { return finished; }))
                progress(double(done.load()) / nTiles);
        });
    }

    tbb::parallel_for(tbb::blocked_range<int>(0, nTiles, 1), [&](const tbb::blocked_range<int> &r) {
        // Flush denormals to zero, as Embree recommends, in every worker.
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        RayCounters &rc = counters.local();
        for (int i = r.begin(); i != r.end(); ++i) {
            if (cancel && *cancel) return;
            // Each body call takes as many tiles as its range holds, but in global order, so
            // tiles finish nearly in index order and few wait for their merge.
            int t = nextTile.fetch_add(1);
            Bounds2i tb = film.TilePixels(t);
            FilmTile *tile = inPlace ? &ownTile.local() : merger.Acquire();
            film.ResetTile(t, tile);
            renderTile(scene, tb, rc, scratch.local(), tile);
            if (inPlace)
                film.ResolveTile(t, *tile);
            else
                merger.Submit(t, tile);
            done.fetch_add(1);
        }
    });
    if (progress) {
        {
            std::lock_guard<std::mutex> lock(mutex);
            finished = true;
        }
        cv.notify_all();
        reporter.join();
        progress(1.0);
    }
    bool cancelled = inPlace ? done.load() < nTiles : !merger.Flush();
    Image img = film.Finish();
    if (stats) {
        stats->renderSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = RayCounters{};
        for (const RayCounters &c : counters) stats->rays += c;
        stats->nonFiniteSamples = film.NonFiniteCount();
        stats->firstNonFinitePixel = film.FirstNonFinitePixel();
        stats->cancelled = cancelled;
        stats->kernelMask = kernelMask;
        stats->noiseVariance = film.NoiseVariance();
        stats->noisePixels = film.NoisePixels();
    }
    return img;
}

std::optional<double> RelativeStandardError(const Image &img, const RenderStats &stats) {
    if (stats.noisePixels == 0) return std::nullopt;
    double signal = 0;
    for (float v : img.pixels)
        if (std::isfinite(v)) signal += double(v) * double(v);
    if (!(signal > 0)) return std::nullopt;
    return std::sqrt(stats.noiseVariance / signal);
}

}  // namespace prism

namespace prism {

FrameTiles::FrameTiles(const RenderScene &scene)
    : scene_(scene),
      kernelMask_(scene.allEffects ? KernelAllFor(scene) : KernelMaskFor(scene)),
      film_(std::make_unique<TiledFilm>(scene.resolution, scene.pixelBounds, scene.filter,
                                        RenderTileSize)) {}

FrameTiles::~FrameTiles() = default;

int FrameTiles::NumTiles() const { return film_->NumTiles(); }

void FrameTiles::RenderTiles(int begin, int end, std::vector<FilmTile> *tiles,
                             RayCounters *rays) const {
    tiles->resize(size_t(end - begin));
    const RenderTileFn renderTile = TileFunction(scene_, kernelMask_);
    tbb::enumerable_thread_specific<RayCounters> counters;
    tbb::enumerable_thread_specific<TileScratch> scratch;
    tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1),
                      [&](const tbb::blocked_range<int> &r) {
                          // As in Render(): denormals flushed to zero in every worker, so the
                          // samples match.
                          _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
                          _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
                          RayCounters &rc = counters.local();
                          for (int t = r.begin(); t != r.end(); ++t) {
                              FilmTile *tile = &(*tiles)[size_t(t - begin)];
                              film_->ResetTile(t, tile);
                              renderTile(scene_, film_->TilePixels(t), rc, scratch.local(), tile);
                          }
                      });
    for (const RayCounters &c : counters) *rays += c;
}

void FrameTiles::ResetTile(int t, FilmTile *tile) const { film_->ResetTile(t, tile); }

void FrameTiles::MergeNext(const FilmTile &tile) { film_->MergeNext(&tile); }

int FrameTiles::NextTile() const { return film_->NextTile(); }

Image FrameTiles::Finish(RenderStats *stats) {
    Image img = film_->Finish();
    if (stats) {
        stats->nonFiniteSamples = film_->NonFiniteCount();
        stats->firstNonFinitePixel = film_->FirstNonFinitePixel();
        stats->kernelMask = kernelMask_;
    }
    return img;
}

}  // namespace prism
