#include "tools/study/target_error.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "render/renderer.h"
#include "render/sampler.h"
#include "tools/study/study.h"

namespace prism {

namespace {

// The reference's trace depth, as the study's (the scene's own when it is deeper).
constexpr int ReferenceMaxDepth = 16;
// The spp at which the pilot measures the depth bias at its resolutions.
constexpr int ProbeSpp = 9;

double Seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Vec2i FullResolution(const SceneDescription &desc, const BuildSettings &base) {
    if (base.resolution.x > 0) return base.resolution;
    return {desc.film.params.GetInt("xresolution", PbrtDefaultXResolution),
            desc.film.params.GetInt("yresolution", PbrtDefaultYResolution)};
}

// A scene built at `res` with `lightSamples` (0: the lights' own), no cutoff; its own budget
// of the render's limit (the pilot scenes are small and live one or two at a time).
RenderScene BuildAt(const SceneDescription &desc, const BuildSettings &base, Vec2i res,
                    int lightSamples, MemoryBudget &budget) {
    BuildSettings s = base;
    s.resolution = res;
    s.spp = 0;
    s.rayCutoff = 0;
    s.lightSamples = lightSamples;
    s.budget = &budget;
    Diagnostics quiet(false);
    return BuildRenderScene(desc, s, quiet);
}

// A render of the scene as built, at `spp` (0: the scene's) and with `cutoff`; the scene is
// not changed.
Image RenderAt(const RenderScene &scene, int spp, float cutoff = 0, RenderStats *stats = nullptr) {
    RenderOptions o;
    o.sampler = scene.sampler;
    if (spp > 0) o.sampler.spp = spp;
    o.trace = scene.trace;
    o.trace->rayCutoff = cutoff;
    return Render(scene, o, stats);
}

// The reference: `spp` samples, the reference's depth, no cutoff.
Image RenderReference(const RenderScene &scene, int spp, double *seconds = nullptr) {
    RenderOptions o;
    o.sampler = scene.sampler;
    o.sampler.spp = spp;
    o.trace = TraceSettings{std::max(ReferenceMaxDepth, scene.trace.maxDepth), 0.0f};
    RenderStats stats;
    Image ref = Render(scene, o, &stats);
    if (seconds) *seconds = stats.renderSeconds;
    return ref;
}

// One pilot series: squared relRmse and render seconds at each spp.
struct Series {
    std::vector<double> err2, seconds;
};

Series RenderSeries(const RenderScene &scene, const std::vector<int> &spps, const Image &ref) {
    Series s;
    for (int n : spps) {
        RenderStats stats;
        Image img = RenderAt(scene, n, 0, &stats);
        double e = RelativeRmse(img, ref);
        s.err2.push_back(e * e);
        s.seconds.push_back(stats.renderSeconds);
    }
    return s;
}

// Least-squares slope of seconds against spp: the render time per sample per pixel.
double SecondsPerSpp(const std::vector<int> &spps, const std::vector<double> &seconds) {
    double n = double(spps.size()), sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < spps.size(); ++i) {
        sx += spps[i];
        sy += seconds[i];
        sxx += double(spps[i]) * spps[i];
        sxy += spps[i] * seconds[i];
    }
    double d = n * sxx - sx * sx;
    double slope = d > 0 ? (n * sxy - sx * sy) / d : 0;
    // Timer noise on a tiny pilot can flatten the slope: never below the mean cost per spp of
    // the largest point's render over twice its spp.
    double floor = seconds.empty() ? 0 : seconds.back() / (2.0 * spps.back());
    return std::max(slope, floor);
}

}  // namespace

double PowerLaw::operator()(double x) const { return a * std::pow(x, -b); }

PowerLaw FitPowerLaw(const std::vector<double> &x, const std::vector<double> &y) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (!(y[i] > 0) || !(x[i] > 0)) continue;
        double lx = std::log(x[i]), ly = std::log(y[i]);
        n += 1;
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    double d = n * sxx - sx * sx;
    if (n < 2 || !(d > 1e-12)) throw std::invalid_argument("FitPowerLaw: needs two distinct x");
    double slope = (n * sxy - sx * sy) / d;
    double intercept = (sy - slope * sx) / n;
    return {std::exp(intercept), -slope};
}

