#include "render/renderer.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "render/distribution_integrator.h"
#include "render/sampler.h"

namespace prism {

namespace {
// TimePurpose: a pattern of its own, so the time dimension shifts no other.
enum SamplePurpose : uint32_t { FilmPurpose = 0, LensPurpose = 1, TimePurpose = 0x74696d65 };
}  // namespace

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

// Per-thread buffers for one tile's samples, reused from tile to tile.
struct TileScratch {
    std::vector<Vec2f> pFilm;
    std::vector<RGB> L;
};

// Camera rays are traced in packets of up to PacketW x PacketH pixels at one sample index
// (coherent rays through Embree's 16-wide packet path), then shaded one by one from their
// hits. Samples are added to the tile afterwards in pixel-then-sample order, so the film sums
// exactly as when each sample was traced and added in turn.
constexpr int PacketW = RenderPacketW, PacketH = RenderPacketH;

template <class Integrator>
void RenderTile(const RenderScene &scene, Bounds2i tb, RayCounters &rc, TileScratch &buf,
                FilmTile *tile) {
    const Integrator integrator(scene);
    const uint32_t spp = uint32_t(scene.spp);
    const int w = tb.pMax.x - tb.pMin.x, h = tb.pMax.y - tb.pMin.y;
    const size_t n = size_t(w) * size_t(h) * spp;
    if (buf.L.size() < n) {
        buf.L.resize(n);
        buf.pFilm.resize(n);
    }
    auto index = [&](int x, int y, uint32_t s) {
        return (size_t(y - tb.pMin.y) * size_t(w) + size_t(x - tb.pMin.x)) * spp + s;
    };
    Ray rays[16];
    RawHit hits[16];
    size_t slot[16];
    uint32_t filmSeed[16], lensSeed[16], timeSeed[16];
    // Motion blur: each camera ray's time (a fraction of the shutter) is stratified over the
    // pixel's samples; scenes where nothing moves keep time 0 and draw nothing.
    const bool motion = scene.features.effects.Has(Effect::MotionBlur);
    const CMJPattern cmj(spp);
    for (int by = tb.pMin.y; by < tb.pMax.y; by += PacketH) {
        for (int bx = tb.pMin.x; bx < tb.pMax.x; bx += PacketW) {
            const int ex = std::min(bx + PacketW, tb.pMax.x),
                      ey = std::min(by + PacketH, tb.pMax.y);
            // The packet's pattern seeds, once for all its samples.
            if (spp > 1 || scene.features.lens || motion) {
                int m = 0;
                for (int y = by; y < ey; ++y)
                    for (int x = bx; x < ex; ++x, ++m) {
                        filmSeed[m] = PatternSeed(x, y, FilmPurpose);
                        lensSeed[m] = scene.features.lens ? PatternSeed(x, y, LensPurpose) : 0;
                        timeSeed[m] = motion ? PatternSeed(x, y, TimePurpose) : 0;
                    }
            }
            for (uint32_t s = 0; s < spp; ++s) {
                int m = 0;
                for (int y = by; y < ey; ++y) {
                    for (int x = bx; x < ex; ++x, ++m) {
                        // One sample: the pixel centre; more: correlated multi-jittered.
                        Vec2f u = spp == 1 ? Vec2f(0.5f, 0.5f) : cmj.Sample(s, filmSeed[m]);
                        Vec2f pFilm(float(x) + u.x, float(y) + u.y);
                        Vec2f uLens =
                            scene.features.lens ? cmj.Sample(s, lensSeed[m]) : Vec2f(0.5f, 0.5f);
                        float time = motion ? cmj.Sample(s, timeSeed[m]).x : 0.f;
                        rays[m] = scene.camera->GenerateRay(pFilm, uLens, time);
                        slot[m] = index(x, y, s);
                        buf.pFilm[slot[m]] = pFilm;
                    }
                }
                scene.accel->IntersectPacket(rays, m, hits);
                scene.accel->PrefetchHits(hits, m);
                rc.camera += uint64_t(m);
                for (int i = 0; i < m; ++i) {
                    SampleContext sc{bx + i % (ex - bx), by + i / (ex - bx), s, spp};
                    RGB L = integrator.LiCamera(rays[i], hits[i], rc, sc) * scene.filmScale;
                    if (scene.maxSampleLuminance < Infinity && L.IsFinite()) {
                        float lum = L.Luminance();
                        if (lum > scene.maxSampleLuminance) L *= scene.maxSampleLuminance / lum;
                    }
                    buf.L[slot[i]] = L;
                }
            }
        }
    }
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
        for (int x = tb.pMin.x; x < tb.pMax.x; ++x)
            for (uint32_t s = 0; s < spp; ++s) {
                size_t i = index(x, y, s);
                tile->AddSample(buf.pFilm[i], buf.L[i]);
            }
}

}  // namespace

Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress,
             const volatile int *cancel) {
    auto start = std::chrono::steady_clock::now();
    TiledFilm film(scene.resolution, scene.pixelBounds, scene.filter, RenderTileSize);
    int nTiles = film.NumTiles();
    TileMerger merger(film);
    std::atomic<int> nextTile{0};
    tbb::enumerable_thread_specific<RayCounters> counters;
    tbb::enumerable_thread_specific<TileScratch> scratch;
    std::atomic<int> done{0};
    // The integrator is chosen here, once per render: each tile runs its own instantiation.
    auto *const renderTile = scene.integrator == IntegratorKind::Distribution
                                 ? &RenderTile<DistributionIntegrator>
                                 : &RenderTile<WhittedIntegrator>;

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
            FilmTile *tile = merger.Acquire();
            film.ResetTile(t, tile);
            renderTile(scene, tb, rc, scratch.local(), tile);
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
    bool cancelled = !merger.Flush();
    Image img = film.Finish();
    if (stats) {
        stats->renderSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = RayCounters{};
        for (const RayCounters &c : counters) stats->rays += c;
        stats->nonFiniteSamples = film.NonFiniteCount();
        stats->firstNonFinitePixel = film.FirstNonFinitePixel();
        stats->cancelled = cancelled;
    }
    return img;
}

}  // namespace prism
