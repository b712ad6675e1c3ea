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

#include "image/film.h"
#include "render/aov.h"

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

}  // namespace

int ForEachTile(int begin, int end, const std::function<void(int t)> &body,
                const volatile int *cancel) {
    std::atomic<int> next{begin}, done{0};
    tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1),
                      [&](const tbb::blocked_range<int> &r) {
                          // Flush denormals to zero, as Embree recommends, in every worker.
                          _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
                          _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
                          for (int i = r.begin(); i != r.end(); ++i) {
                              if (cancel && *cancel) return;
                              // Each body call takes as many tiles as its range holds, but in
                              // global order, so tiles finish nearly in index order and few wait
                              // for their merge.
                              body(next.fetch_add(1));
                              done.fetch_add(1);
                          }
                      });
    return done.load();
}

TileDriver::TileDriver(const RenderScene &scene, const SamplerSettings &sampler, AovFrame *aovs)
    : scene_(scene),
      sampler_(sampler),
      camera_(scene, sampler_),
      context_{scene, sampler_, camera_, scene.integrator->KernelMask(scene)},
      aovs_(aovs) {}

bool TileDriver::RenderTile(int t, const Bounds2i &tb, FilmTile *tile, TileSamples &buf,
                            RayCounters &rc, const volatile int *cancel) const {
    const bool unitBox = tile->UnitBox();
    buf.wantDirect = aovs_ && aovs_->WantsDirect();
    buf.wantPositions = !unitBox || buf.wantDirect;
    buf.Reset(tb, uint32_t(sampler_.spp));
    if (!cancel) {
        scene_.integrator->RenderTile(context_, buf, rc);
    } else {
        // One camera packet at a time, the cancel flag read before each, so that a tile of
        // expensive pixels stops within one packet. The packets are the ones the whole tile
        // would trace (aligned to the tile's corner) and every sample depends only on its
        // pixel and index (per-pixel seeds), so the samples are the same bits.
        static thread_local TileSamples part;
        part.wantDirect = buf.wantDirect;
        part.wantPositions = buf.wantPositions;
        const size_t spp = buf.spp;
        for (int by = tb.pMin.y; by < tb.pMax.y; by += RenderPacketH)
            for (int bx = tb.pMin.x; bx < tb.pMax.x; bx += RenderPacketW) {
                if (*cancel) return false;
                const Bounds2i pb{{bx, by},
                                  {std::min(bx + RenderPacketW, tb.pMax.x),
                                   std::min(by + RenderPacketH, tb.pMax.y)}};
                part.Reset(pb, buf.spp);
                scene_.integrator->RenderTile(context_, part, rc);
                for (int y = pb.pMin.y; y < pb.pMax.y; ++y)
                    for (int x = pb.pMin.x; x < pb.pMax.x; ++x) {
                        const size_t from = part.Index(x, y, 0), to = buf.Index(x, y, 0);
                        std::copy_n(part.L.begin() + ptrdiff_t(from), spp,
                                    buf.L.begin() + ptrdiff_t(to));
                        if (buf.wantPositions)
                            std::copy_n(part.pFilm.begin() + ptrdiff_t(from), spp,
                                        buf.pFilm.begin() + ptrdiff_t(to));
                        if (buf.wantDirect)
                            std::copy_n(part.direct.begin() + ptrdiff_t(from), spp,
                                        buf.direct.begin() + ptrdiff_t(to));
                    }
            }
        if (*cancel) return false;
    }
    // The film's scale, and pbrt's clamp of bright samples (Film "maxsampleluminance"); the
    // direct part is scaled as its sample is.
    const float scale = scene_.filmScale, maxLum = scene_.maxSampleLuminance;
    // Scale 1 without a clamp changes no sample (x * 1 is x): no pass over them.
    const size_t n = scale != 1 || maxLum < Infinity ? size_t(tb.Area()) * buf.spp : 0;
    for (size_t i = 0; i < n; ++i) {
        RGB L = buf.L[i] * scale;
        float clamp = 1;
        if (maxLum < Infinity && L.IsFinite()) {
            const float lum = L.Luminance();
            if (lum > maxLum) {
                clamp = maxLum / lum;
                L *= clamp;
            }
        }
        buf.L[i] = L;
        if (buf.wantDirect) buf.direct[i] = buf.direct[i] * (scale * clamp);
    }
    // Pixel by pixel in the buffer's order (TileSamples::Index), each pixel's samples in turn.
    const int spp = int(buf.spp);
    size_t first = 0;
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
        for (int x = tb.pMin.x; x < tb.pMax.x; ++x, first += size_t(spp)) {
            // pbrt's default box: each pixel's samples go to it at once (they lie in it:
            // FilmPosition).
            if (unitBox) {
                tile->AddPixelSamples({x, y}, buf.L.data() + first, spp);
                continue;
            }
            for (int s = 0; s < spp; ++s)
                tile->AddSample(buf.pFilm[first + size_t(s)], buf.L[first + size_t(s)]);
        }
    if (aovs_) aovs_->AddTile(context_, t, buf);
    return true;
}

Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress,
             const volatile int *cancel) {
    RenderOptions options;
    options.sampler = scene.sampler;
    options.progress = progress;
    options.cancel = cancel;
    return Render(scene, options, stats);
}