bool IsWellStratifiedSampleCount(int n) {
    if (n < 1) return false;
    if (n <= 8) return true;
    CMJGrid grid{uint32_t(n)};
    return grid.m <= 2 * grid.n;
}

int NextWellStratifiedSampleCount(int n) {
    n = std::max(n, 1);
    while (!IsWellStratifiedSampleCount(n)) ++n;
    return n;
}

double ErrorCurve::Error(double spp) const {
    double noise = this->noise(spp);
    return std::sqrt(floor2 + noise * noise);
}

std::optional<int> ErrorCurve::SppFor(double target) const {
    double t2 = target * target;
    if (!(t2 > floor2)) return std::nullopt;
    if (!(noise.a > 0)) return 1;
    if (!(noise.b > 0))
        return noise.a * noise.a <= t2 - floor2 ? std::optional<int>(1) : std::nullopt;
    // floor2 + a^2 n^-2b <= t2  <=>  n >= (a^2 / (t2 - floor2))^(1 / 2b)
    double n = std::pow(noise.a * noise.a / (t2 - floor2), 1 / (2 * noise.b));
    if (!(n <= double(MaxSamplesPerPixel))) return std::nullopt;
    int spp = NextWellStratifiedSampleCount(std::max(1, int(std::ceil(n - 1e-9))));
    // Rounding: make sure the count reaches the target.
    while (spp < MaxSamplesPerPixel && Error(spp) > target)
        spp = NextWellStratifiedSampleCount(spp + 1);
    return spp;
}

ErrorCurve FitErrorCurve(const std::vector<int> &spp, const std::vector<double> &err2) {
    if (spp.size() != err2.size() || spp.size() < 2)
        throw std::invalid_argument("FitErrorCurve: needs two points or more");
    double minErr2 = Infinity;
    for (double e : err2) minErr2 = std::min(minErr2, e);
    std::vector<double> x(spp.begin(), spp.end());
    ErrorCurve best;
    double bestCost = Infinity, bestT = 0;
    // The floor as minErr2 * (1 - 1e-4^t), t in [0, 1]: from 0 to just under the smallest
    // error, finer near the top (where the curve flattens). Each is judged by the misfit of
    // log(err2); a coarse search over t, then a fine one around the best.
    auto tryFloor = [&](double t) {
        double f = t <= 0 ? 0 : minErr2 * (1 - std::pow(1e-4, t));
        std::vector<double> y;
        for (double e : err2) y.push_back(std::sqrt(std::max(e - f, 0.0)));
        PowerLaw p;
        try {
            p = FitPowerLaw(x, y);
        } catch (const std::invalid_argument &) {
            return;
        }
        if (!(p.b >= 0)) return;  // error growing with spp: not a noise curve
        ErrorCurve c{f, p};
        double cost = 0;
        for (size_t k = 0; k < x.size(); ++k) {
            double m = c.Error(x[k]), e = std::sqrt(std::max(err2[k], 1e-300));
            double r = std::log(std::max(m, 1e-300) / e);
            cost += r * r;
        }
        if (cost < bestCost) {
            bestCost = cost;
            best = c;
            bestT = t;
        }
    };
    const int steps = 200;
    for (int i = 0; i <= steps; ++i) tryFloor(double(i) / steps);
    const double t0 = bestT;
    for (int i = -steps; i <= steps; ++i)
        tryFloor(std::clamp(t0 + double(i) / (steps * steps), 0.0, 1.0));
    if (!(bestCost < Infinity)) {
        // No decreasing power law fits: the errors are a floor.
        best.floor2 = minErr2;
        best.noise = {0, 0};
    }
    return best;
}

double RelativeRmse(const Image &image, const Image &reference) {
    return MeasureError(image, reference, 0).relRmse;
}

Vec2i PilotResolution(Vec2i full) {
    int w = std::min(full.x, std::max(64, (full.x + 1) / 2));
    int h = std::max(1, int(std::lround(double(full.y) * w / std::max(1, full.x))));
    return {w, h};
}

