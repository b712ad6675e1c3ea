#include "tools/study/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/memory.h"
#include "render/renderer.h"
#include "tools/validate/tessellate.h"

namespace prism {

namespace {

struct KnobEntry {
    StudyKnob knob;
    const char *name;
};
constexpr KnobEntry Knobs[] = {
    {StudyKnob::Spp, "spp"},
    {StudyKnob::MaxDepth, "maxdepth"},
    {StudyKnob::Cutoff, "cutoff"},
    {StudyKnob::Precision, "precision"},
    {StudyKnob::Offset, "offset"},
    {StudyKnob::Tessellate, "tessellate"},
    {StudyKnob::Robust, "robust"},
    {StudyKnob::BvhQuality, "bvh-quality"},
    {StudyKnob::LightSamples, "light-samples"},
    {StudyKnob::LightSampler, "light-sampler"},
};

// The reference's trace depth (the "depth 16"; the scene's own when it is deeper).
constexpr int ReferenceMaxDepth = 16;

double Median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

StudySetting Setting(StudyKnob knob, std::string value, std::function<void(BuildSettings &)> f) {
    return StudySetting{knob, std::move(value), std::move(f)};
}

// The render-time fields of the settings as a render of the built base scene runs them
// (KnobReusesScene): the scene stays as built. Every knob KnobReusesScene names must be read
// here.
RenderOptions RenderTimeOptions(const BuildSettings &s, const RenderScene &scene) {
    RenderOptions o;
    o.sampler = scene.sampler;
    if (s.spp > 0) o.sampler.spp = s.spp;
    TraceSettings trace = scene.trace;
    if (s.maxDepth >= 0) trace.maxDepth = s.maxDepth;
    trace.rayCutoff = s.rayCutoff;
    o.trace = trace;
    return o;
}

struct Run {
    Image image;
    RenderStats stats;
};

Run RenderOnce(const RenderScene &scene, const RenderOptions &options) {
    Run r;
    r.image = Render(scene, options, &r.stats);
    return r;
}
Run RenderOnce(const RenderScene &scene) {
    Run r;
    r.image = Render(scene, &r.stats);
    return r;
}

// Whether the setting leaves the base settings as they are (light samples are per light, the
// light sampler's base is the file's and the BVH quality's is Auto, so none of theirs is).
bool IsBaseSetting(const StudySetting &s, int baseSpp, int baseMaxDepth) {
    switch (s.knob) {
        case StudyKnob::Spp:
            return s.value == std::to_string(baseSpp);
        case StudyKnob::MaxDepth:
            return s.value == std::to_string(baseMaxDepth);
        case StudyKnob::Cutoff:
            return s.value == "0";
        case StudyKnob::Precision:
            return s.value == "double";
        case StudyKnob::Offset:
            return s.value == "errorbounds";
        case StudyKnob::Robust:
            return s.value == "off";
        default:
            return false;
    }
}

StudyRow MakeRow(const StudySetting &s, const std::vector<double> &times,
                 const std::vector<double> &builds, const Run &last, const Image &reference) {
    StudyRow row;
    row.knob = KnobName(s.knob);
    row.value = s.value;
    row.timeSeconds = Median(times);
    row.buildSeconds = Median(builds);
    row.rays = last.stats.rays.Total();
    row.error = MeasureError(last.image, reference, last.stats.nonFiniteSamples);
    return row;
}

void CheckOptions(const StudyOptions &o) {
    if (o.repeats < 1) throw std::invalid_argument("study: repeats must be at least 1");
    if (o.referenceSpp < 1 || o.referenceSpp > MaxSamplesPerPixel)
        throw std::invalid_argument("study: reference spp out of range");
    if (o.baseSpp < 0 || o.baseSpp > MaxSamplesPerPixel)
        throw std::invalid_argument("study: base spp out of range");
    for (int n : o.tessellateLevels)
        if (n < 3 || n > 4096)
            throw std::invalid_argument("study: tessellation level out of range");
}

}  // namespace

const char *KnobName(StudyKnob knob) {
    for (const KnobEntry &e : Knobs)
        if (e.knob == knob) return e.name;
    return "?";
}

std::optional<StudyKnob> ParseKnobName(std::string_view name) {
    for (const KnobEntry &e : Knobs)
        if (name == e.name) return e.knob;
    return std::nullopt;
}

std::vector<StudyKnob> AllStudyKnobs() {
    std::vector<StudyKnob> all;
    for (const KnobEntry &e : Knobs) all.push_back(e.knob);
    return all;
}

std::vector<StudySetting> KnobSettings(StudyKnob knob, const StudyOptions &options) {
    std::vector<StudySetting> v;
    switch (knob) {
        case StudyKnob::Spp:
            // Below the reference's spp: at the same count the samples are the reference's own.
            for (int n = 1; n <= 256 && n < options.referenceSpp; n *= 2)
                v.push_back(Setting(knob, std::to_string(n), [n](BuildSettings &s) { s.spp = n; }));
            break;
        case StudyKnob::MaxDepth:
            for (int d = 1; d <= ReferenceMaxDepth; ++d)
                v.push_back(
                    Setting(knob, std::to_string(d), [d](BuildSettings &s) { s.maxDepth = d; }));
            break;
        case StudyKnob::Cutoff: {
            const std::pair<const char *, float> cutoffs[] = {
                {"0", 0.f}, {"1e-4", 1e-4f}, {"1e-3", 1e-3f}, {"1e-2", 1e-2f}};
            for (const auto &[label, c] : cutoffs)
                v.push_back(Setting(knob, label, [c = c](BuildSettings &s) { s.rayCutoff = c; }));
            break;
        }
        case StudyKnob::Precision:
            v.push_back(
                Setting(knob, "float", [](BuildSettings &s) { s.precision = Precision::Float; }));
            v.push_back(
                Setting(knob, "double", [](BuildSettings &s) { s.precision = Precision::Double; }));
            break;
        case StudyKnob::Offset: {
            const std::tuple<const char *, OffsetMode, float> offsets[] = {
                {"errorbounds", OffsetMode::ErrorBounds, 0.f},
                {"epsilon-1e-4", OffsetMode::FixedEpsilon, 1e-4f},
                {"epsilon-1e-3", OffsetMode::FixedEpsilon, 1e-3f},
                {"none", OffsetMode::None, 0.f}};
            for (const auto &[label, mode, eps] : offsets)
                v.push_back(Setting(knob, label, [mode = mode, eps = eps](BuildSettings &s) {
                    s.offset.mode = mode;
                    if (mode == OffsetMode::FixedEpsilon) s.offset.epsilon = eps;
                }));
            break;
        }
        case StudyKnob::Tessellate:
            for (int n : options.tessellateLevels)
                v.push_back(Setting(knob, std::to_string(n), [n](BuildSettings &s) {
                    s.replaceAnalyticShape = TessellateWith(n);
                }));
            break;
        case StudyKnob::Robust:
            v.push_back(Setting(knob, "off", [](BuildSettings &s) { s.robust = false; }));
            v.push_back(Setting(knob, "on", [](BuildSettings &s) { s.robust = true; }));
            break;
        case StudyKnob::BvhQuality: {
            const std::pair<const char *, BvhQuality> qualities[] = {{"low", BvhQuality::Low},
                                                                     {"medium", BvhQuality::Medium},
                                                                     {"high", BvhQuality::High}};
            for (const auto &[label, q] : qualities)
                v.push_back(Setting(knob, label, [q = q](BuildSettings &s) { s.bvhQuality = q; }));
            break;
        }
        case StudyKnob::LightSamples:
            for (int n : {1, 2, 4, 8, 16})
                v.push_back(Setting(knob, std::to_string(n),
                                    [n](BuildSettings &s) { s.lightSamples = n; }));
            break;
        case StudyKnob::LightSampler:
            for (const char *name : {"uniform", "power", "bvh"})
                v.push_back(
                    Setting(knob, name, [name](BuildSettings &s) { s.lightSampler = name; }));
            break;
    }
    return v;
}

bool KnobReusesScene(StudyKnob knob) {
    // Light samples live in each light and the ray offset in the scene (both built), so they
    // rebuild; samples, depth and cutoff are render options (RenderTimeOptions).
    return knob == StudyKnob::Spp || knob == StudyKnob::MaxDepth || knob == StudyKnob::Cutoff;
}

std::optional<std::string> KnobSkipReason(StudyKnob knob, const SceneFeatures &f) {
    switch (knob) {
        case StudyKnob::MaxDepth:
            if (!f.specularReflection && !f.transmission)
                return "the scene has no mirror, glass or other specular material, so the trace "
                       "depth changes nothing";
            break;
        case StudyKnob::Precision:
        case StudyKnob::Tessellate:
            if (f.analyticShapes == 0) return "the scene has no analytic shapes";
            break;
        case StudyKnob::LightSamples:
            if (!f.areaLights && !f.environment)
                return "the scene has no area or infinite light (point, spot and distant lights "
                       "take one shadow ray)";
            break;
        default:
            break;
    }
    return std::nullopt;
}

std::optional<std::string> LightSamplerSkipReason(const RenderScene &scene) {
    const std::string name = scene.integrator ? scene.integrator->Name() : "";
    if (name != "path" && name != "volpath")
        return "the " + name + " integrator does not choose one light per shadow ray";
    if (scene.lights.size() < 2 && (scene.lights.empty() || !scene.lights[0]->IsArea()))
        return std::string("the scene has one light, which every choice takes");
    return std::nullopt;
}

ImageError MeasureError(const Image &image, const Image &reference, uint64_t nonFiniteSamples) {
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("MeasureError: images of different sizes");
    ImageError e;
    e.nanCount = nonFiniteSamples;
    double sumSq = 0, sumAbs = 0, sumRef = 0, sumRefSq = 0;
    uint64_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            RGB a = image.GetRGB(x, y), b = reference.GetRGB(x, y);
            bool bad = false;
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(a[c])) {
                    ++e.nanCount;
                    continue;
                }
                double d = std::abs(double(a[c]) - double(b[c]));
                sumSq += d * d;
                sumAbs += d;
                sumRef += std::abs(double(b[c]));
                sumRefSq += double(b[c]) * double(b[c]);
                e.maxAbs = std::max(e.maxAbs, d);
                bad |= d > BadPixelThreshold;
                ++n;
            }
            e.badPixels += bad;
        }
    double mse = n ? sumSq / double(n) : 0;
    e.rmse = std::sqrt(mse);
    e.relL1 = sumRef > 0 ? sumAbs / sumRef : (sumAbs > 0 ? Infinity : 0);
    e.psnr = mse > 0 ? 10 * std::log10(1 / mse) : Infinity;
    e.relRmse = sumRefSq > 0 ? std::sqrt(sumSq / sumRefSq) : (sumSq > 0 ? Infinity : 0);
    return e;
}

