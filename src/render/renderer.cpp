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
#include <functional>
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

// Reports progress from a helper thread (every 250 ms, then 1 at the end), so worker threads
// never block on output; fraction() is read on that thread.
class ProgressReporter {
  public:
    ProgressReporter(const ProgressFn &progress, std::function<double()> fraction)
        : progress_(progress), fraction_(std::move(fraction)) {
        if (!progress_) return;
        thread_ = std::thread([this] {
            std::unique_lock<std::mutex> lock(mutex_);
            while (!cv_.wait_for(lock, std::chrono::milliseconds(250), [&] { return finished_; }))
                progress_(fraction_());
        });
    }
    // Stops the thread and reports 1.
    void Finish() {
        if (!Stop()) return;
        progress_(1.0);
    }
    ~ProgressReporter() { Stop(); }

  private:
    const ProgressFn &progress_;
    std::function<double()> fraction_;
    std::mutex mutex_;
    std::condition_variable cv_;
    bool finished_ = false;
    std::thread thread_;

    bool Stop() {
        if (!thread_.joinable()) return false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            finished_ = true;
        }
        cv_.notify_all();
        thread_.join();
        return true;
    }
};

// A whole-frame integrator's render (Integrator::RendersWholeFrame).
Image RenderWholeFrame(const RenderScene &scene, const RenderOptions &options, RenderStats *stats) {
    const auto start = std::chrono::steady_clock::now();
    const FrameContext frame(scene, options);
    Image img;
    {
        ProgressReporter reporter(options.progress, [&] { return frame.Progress(); });
        img = scene.integrator->RenderFrame(frame);
        reporter.Finish();
    }
    if (stats) {
        stats->renderSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->spp = frame.SamplesPerPixel();
        stats->rays = frame.Rays();
        stats->nonFiniteSamples = frame.NonFinitePixels();
        stats->firstNonFinitePixel = frame.FirstNonFinitePixel();
        stats->cancelled = frame.Cancelled();
        stats->kernelMask = 0;
    }
    return img;
}

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