TargetChoice ChooseTargetSettings(const SceneDescription &desc, const BuildSettings &base,
                                  const TargetOptions &o, Diagnostics &diag) {
    (void)diag;
    if (!(o.target > 0) || !std::isfinite(o.target))
        throw std::invalid_argument("target error must be positive");
    if (o.cutoffs.empty() || o.cutoffs[0] != 0 || o.pilotSpp.size() < 3)
        throw std::invalid_argument("target error: cutoffs must start with 0, three spp or more");
    auto t0 = std::chrono::steady_clock::now();
    TargetChoice choice;
    choice.target = o.target;
    choice.resolution = FullResolution(desc, base);
    const Vec2i pilot = PilotResolution(choice.resolution);
    choice.pilotResolution = pilot;
    // The second, coarser pilot that separates edge error from the rest (docs/ACCURACY.md).
    const Vec2i half{
        std::max(8, pilot.x / 2),
        std::max(1, int(std::lround(double(pilot.y) * std::max(8, pilot.x / 2) / pilot.x)))};
    const uint64_t limit = base.budget ? base.budget->Limit() : 0;

    // Light samples are a choice only with area or infinite lights.
    std::vector<int> lightChoices{0};
    {
        MemoryBudget b(limit);
        RenderScene probe = BuildAt(desc, base, half, 0, b);
        if (probe.features.areaLights || probe.features.environment) lightChoices = o.lightSamples;
        if (std::find(lightChoices.begin(), lightChoices.end(), 0) == lightChoices.end())
            lightChoices.insert(lightChoices.begin(), 0);
    }

    // The scene's own light samples: the spp series at the pilot and the half pilot, each
    // against its reference; the reference's own noise (the fitted noise at its spp) is taken
    // out of every error. The cutoffs are probed on the pilot at one spp.
    Series own[2];
    double refNoise2[2] = {0, 0};   // pilot, half
    double depthBias2[2] = {0, 0};  // the scene's maxdepth against the reference's
    Image pilotRef;
    for (int r = 0; r < 2; ++r) {
        MemoryBudget b(limit);
        const RenderScene scene = BuildAt(desc, base, r == 0 ? pilot : half, 0, b);
        Image ref = RenderReference(scene, o.pilotRefSpp);
        own[r] = RenderSeries(scene, o.pilotSpp, ref);
        ErrorCurve c = FitErrorCurve(o.pilotSpp, own[r].err2);
        double n = c.noise(o.pilotRefSpp);
        refNoise2[r] = n * n;
        // The depth bias at this resolution: the same samples at the reference's depth.
        Image shallow = RenderAt(scene, ProbeSpp);
        double d = RelativeRmse(shallow, RenderReference(scene, ProbeSpp));
        depthBias2[r] = d * d;
        if (r == 0) pilotRef = std::move(ref);
    }

    // Biases, measured at the full resolution: they sit on small features (deep
    // inter-reflections) and grow with the resolution until it resolves them (quadrics at
    // 9 spp: depth bias 0.0021, 0.0046, 0.0068 at widths 50, 100, 400), so no pilot resolution
    // shows them. Each is measured against the same samples without it, so the noise cancels:
    // each cutoff against none (cutoffs[0] is 0) at one sample per pixel (the pixel centre: an
    // upper bound), with the rays it leaves; the depth bias against the reference's depth.
    double fullDepthBias2 = 0;
    std::vector<double> cutoffErr2(o.cutoffs.size()), cutoffRays(o.cutoffs.size());
    {
        MemoryBudget b(limit);
        const RenderScene scene = BuildAt(desc, base, choice.resolution, 0, b);
        Image noCutoff;
        for (size_t c = 0; c < o.cutoffs.size(); ++c) {
            RenderStats st;
            Image img = RenderAt(scene, 1, o.cutoffs[c], &st);
            if (c == 0) noCutoff = img;
            double e = RelativeRmse(img, noCutoff);
            cutoffErr2[c] = e * e;
            cutoffRays[c] = double(st.rays.Total());
        }
        // The depth bias of a pixel's mean falls with the samples towards the bias of the
        // pixel's integral, as b^2(n) = B^2 + v / n (v: the deep paths' own sampling noise):
        // measured at 2 and 4 spp, B^2 = 2 b^2(4) - b^2(2) (at least b^2(4) / 2).
        double b2[2];
        for (int i = 0; i < 2; ++i) {
            double d = RelativeRmse(RenderAt(scene, 2 << i), RenderReference(scene, 2 << i));
            b2[i] = d * d;
        }
        fullDepthBias2 = std::max(2 * b2[1] - b2[0], 0.5 * b2[1]);
    }
    choice.depthBias = std::sqrt(fullDepthBias2);

    // From the pilot and the half pilot to the full resolution, per spp: the true squared
    // error is E * (pilot width / width) + S, E the part on edges (their share of the pixels
    // goes as 1 / width), S the rest (per-pixel shading and light noise, bias).
    const double kHalf = double(pilot.x) / half.x, kFull = double(pilot.x) / choice.resolution.x;
    const double pixelRatio =
        double(choice.resolution.x) * choice.resolution.y / (double(pilot.x) * pilot.y);
    std::vector<double> ownFull2;
    for (size_t k = 0; k < o.pilotSpp.size(); ++k) {
        double tp = std::max(own[0].err2[k] - refNoise2[0] - depthBias2[0], 0.0);
        double th = std::max(own[1].err2[k] - refNoise2[1] - depthBias2[1], 0.0);
        double E = kHalf > 1 ? std::max(0.0, (th - tp) / (kHalf - 1)) : 0;
        double full2 = 0;
        if (E <= tp) {
            full2 = E * kFull + (tp - E);
        } else {
            // Falling faster than edges (th > kHalf tp): smooth shading varies inside a pixel
            // by its size, so its share falls as 1 / width^2. Carried on as the measured power
            // of the width (at most 2).
            E = tp;
            double g = std::min(2.0, std::log(th / tp) / std::log(kHalf));
            full2 = tp * std::pow(kFull, g);
        }
        ownFull2.push_back(std::max(full2, 1e-30));
        if (o.pilotSpp[k] == 9 && tp > 0) {
            choice.edgeShare = E / tp;
            choice.resolutionFactor = std::sqrt(ownFull2.back() / tp);
        }
    }
    const double ownPerSpp = SecondsPerSpp(o.pilotSpp, own[0].seconds) * pixelRatio;

    // Other light samples: a short series on the pilot. Light noise is per-pixel noise, so the
    // change it makes to the squared error carries over to the full resolution as it is; it
    // falls with spp like the light noise it is, a power law fitted over the short series.
    for (int L : lightChoices) {
        std::vector<double> full2 = ownFull2;
        double perSpp = ownPerSpp;
        if (L != 0) {
            MemoryBudget b(limit);
            const RenderScene scene = BuildAt(desc, base, pilot, L, b);
            Series s = RenderSeries(scene, o.lightSpp, pilotRef);
            std::vector<double> x, diff;
            double sum = 0;
            for (size_t k = 0; k < o.lightSpp.size(); ++k) {
                // The scene's own error at the same spp (the series share their points).
                auto at = std::find(o.pilotSpp.begin(), o.pilotSpp.end(), o.lightSpp[k]);
                if (at == o.pilotSpp.end()) continue;
                double d = s.err2[k] - own[0].err2[size_t(at - o.pilotSpp.begin())];
                x.push_back(o.lightSpp[k]);
                diff.push_back(d);
                sum += d;
            }
            double sign = sum < 0 ? -1 : 1;
            for (double &d : diff) d *= sign;
            PowerLaw fit{0, 0};
            try {
                fit = FitPowerLaw(x, diff);
            } catch (const std::invalid_argument &) {
            }
            for (size_t k = 0; k < o.pilotSpp.size(); ++k)
                full2[k] = std::max(full2[k] + sign * fit(o.pilotSpp[k]), 1e-30);
            perSpp = SecondsPerSpp(o.lightSpp, s.seconds) * pixelRatio;
        }
        ErrorCurve curve = FitErrorCurve(o.pilotSpp, full2);
        for (size_t c = 0; c < o.cutoffs.size(); ++c) {
            TargetCandidate cand;
            cand.lightSamples = L;
            cand.cutoff = o.cutoffs[c];
            cand.curve = curve;
            // The depth bias and a cutoff's bias add to the floor (measured at the scene's
            // light samples; the cutoff never drops shadow rays); the time goes with the rays
            // the cutoff leaves.
            cand.curve.floor2 += fullDepthBias2 + cutoffErr2[c];
            double rayRatio = cutoffRays[0] > 0 ? cutoffRays[c] / cutoffRays[0] : 1;
            cand.secondsPerSpp = perSpp * std::min(1.0, rayRatio);
            cand.spp = cand.curve.SppFor(o.target);
            if (cand.spp) {
                cand.predictedError = cand.curve.Error(*cand.spp);
                cand.predictedSeconds = *cand.spp * cand.secondsPerSpp;
            }
            choice.candidates.push_back(cand);
        }
    }
    choice.pilotSeconds = Seconds(t0);

    // The cheapest; a candidate must be more than 2% faster to displace an earlier one (the
    // list starts with the scene's light samples and no cutoff).
    const TargetCandidate *best = nullptr;
    for (const TargetCandidate &c : choice.candidates)
        if (c.spp && (!best || c.predictedSeconds < 0.98 * best->predictedSeconds)) best = &c;
    if (!best) {
        double floor = Infinity;
        for (const TargetCandidate &c : choice.candidates)
            floor = std::min(floor, std::sqrt(c.curve.floor2));
        throw SceneError(fmt::format(
            "--target-error {:g} cannot be reached: the pilot predicts an error floor of {:.3g} "
            "that no spp removes (the scene's maxdepth against the reference's {}, or bias), "
            "or more than {} spp; ask for a larger error",
            o.target, floor, ReferenceMaxDepth, MaxSamplesPerPixel));
    }
    choice.spp = *best->spp;
    choice.cutoff = best->cutoff;
    choice.lightSamples = best->lightSamples;
    choice.predictedError = best->predictedError;
    choice.predictedSeconds = best->predictedSeconds;
    return choice;
}