StudyResult RunStudy(const SceneDescription &desc, const std::string &sceneName,
                     const StudyOptions &options, Diagnostics &diag,
                     const StudyProgress &progress) {
    CheckOptions(options);
    std::vector<StudyKnob> knobs = options.knobs.empty() ? AllStudyKnobs() : options.knobs;
    // Each knob once, in the order given.
    std::vector<StudyKnob> unique;
    for (StudyKnob k : knobs)
        if (std::find(unique.begin(), unique.end(), k) == unique.end()) unique.push_back(k);

    // The base scene: the scene's own settings (spp maybe replaced); it stays built for the
    // reference and for the knobs that reuse it. Rebuilt settings charge a budget of their own
    // on top of what it holds, so at most two built scenes are alive at a time.
    MemoryBudget budget(options.maxMemory);
    BuildSettings base;
    base.resolution = options.resolution;
    base.spp = options.baseSpp;
    base.budget = &budget;
    const RenderScene scene = BuildRenderScene(desc, base, diag);
    const int baseSpp = scene.sampler.spp, baseMaxDepth = scene.trace.maxDepth;

    StudyResult result;
    result.scene = sceneName;
    result.resolution = {scene.pixelBounds.pMax.x - scene.pixelBounds.pMin.x,
                         scene.pixelBounds.pMax.y - scene.pixelBounds.pMin.y};
    result.repeats = options.repeats;
    result.referenceSpp = options.referenceSpp;
    result.referenceMaxDepth = std::max(ReferenceMaxDepth, baseMaxDepth);
    result.baseSpp = baseSpp;
    result.baseMaxDepth = baseMaxDepth;

    // What runs: every applicable knob's settings.
    std::vector<StudySetting> settings;
    bool anyReused = false;
    for (StudyKnob k : unique) {
        std::optional<std::string> why = KnobSkipReason(k, scene.features);
        if (k == StudyKnob::LightSampler) why = LightSamplerSkipReason(scene);
        if (why) {
            result.skipped.push_back({k, *why});
            continue;
        }
        for (StudySetting &s : KnobSettings(k, options)) settings.push_back(std::move(s));
        anyReused |= KnobReusesScene(k);
    }

    // The reference: the base scene (double precision, analytic shapes, error-bound offsets,
    // no cutoff are the defaults) at many samples and depth 16.
    RenderOptions refOptions;
    refOptions.sampler = scene.sampler;
    refOptions.sampler.spp = options.referenceSpp;
    refOptions.trace = scene.trace;
    refOptions.trace->maxDepth = std::max(ReferenceMaxDepth, baseMaxDepth);
    const Run ref = RenderOnce(scene, refOptions);
    result.referenceSeconds = ref.stats.renderSeconds;

    // The shared scene's build time, as a median over as many builds as the others get.
    Diagnostics quiet(false);
    std::vector<double> sharedBuilds{scene.buildSeconds};
    if (anyReused)
        for (int i = 1; i < options.repeats; ++i) {
            MemoryBudget b(options.maxMemory);
            b.Charge(budget.Used(), "the study's base scene");
            BuildSettings s = base;
            s.budget = &b;
            sharedBuilds.push_back(BuildRenderScene(desc, s, quiet).buildSeconds);
        }

    int index = 0;
    for (const StudySetting &setting : settings) {
        if (progress) progress(++index, int(settings.size()), setting);
        BuildSettings s = base;
        setting.apply(s);
        std::vector<double> times, builds;
        Run last;
        if (KnobReusesScene(setting.knob)) {
            const RenderOptions renderOptions = RenderTimeOptions(s, scene);
            for (int i = 0; i < options.repeats; ++i) {
                last = RenderOnce(scene, renderOptions);
                times.push_back(last.stats.renderSeconds);
            }
            builds = sharedBuilds;
        } else {
            for (int i = 0; i < options.repeats; ++i) {
                MemoryBudget b(options.maxMemory);
                b.Charge(budget.Used(), "the study's base scene");
                s.budget = &b;
                RenderScene built = BuildRenderScene(desc, s, quiet);
                builds.push_back(built.buildSeconds);
                last = RenderOnce(built);
                times.push_back(last.stats.renderSeconds);
            }
        }
        result.rows.push_back(MakeRow(setting, times, builds, last, ref.image));
        result.rows.back().base = IsBaseSetting(setting, baseSpp, baseMaxDepth);
    }
    return result;
}

}  // namespace prism