TileDriver::TileDriver(const RenderScene &scene, const SamplerSettings &sampler,
                       const TraceSettings &trace, AovFrame *aovs)
    : scene_(scene),
      sampler_(sampler),
      trace_(trace),
      camera_(scene, sampler_),
      context_{scene, sampler_, trace_, camera_, scene.integrator->KernelMask(scene, trace_)},
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
        // The integrator reads the flag before every camera packet or pixel, so that a tile
        // of expensive pixels stops within one packet; a tile it stopped is dropped.
        TileContext ctx = context_;
        ctx.cancel = cancel;
        scene_.integrator->RenderTile(ctx, buf, rc);
        if (*cancel) return false;
    }
    // The film's scale, and pbrt's clamps of bright samples (Film "maxsampleluminance",
    // pbrt-v4's "maxcomponentvalue", after the sensor's colour matrix as in pbrt-v4); the
    // direct part is scaled as its sample is.
    const float scale = scene_.filmScale, maxLum = scene_.maxSampleLuminance,
                maxComp = scene_.maxComponentValue;
    const std::optional<std::array<float, 9>> &color = scene_.filmColor;
    // Scale 1 without a clamp changes no sample (x * 1 is x): no pass over them.
    const size_t n = scale != 1 || maxLum < Infinity || maxComp < Infinity || color
                         ? size_t(tb.Area()) * buf.spp
                         : 0;
    for (size_t i = 0; i < n; ++i) {
        RGB L = buf.L[i] * scale;
        if (color) {
            L = ApplyColorMatrix(*color, L);
            if (buf.wantDirect) buf.direct[i] = ApplyColorMatrix(*color, buf.direct[i]);
        }
        float clamp = 1;
        if (maxLum < Infinity && L.IsFinite()) {
            const float lum = L.Luminance();
            if (lum > maxLum) {
                clamp = maxLum / lum;
                L *= clamp;
            }
        }
        if (maxComp < Infinity && L.IsFinite()) {
            const float m = std::max({L.r, L.g, L.b});
            if (m > maxComp) {
                clamp *= maxComp / m;
                L *= maxComp / m;
            }
        }
        buf.L[i] = L;
        if (buf.wantDirect) buf.direct[i] = buf.direct[i] * (scale * clamp);
    }
    // The camera's ray weights (a lens system's; pbrt-v3 weights the clamped sample), from
    // the same camera samples the integrator traced.
    if (camera_.HasRayWeights())
        for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
            for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
                const CameraSampler::Seeds seeds = camera_.PixelSeeds(x, y);
                for (uint32_t s = 0; s < buf.spp; ++s) {
                    const size_t i = buf.Index(x, y, s);
                    const float w = camera_.RayWeight(camera_.Sample(x, y, s, seeds));
                    buf.L[i] = buf.L[i] * w;
                    if (buf.wantDirect) buf.direct[i] = buf.direct[i] * w;
                }
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
    // Splats, with the film scale and clamp of a sample, divided by the samples per pixel.
    for (const SampleSplat &sp : buf.splats) {
        RGB L = sp.L * scale;
        if (maxLum < Infinity && L.IsFinite() && L.Luminance() > maxLum)
            L *= maxLum / L.Luminance();
        tile->AddSplat(sp.pixel, L / float(spp));
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
    if (scene.integrator->RendersWholeFrame()) return RenderWholeFrame(scene, options, stats);
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
    // Splats reach any pixel: their tiles merge in order.
    const bool inPlace = !scene.integrator->Traits().splats && film.EnableResolveInPlace();
    tbb::enumerable_thread_specific<FilmTile> ownTile;
    std::atomic<int> done{0};
    if (options.aovs) options.aovs->BeginPass(nTiles);
    const TileDriver driver(scene, options.sampler, options.trace.value_or(scene.trace),
                            options.aovs);

    ProgressReporter reporter(progress, [&] { return double(done.load()) / nTiles; });

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
    reporter.Finish();
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

namespace {
const RenderScene &TiledScene(const RenderScene &scene) {
    if (scene.integrator->RendersWholeFrame())
        throw SceneError(std::string("Integrator ") + Quote(scene.IntegratorName()) +
                         " renders the frame as a whole, which cannot be split into tiles "
                         "rendered apart (render it on one process)");
    return scene;
}
}  // namespace

FrameTiles::FrameTiles(const RenderScene &scene)
    : scene_(TiledScene(scene)),
      driver_(scene, scene.sampler, scene.trace, nullptr),
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

namespace prism {

struct FrameContext::Workers {
    tbb::enumerable_thread_specific<RayCounters> rays;
    std::atomic<double> progress{0};
};

FrameContext::FrameContext(const RenderScene &s, const RenderOptions &options)
    : scene(s),
      sampler(options.sampler),
      trace(options.trace.value_or(s.trace)),
      options_(options),
      workers_(std::make_unique<Workers>()) {
    const Bounds2i &pb = s.pixelBounds;
    nx_ = (pb.Width() + RenderTileSize - 1) / RenderTileSize;
    ny_ = (pb.Height() + RenderTileSize - 1) / RenderTileSize;
}

FrameContext::~FrameContext() = default;

Bounds2i FrameContext::TilePixels(int t) const {
    const Bounds2i &pb = scene.pixelBounds;
    Bounds2i tb;
    tb.pMin = {pb.pMin.x + (t % nx_) * RenderTileSize, pb.pMin.y + (t / nx_) * RenderTileSize};
    tb.pMax = {std::min(tb.pMin.x + RenderTileSize, pb.pMax.x),
               std::min(tb.pMin.y + RenderTileSize, pb.pMax.y)};
    return tb;
}

void FrameContext::ForEach(int begin, int end,
                           const std::function<void(int i, RayCounters &rays)> &body) const {
    Workers &w = *workers_;
    ForEachTile(
        begin, end, [&](int i) { body(i, w.rays.local()); }, options_.cancel);
}

void FrameContext::SetProgress(double fraction) const {
    workers_->progress.store(std::clamp(fraction, 0.0, 1.0), std::memory_order_relaxed);
}

double FrameContext::Progress() const { return workers_->progress.load(std::memory_order_relaxed); }

RayCounters FrameContext::Rays() const {
    RayCounters sum;
    for (const RayCounters &c : workers_->rays) sum += c;
    return sum;
}

Image FrameContext::MakeImage(const std::function<RGB(int x, int y)> &pixel) const {
    const Bounds2i &pb = scene.pixelBounds;
    Image img = Image::Uninitialized(pb.Width(), pb.Height(), 3);
    const float scale = scene.filmScale;
    // Rows in parallel; the non-finite pixels counted per row and summed in row order.
    std::vector<uint32_t> bad(size_t(pb.Height()), 0);
    std::vector<int> firstBadX(size_t(pb.Height()), -1);
    tbb::parallel_for(pb.pMin.y, pb.pMax.y, [&](int y) {
        const size_t row = size_t(y - pb.pMin.y);
        for (int x = pb.pMin.x; x < pb.pMax.x; ++x) {
            RGB L = pixel(x, y) * scale;
            if (scene.filmColor) L = ApplyColorMatrix(*scene.filmColor, L);
            if (!L.IsFinite()) {
                if (bad[row]++ == 0) firstBadX[row] = x;
                L = RGB(0);
            }
            for (int c = 0; c < 3; ++c) img.At(x - pb.pMin.x, y - pb.pMin.y, c) = L[c];
        }
    });
    nonFinite_ = 0;
    firstNonFinite_.reset();
    for (size_t row = 0; row < bad.size(); ++row) {
        if (bad[row] && !firstNonFinite_)
            firstNonFinite_ = Vec2i{firstBadX[row], pb.pMin.y + int(row)};
        nonFinite_ += bad[row];
    }
    return img;
}

void FrameContext::Intermediate(const Image &img) const {
    if (options_.intermediate) options_.intermediate(img);
}

}  // namespace prism