BuildSettings ApplyTargetChoice(BuildSettings base, const TargetChoice &choice) {
    base.spp = choice.spp;
    base.rayCutoff = choice.cutoff;
    base.lightSamples = choice.lightSamples;
    return base;
}

TargetVerification VerifyTarget(const SceneDescription &desc, const BuildSettings &base,
                                const TargetChoice &choice, const Image &image, Diagnostics &diag) {
    (void)diag;
    TargetVerification v;
    // Well above the render's spp, so that the two sample patterns are far apart and the
    // reference's own error small against the target.
    v.refSpp = NextWellStratifiedSampleCount(std::clamp(4 * choice.spp, 128, 1024));
    MemoryBudget b(base.budget ? base.budget->Limit() : 0);
    const RenderScene scene = BuildAt(desc, base, choice.resolution, 0, b);
    Image ref = RenderReference(scene, v.refSpp, &v.refSeconds);
    v.measured = RelativeRmse(image, ref);
    // The reference's noise: the noise part of the predicted curve for the scene's light
    // samples (the first candidate), at the reference's spp.
    if (!choice.candidates.empty()) v.refError = choice.candidates.front().curve.noise(v.refSpp);
    v.reached = std::sqrt(std::max(0.0, v.measured * v.measured - v.refError * v.refError));
    return v;
}

