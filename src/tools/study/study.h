// `prism study`: what each kind of accuracy costs in time on one scene. Every setting of each
// accuracy knob is rendered (the other knobs at the base settings), timed (median of repeats,
// BVH build and render apart) and compared with a reference render (study_report.h writes the
// results). The loaded SceneDescription serves every setting; knobs that only the renderer reads
// (spp, maxdepth, cutoff, offset; KnobReusesScene) reuse one built RenderScene and its BVH, the
// others rebuild it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "assembly/build_scene.h"
#include "core/vecmath.h"
#include "image/image.h"
#include "scene/scene_description.h"

namespace prism {

// The knobs, in the order `--knob all` studies them.
enum class StudyKnob {
    Spp,
    MaxDepth,
    Cutoff,
    Precision,
    Offset,
    Tessellate,
    Robust,
    BvhQuality,
    LightSamples,
    LightSampler
};

// The name `--knob` takes ("spp", "maxdepth", "cutoff", "precision", "offset", "tessellate",
// "robust", "bvh-quality", "light-samples", "light-sampler") and its inverse.
const char *KnobName(StudyKnob knob);
std::optional<StudyKnob> ParseKnobName(std::string_view name);
std::vector<StudyKnob> AllStudyKnobs();

// One setting of one knob: its label in results.csv and what it changes in the base settings.
struct StudySetting {
    StudyKnob knob = StudyKnob::Spp;
    std::string value;  // "16", "1e-3", "float", "epsilon-1e-4", "on", "high", ...
    std::function<void(BuildSettings &)> apply;
};

struct StudyOptions {
    std::vector<StudyKnob> knobs;  // empty: all
    Vec2i resolution{0, 0};        // 0: the Film's
    int repeats = 3;               // runs per setting; times are medians
    int referenceSpp = 256;
    // spp of every setting of the other knobs; 0: the scene's own (its Sampler).
    int baseSpp = 0;
    std::vector<int> tessellateLevels{8, 16, 32, 64, 128};
    uint64_t maxMemory = 0;  // bytes for the scene and two built scenes at a time; 0: default
};

// The settings of a knob. spp takes powers of two up to 256 below options.referenceSpp (the
// camera samples are a pure function of the pixel and the count, so at the reference's own
// count they would be the reference's).
std::vector<StudySetting> KnobSettings(StudyKnob knob, const StudyOptions &options);

// Whether the knob is read only by the renderer, so that one built scene (and BVH) serves all
// its settings: spp, maxdepth, the cutoff and the offset (RenderScene fields).
// The others rebuild (light samples are in the lights).
bool KnobReusesScene(StudyKnob knob);

// Why the knob does not apply to the scene (nothing to study), or nullopt when it does.
std::optional<std::string> KnobSkipReason(StudyKnob knob, const SceneFeatures &features);
// The light-sampler knob's: an integrator that does not choose one light per shadow ray (all
// but path and volpath), or a scene of one light that is not an emissive shape.
std::optional<std::string> LightSamplerSkipReason(const RenderScene &scene);

// Error of an image against the reference, over every pixel's RGB components (docs/USAGE.md
// "Accuracy study"):
//   rmse        sqrt(mean (a - ref)^2)
//   rel_l1      sum |a - ref| / sum |ref|  (mean absolute error over the mean reference value)
//   max_abs_err max |a - ref|
//   psnr        10 log10(1 / mse), peak 1 (linear radiance; +inf when identical)
//   bad_pixels  pixels with some component off by more than BadPixelThreshold (acne, leaks)
//   nan_count   NaN/Inf samples (the renderer writes them as 0) plus non-finite components
// A component non-finite in `a` counts in nan_count and is left out of the other measures.
// relRmse (not in results.csv; for `--target-error`) is sqrt(sum (a - ref)^2 / sum ref^2),
// the rmse relative to the reference's root mean square.
inline constexpr float BadPixelThreshold = 0.1f;
struct ImageError {
    double rmse = 0, relL1 = 0, maxAbs = 0, psnr = 0, relRmse = 0;
    int64_t badPixels = 0;
    uint64_t nanCount = 0;
};
// Throws std::invalid_argument when the sizes differ.
ImageError MeasureError(const Image &image, const Image &reference, uint64_t nonFiniteSamples);

// One row of results.csv.
struct StudyRow {
    std::string knob, value;
    double timeSeconds = 0;   // render, median of the repeats
    double buildSeconds = 0;  // BVH build, median (of the shared scene's builds when reused)
    uint64_t rays = 0;        // rays traced by one render (RayCounters::Total)
    ImageError error;
    // The value is the base settings' (spp and maxdepth the scene's, cutoff 0, double, error
    // bounds, ROBUST off): the row renders the base image.
    bool base = false;
};

struct SkippedKnob {
    StudyKnob knob;
    std::string reason;
};

struct StudyResult {
    std::string scene;  // as given (for the report)
    Vec2i resolution{0, 0};
    int repeats = 0;
    int referenceSpp = 0, referenceMaxDepth = 0;
    double referenceSeconds = 0;
    int baseSpp = 0, baseMaxDepth = 0;  // the settings the other knobs keep
    std::vector<StudyRow> rows;
    std::vector<SkippedKnob> skipped;
};

// Called before each setting: index from 1 to count.
using StudyProgress = std::function<void(int index, int count, const StudySetting &setting)>;

// Renders the reference (referenceSpp, maxdepth 16 or the scene's if deeper, double precision,
// analytic shapes, error-bound offsets, no cutoff, the scene's light samples) and every setting of
// every applicable knob. Throws SceneError for bad input (as BuildRenderScene does), before any
// setting is timed when the scene itself is bad.
StudyResult RunStudy(const SceneDescription &desc, const std::string &sceneName,
                     const StudyOptions &options, Diagnostics &diag,
                     const StudyProgress &progress = {});

}  // namespace prism