Image Render(const RenderScene &scene, const RenderOptions &options, RenderStats *stats) {
    auto start = std::chrono::steady_clock::now();
    const ProgressFn &progress = options.progress;
    TiledFilm film(scene.resolution, scene.pixelBounds, scene.filter, RenderTileSize);
    if (scene.estimateNoise) film.EnableNoiseEstimate();
    const int nTiles = film.NumTiles();
    TileMerger merger(film);
    tbb::enumerable_thread_specific<RayCounters> counters;
    tbb::enumerable_thread_specific<TileSamples> scratch;
    // pbrt's default box filter: each worker resolves its tiles straight into the image
    // (TiledFilm::ResolvesTiles), in a tile buffer of its own; other filters merge in order.
    const bool inPlace = film.EnableResolveInPlace();
    tbb::enumerable_thread_specific<FilmTile> ownTile;
    std::atomic<int> done{0};
    if (options.aovs) options.aovs->BeginPass(nTiles);
    const TileDriver driver(scene, options.sampler, options.aovs);

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

    ForEachTile(
        0, nTiles,
        [&](int t) {
            FilmTile *tile = inPlace ? &ownTile.local() : merger.Acquire();
            film.ResetTile(t, tile);
            if (!driver.RenderTile(t, film.TilePixels(t), tile, scratch.local(), counters.local(),
                                   options.cancel))
                return;  // cancelled inside the tile: it stays unrendered
            if (inPlace)
                film.ResolveTile(t, *tile);
            else
                merger.Submit(t, tile);
            done.fetch_add(1);
        },
        options.cancel);
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
    if (options.aovs && !cancelled) options.aovs->EndPass(options.sampler.spp);
    Image img = film.Finish();
    if (stats) {
        stats->renderSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->spp = options.sampler.spp;
        stats->rays = RayCounters{};
        for (const RayCounters &c : counters) stats->rays += c;
        stats->nonFiniteSamples = film.NonFiniteCount();
        stats->firstNonFinitePixel = film.FirstNonFinitePixel();
        stats->cancelled = cancelled;
        stats->kernelMask = driver.KernelMask();
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
      driver_(scene, scene.sampler, nullptr),
      kernelMask_(driver_.KernelMask()),
      film_(std::make_unique<TiledFilm>(scene.resolution, scene.pixelBounds, scene.filter,
                                        RenderTileSize)) {}

FrameTiles::~FrameTiles() = default;

int FrameTiles::NumTiles() const { return film_->NumTiles(); }

bool FrameTiles::RenderTiles(int begin, int end, std::vector<FilmTile> *tiles, RayCounters *rays,
                             const volatile int *cancel) const {
    tiles->resize(size_t(end - begin));
    tbb::enumerable_thread_specific<RayCounters> counters;
    tbb::enumerable_thread_specific<TileSamples> scratch;
    std::atomic<bool> stopped{false};
    const int ran = ForEachTile(
        begin, end,
        [&](int t) {
            FilmTile *tile = &(*tiles)[size_t(t - begin)];
            film_->ResetTile(t, tile);
            if (!driver_.RenderTile(t, film_->TilePixels(t), tile, scratch.local(),
                                    counters.local(), cancel))
                stopped = true;
        },
        cancel);
    for (const RayCounters &c : counters) *rays += c;
    return !stopped && ran == end - begin;
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
        stats->spp = scene_.sampler.spp;
    }
    return img;
}

}  // namespace prism