std::string DescribeChoice(const TargetChoice &c) {
    std::string lights = c.lightSamples > 0 ? std::to_string(c.lightSamples) : "the scene's";
    return fmt::format(
               "target-error: chose spp {}, cutoff {:g}, light samples {}; predicted rel. RMSE "
               "{:.4g} "
               "(pilot {:.1f} s at {}x{}; predicted render {:.2f} s)",
               c.spp, double(c.cutoff), lights, c.predictedError, c.pilotSeconds,
               c.pilotResolution.x, c.pilotResolution.y, c.predictedSeconds) +
           fmt::format(
               "\ntarget-error: resolution correction: {:.0f}% of the pilot's squared "
               "error at 9 spp is edge-like (falls as 1/width), so {}x{} has {:.2f}x the "
               "pilot's noise; bias of the scene's maxdepth {:.2g}",
               100 * c.edgeShare, c.resolution.x, c.resolution.y, c.resolutionFactor, c.depthBias);
}

std::string DescribeVerification(const TargetChoice &c, const TargetVerification &v) {
    double off = c.target > 0 ? (v.reached - c.target) / c.target : 0;
    return fmt::format(
        "target-error: reached rel. RMSE {:.4g} (target {:g}, {} {:.0f}%; predicted {:.4g}; "
        "measured {:.4g} against a {}-spp reference whose own error is estimated at {:.2g})",
        v.reached, c.target, std::abs(off) <= 0.25 ? "within" : "off by", std::abs(off) * 100,
        c.predictedError, v.measured, v.refSpp, v.refError);
}

}  // namespace prism
