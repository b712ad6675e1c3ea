#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>
#include <pmmintrin.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "render/sampler.h"

namespace prism {

namespace {
constexpr int TileSize = RenderTileSize;

enum SamplePurpose : uint32_t { FilmPurpose = 0, LensPurpose = 1 };
}  // namespace

Image Render(const RenderScene &scene, RenderStats *stats, const ProgressFn &progress,
             const volatile int *cancel) {
    auto start = std::chrono::steady_clock::now();
    Film film(scene.resolution, scene.pixelBounds, scene.filter);
    const Bounds2i &pb = scene.pixelBounds;
    int nx = (pb.pMax.x - pb.pMin.x + TileSize - 1) / TileSize;
    int ny = (pb.pMax.y - pb.pMin.y + TileSize - 1) / TileSize;
    int nTiles = nx * ny;
    std::vector<std::optional<FilmTile>> tiles(static_cast<size_t>(nTiles));
    tbb::enumerable_thread_specific<RayCounters> counters;
    std::atomic<int> done{0};
    WhittedIntegrator integrator(scene);

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
        for (int t = r.begin(); t != r.end(); ++t) {
            if (cancel && *cancel) return;
            int tx = t % nx, ty = t / nx;
            Bounds2i tb;
            tb.pMin = {pb.pMin.x + tx * TileSize, pb.pMin.y + ty * TileSize};
            tb.pMax = {std::min(tb.pMin.x + TileSize, pb.pMax.x), std::min(tb.pMin.y + TileSize, pb.pMax.y)};
            FilmTile tile = film.MakeTile(tb);
            const uint32_t spp = uint32_t(scene.spp);
            for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
                for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
                    uint32_t filmSeed = PatternSeed(x, y, FilmPurpose);
                    uint32_t lensSeed = PatternSeed(x, y, LensPurpose);
                    for (uint32_t s = 0; s < spp; ++s) {
                        // One sample: the pixel centre; more: correlated multi-jittered.
                        Vec2f u = spp == 1 ? Vec2f(0.5f, 0.5f) : CMJSample(s, spp, filmSeed);
                        Vec2f pFilm(float(x) + u.x, float(y) + u.y);
                        Vec2f uLens = scene.features.lens ? CMJSample(s, spp, lensSeed) : Vec2f(0.5f, 0.5f);
                        Ray ray = scene.camera->GenerateRay(pFilm, uLens);
                        rc.camera++;
                        SampleContext sc{x, y, s, spp};
                        RGB L = integrator.Li(ray, 0, rc, sc) * scene.filmScale;
                        if (scene.maxSampleLuminance < Infinity && L.IsFinite()) {
                            float lum = L.Luminance();
                            if (lum > scene.maxSampleLuminance) L *= scene.maxSampleLuminance / lum;
                        }
                        tile.AddSample(pFilm, L);
                    }
                }
            }
            tiles[size_t(t)] = std::move(tile);
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
    bool cancelled = false;
    for (auto &tile : tiles) {
        if (tile) film.MergeTile(*tile);
        else cancelled = true;
    }
    Image img = film.ToImage();
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
