// `prism bench compare`: time to equal error against reference renderers (pbrt-v3, pbrt-v4) on a
// scene a user brings. Each renderer renders the same file at a ladder of sample counts, in
// interleaved repeats. Each image's relative RMSE against a converged reference is fitted as a
// power of the sample count (a line in log-log) and each renderer's CPU time as a start-up cost
// plus a cost per sample; the time each needs to reach one error is read off the two
// (docs/BENCHMARKS.md, "Equal-error comparison").
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace prism {

enum class CompareKind { Prism, PbrtV3, PbrtV4 };

struct CompareRenderer {
    std::string name;  // "prism", "pbrt-v3", "pbrt-v4"
    CompareKind kind = CompareKind::Prism;
    std::string path;  // the executable ("" for prism: this one)
};

struct CompareOptions {
    std::string scene;
    std::vector<CompareRenderer> against;  // the reference renderers, the first one the reference
    int threads = 1;
    double targetError = 0;  // 0: the first reference renderer's error at targetSpp
    int targetSpp = 0;       // 0: the file's count
    std::string outDir;      // "": a temporary folder, removed at the end
    std::string reference;   // a converged image; "": rendered (referenceSpp)
    std::vector<int> spp;    // the ladder; empty: DefaultLadder of the scene's spp
    int referenceSpp = 0;    // 0: 8 x the ladder's largest count
    // Each renderer measured against its own referenceSpp image (its noise alone), not the
    // shared one; the references' differences are printed. Ignored with `reference`.
    bool ownReference = false;
    int repeats = 3;            // timing repeats (medians); the images of the first are measured
    int width = 0, height = 0;  // --res: every renderer's image size (0: the file's)
    std::string commandLine;    // printed and written to the CSV's folder
    std::string sourceDir;      // for tools/plot_compare.py
};

struct CompareOutcome;
// Returns the exit status: 0 when every renderer rendered and reached the error, 3 when one
// failed or never reaches it (each is reported as such). Throws SceneError (the scene, or a
// pbrt-v3 Sampler that cannot be rewritten) and std::runtime_error. With `outcomes`, also each
// renderer's outcome (Prism first) and the target error.
int RunCompare(const CompareOptions &options, std::FILE *out,
               std::vector<CompareOutcome> *outcomes = nullptr, double *target = nullptr);

// --- pieces, exposed for the tests -----------------------------------------------------------

// The scene's spp / 8, / 4, / 2, x 1 and x 2, at least 1, without repeats.
std::vector<int> DefaultLadder(int sceneSpp);

// pbrt-v3 text with every Sampler before WorldBegin asking for `spp` samples ("pixelsamples";
// for "stratified", xsamples x ysamples = spp, as pbrt-v4's --spp splits it), and a Sampler
// "halton" (pbrt-v3's default) inserted before WorldBegin when the file has none. `file` labels
// errors (SceneError: the text does not tokenize, or has no WorldBegin).
std::string SetPbrtV3SampleCount(const std::string &text, int spp, const std::string &file);

// pbrt text with every Film before WorldBegin at width x height ("xresolution",
// "yresolution"), and a Film `defaultFilm` ("image" for pbrt-v3, "rgb" for pbrt-v4) of that size
// inserted before WorldBegin when the file has none. SceneError as above.
std::string SetPbrtResolution(const std::string &text, int width, int height,
                              const std::string &defaultFilm, const std::string &file);

// log(y) = a + b log(x), least squares over the points with positive, finite values; ok needs
// two distinct x.
struct LogLogFit {
    double a = 0, b = 0;
    bool ok = false;
};
LogLogFit FitLogLog(const std::vector<double> &x, const std::vector<double> &y);

// A renderer's error and time as functions of the sample count n: error = e^a n^b (the
// log-log line) and seconds = t0 + c n (least squares; t0 >= 0, c >= 0). The time is a line in
// n, not a power: a whole process pays its start-up once, so the error is not a power of the
// time where start-up is a good part of it.
struct CompareFit {
    LogLogFit error;
    double t0 = 0, c = 0;
    double Seconds(double n) const { return t0 + c * n; }
};
CompareFit FitRenderer(const std::vector<int> &spp, const std::vector<double> &errors,
                       const std::vector<double> &seconds);
// The (fractional) sample count at which the error reaches `error`; nullopt when it never does
// (slope >= -0.05: the error no longer falls with more samples).
std::optional<double> SppToError(const LogLogFit &fit, double error);

// The last line: `equal-error E: prism T s, NAME T s (ratio R), ...` (a renderer without a time
// is "NAME failed" or "NAME never").
struct CompareOutcome {
    std::string name;
    std::optional<double> seconds;  // nullopt: failed or never
    bool failed = false;
};
std::string EqualErrorLine(double error, const std::vector<CompareOutcome> &outcomes);

}  // namespace prism
