#include "render/progressive.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace prism {

int NextPassSpp(int done, int maxSpp, double secondsLeft, double secondsPerSpp) {
    const int budget = maxSpp - done;
    if (budget <= 0) return 0;
    if (done == 0) return std::min(budget, 2);
    double fits = secondsPerSpp > 0 ? 0.9 * secondsLeft / secondsPerSpp : double(budget);
    int n = int(std::min({fits, double(std::max(done, 2)), double(budget)}));
    if (n >= 2 || (n == 1 && budget == 1)) return n;
    return 0;
}

Image RenderProgressive(const RenderScene &scene, const TimeLimit &limit, RenderStats *stats,
                        const ProgressFn &progress, const volatile int *cancel, AovFrame *aovs) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    RenderStats total;
    std::vector<double> sum;  // sum over passes of spp * pass image
    Image img;
    int done = 0;
    // Per pass: its samples and its noise variance (negative: the pass had no estimate).
    std::vector<std::pair<int, double>> noise;
    // The passes are stopped by this flag, raised by a watcher at the deadline or when the
    // caller's flag is: a pass cut off by the deadline is dropped (the earlier ones are the
    // image), so that no pass outlives the time limit by more than one camera packet.
    volatile int stop = 0;
    std::mutex mutex;
    std::condition_variable cv;
    bool finished = false;
    std::thread watcher([&] {
        std::unique_lock<std::mutex> lock(mutex);
        while (!cv.wait_for(lock, std::chrono::milliseconds(10), [&] { return finished; }))
            if ((cancel && *cancel) || elapsed() >= limit.seconds) stop = 1;
    });
    // A whole-frame integrator (sppm) is one render stopped at the deadline: its own passes
    // (iterations) done by then make the image.
    const bool wholeFrame = scene.integrator->RendersWholeFrame();
    if (wholeFrame) {
        RenderOptions options;
        options.sampler = scene.sampler;
        options.cancel = &stop;
        options.progress = progress;
        img = Render(scene, options, &total);
        const bool userCancel = cancel && *cancel;
        total.cancelled = userCancel || total.spp == 0;
        total.timedOut = !userCancel && total.spp == 0;
        if (!total.cancelled) total.passSpp.push_back(total.spp);
    }
    for (uint32_t pass = 0; !wholeFrame; ++pass) {
        const int spp = NextPassSpp(done, limit.maxSpp, limit.seconds - elapsed(),
                                    done > 0 ? total.renderSeconds / double(done) : 0.0);
        if (spp == 0) break;
        RenderOptions options;
        options.sampler = scene.sampler;
        options.sampler.spp = spp;
        // Pass 0 keeps the scene's seed: a budget of one pass renders what a plain render
        // would. Halton's and Sobol's passes continue their sequence instead, so together they are
        // the points of one render of their total count.
        if (scene.sampler.pattern == SamplePattern::Halton)
            options.sampler.halton.firstSample = uint64_t(done);
        else if (scene.sampler.pattern == SamplePattern::Sobol)
            options.sampler.sobol.firstSample = uint64_t(done);
        else
            options.sampler.seed = scene.sampler.seed + pass * 0x9E3779B9u;
        // The AOVs take a pass's tiles as they finish (the variance merges them at once), so a
        // pass cut short would leave part of itself in them: with AOVs only the first pass
        // (no image without it) is cut at the deadline; later ones are sized to fit and finish.
        options.cancel = aovs && done > 0 ? cancel : &stop;
        options.aovs = aovs;
        if (progress) {
            options.progress = [&, spp](double f) {
                double bySamples = (double(done) + f * spp) / double(limit.maxSpp);
                double byTime = limit.seconds > 0 ? elapsed() / limit.seconds : 1.0;
                progress(std::min(0.99, std::max(bySamples, byTime)));
            };
        }
        RenderStats ps;
        Image pi = Render(scene, options, &ps);
        total.rays += ps.rays;
        total.renderSeconds += ps.renderSeconds;
        total.nonFiniteSamples += ps.nonFiniteSamples;
        if (ps.firstNonFinitePixel &&
            (!total.firstNonFinitePixel ||
             std::pair(ps.firstNonFinitePixel->y, ps.firstNonFinitePixel->x) <
                 std::pair(total.firstNonFinitePixel->y, total.firstNonFinitePixel->x)))
            total.firstNonFinitePixel = ps.firstNonFinitePixel;
        total.kernelMask = ps.kernelMask;
        if (ps.cancelled) {
            // The caller's cancel, or the deadline before any pass finished: no image.
            if ((cancel && *cancel) || done == 0) {
                total.cancelled = true;
                total.timedOut = !(cancel && *cancel);
            }
            break;
        }
        if (sum.empty()) {
            sum.assign(pi.pixels.size(), 0.0);
            img = pi;
        }
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += double(spp) * double(pi.pixels[i]);
        noise.emplace_back(spp, ps.noisePixels > 0 ? ps.noiseVariance : -1.0);
        total.noisePixels = std::max(total.noisePixels, ps.noisePixels);
        total.passSpp.push_back(spp);
        done += spp;
    }
    {
        std::lock_guard<std::mutex> lock(mutex);
        finished = true;
    }
    cv.notify_all();
    watcher.join();
    if (wholeFrame) {
        if (stats) *stats = total;
        return img;
    }
    if (done > 0)
        for (size_t i = 0; i < sum.size(); ++i) img.pixels[i] = float(sum[i] / double(done));
    // The average of independent passes: variance sum over passes of (spp_k / N)^2 var_k. A
    // pass without an estimate of its own (1 spp) takes the per-sample variance the other
    // passes show (var_k spp_k, weighted by spp_k), divided by its spp.
    double perSample = 0, weight = 0;
    for (auto [n, v] : noise)
        if (v >= 0) perSample += v * n * n, weight += n;
    if (weight > 0) perSample /= weight;
    double var = 0;
    for (auto [n, v] : noise) {
        double vk = v >= 0 ? v : perSample / n;
        var += (double(n) / done) * (double(n) / done) * vk;
    }
    total.noiseVariance = weight > 0 ? var : 0;
    if (weight == 0) total.noisePixels = 0;
    total.spp = done;
    if (progress && !total.cancelled) progress(1.0);
    if (stats) *stats = total;
    return img;
}

}  // namespace prism
