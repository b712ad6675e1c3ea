// `prism render --target-error E`: the cheapest spp, ray cutoff and light samples predicted to
// reach a relative RMSE of E (sqrt(sum (a - ref)^2 / sum ref^2) against the study's reference),
// chosen from a pilot study at low resolution. The model and its measured accuracy are in
// docs/ACCURACY.md, "--target-error".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "assembly/build_scene.h"
#include "image/image.h"
#include "scene/scene_description.h"

namespace prism {

// y = a x^-b.
struct PowerLaw {
    double a = 0, b = 0;
    double operator()(double x) const;
};
// Least squares on (log x, log y); points with y <= 0 are left out. Needs two distinct x.
PowerLaw FitPowerLaw(const std::vector<double> &x, const std::vector<double> &y);

// The error of a render at n samples per pixel, as relRmse^2(n) = floor2 + (a n^-b)^2: noise
// that falls as a power of n (stratified sampling: b near 0.5 for shading and light noise,
// up to 0.75 on edges) over a floor that no spp removes (the bias of the scene's maxdepth
// against the reference's 16, of a ray cutoff).
struct ErrorCurve {
    double floor2 = 0;
    PowerLaw noise;
    double Error(double spp) const;
    // The fewest samples, among the well-stratified sample counts (IsWellStratifiedSampleCount),
    // whose predicted error is at most `target`; nullopt when the floor is at or above it (or more
    // than MaxSamplesPerPixel would be needed).
    std::optional<int> SppFor(double target) const;
};
// Whether n samples stratify well: any count up to 8, above that the counts whose grid of
// strata (render/sampler.h, CMJGrid: m x n/m, m >= n/m) is at most twice as wide as tall: 9,
// 12, 15, 16, 18, 20, 24, 25, 28, 30, 32, ... The sampler fills every count's grid exactly, but
// long thin grids (a prime n is n x 1) stratify 2-D features less well, so above a few samples
// the error is not monotone across them (scenes/whitted.pbrt at 320x240 against 256 spp:
// RMSE 0.00258 at 20 spp, 0.00255 at 21, 0.00300 at 23; but 2, 3, 4, 5, 6 spp: 0.0168, 0.0116,
// 0.0091, 0.0080, 0.0067, smooth). The choice uses these counts.
bool IsWellStratifiedSampleCount(int n);
// The smallest well-stratified count >= n.
int NextWellStratifiedSampleCount(int n);

// Fits an ErrorCurve to squared errors at the given spp: the floor by a search over
// [0, min err2), the power law by FitPowerLaw on err2 - floor; the fit with the least squared
// error of log(err2) wins.
ErrorCurve FitErrorCurve(const std::vector<int> &spp, const std::vector<double> &err2);

// relRmse of `image` against `reference` (as MeasureError's relRmse): non-finite components
// are left out. Throws std::invalid_argument when the sizes differ.
double RelativeRmse(const Image &image, const Image &reference);

// The pilot's resolution for a full resolution: half of each axis, at least 64 pixels wide
// (the full width when that is smaller), the aspect ratio kept.
Vec2i PilotResolution(Vec2i full);

// One candidate setting and what the pilot predicts for it at the full resolution.
struct TargetCandidate {
    int lightSamples = 0;  // 0: each light's own nsamples
    float cutoff = 0;
    ErrorCurve curve;             // predicted error at the full resolution
    double secondsPerSpp = 0;     // predicted render time per spp at the full resolution
    std::optional<int> spp;       // fewest spp reaching the target (nullopt: unreachable)
    double predictedError = 0;    // curve.Error(*spp)
    double predictedSeconds = 0;  // *spp * secondsPerSpp
};

struct TargetChoice {
    int spp = 1;
    float cutoff = 0;
    int lightSamples = 0;  // 0: the scene's own
    double target = 0, predictedError = 0, predictedSeconds = 0;
    double pilotSeconds = 0;  // wall time of the whole pilot
    Vec2i pilotResolution{0, 0}, resolution{0, 0};
    std::vector<TargetCandidate> candidates;  // every setting the pilot weighed
    // The resolution correction at 9 spp (the scene's light samples): the share of the
    // pilot's squared error that behaves as edge error (falls as 1 / width), and the predicted
    // full-resolution error over the pilot's.
    double edgeShare = 0, resolutionFactor = 1;
    // relRmse of the scene's maxdepth against the reference's, at the full resolution.
    double depthBias = 0;
};

struct TargetOptions {
    double target = 0;     // relRmse to reach, > 0
    int pilotRefSpp = 64;  // the pilot reference's spp
    // The pilot's spp points (well-stratified sample counts, as the choice), at the scene's own
    // light samples; the other light-sample choices are rendered at lightSpp only.
    std::vector<int> pilotSpp{1, 2, 4, 6, 9, 12, 16, 20};
    std::vector<int> lightSpp{2, 4, 9};
    std::vector<float> cutoffs{0, 1e-4f, 1e-3f, 1e-2f};  // starts with 0
    // Light samples per area/infinite light to weigh (0: the lights' own); only for scenes
    // with such lights.
    std::vector<int> lightSamples{0, 1, 4, 16};
};

// Runs the pilot and picks the cheapest candidate predicted to reach options.target. `base` is
// the render's settings (resolution, crop, camera, maxdepth, precision, offsets, BVH); its spp,
// cutoff and light samples are ignored. Throws UsageError when no candidate can reach the
// target (its floor is above it) and SceneError for bad input.
TargetChoice ChooseTargetSettings(const SceneDescription &desc, const BuildSettings &base,
                                  const TargetOptions &options, Diagnostics &diag);

// The settings with the choice applied.
BuildSettings ApplyTargetChoice(BuildSettings base, const TargetChoice &choice);

// --verify: `image`, rendered with the choice, against a reference at the full resolution
// (refSpp samples, maxdepth 16 or the scene's if deeper, no cutoff, the scene's light samples,
// `base`'s precision and offsets). The reference's own error is estimated from the pilot's
// curve for the scene's light samples and taken out: reached^2 = measured^2 - refError^2.
struct TargetVerification {
    int refSpp = 0;
    double measured = 0, refError = 0, reached = 0, refSeconds = 0;
};
TargetVerification VerifyTarget(const SceneDescription &desc, const BuildSettings &base,
                                const TargetChoice &choice, const Image &image, Diagnostics &diag);

// The report lines ("target-error: chose spp 23, ..."), without a trailing newline.
// DescribeChoice has two lines: the choice, then the resolution correction.
std::string DescribeChoice(const TargetChoice &choice);
std::string DescribeVerification(const TargetChoice &choice, const TargetVerification &v);

}  // namespace prism
