// `prism render`'s options and the steps around the render loop, shared by `prism render` and
// `prism-mpi render` (src/tools/mpi), so both executables take the same options, load and build the
// scene the same way and write the same image.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "app/common.h"
#include "render/renderer.h"

namespace CLI {
class App;
}

namespace prism {

struct RenderArgs {
    std::string scene, output, res, crop, precision = "double", lookAt, maxMemory, camera;
    int spp = 0, threads = 0, maxDepth = -1, lightSamples = 0, glossySamples = 0;
    std::string integrator;     // empty: the scene's
    std::string sampler;        // --sampler; empty: the scene's
    std::string lightSampler;   // --light-sampler; empty: the integrator's
    std::string pbrtVersion;    // --pbrt-version; empty: detected
    std::string textureFilter;  // --texture-filter; empty: each texture's own
    int tessellate = 0;         // [validate hook]
    float fov = 0;
    bool quiet = false, noProgress = false;
    ConfineOption confine;          // --confine [DIR]
    std::string effects = "scene";  // --effects: "scene" (specialized kernel) or "all"
    // Accuracy knobs (docs/SHAPES.md, `prism study`).
    float cutoff = 0, offsetEpsilon = 0;      // offsetEpsilon 0: not given
    std::string offset, bvhQuality = "auto";  // offset empty: not given
    bool robust = false;
    // --target-error (docs/ACCURACY.md): 0 when not given; the explicit options it conflicts
    // with, as given on the command line.
    double targetError = 0;
    bool verify = false, sppGiven = false, cutoffGiven = false, lightSamplesGiven = false;
    // Output (docs/USAGE.md "Exposure and tone mapping"): empty / not given → the Film's, else
    // the scene format's default.
    float exposure = 0;
    bool exposureGiven = false, exposureAuto = false;  // --exposure auto
    std::string exposureText;                          // as given
    std::string toneMap;
    // --env (docs/USAGE.md "Lighting"): empty when not given.
    std::string env, envMode;
    double envRotate = 0;
    bool envRotateGiven = false;
    std::string aov;  // --aov LIST|all (render/aov.h); empty: the Film's "aovs"
    // --time-limit (render/progressive.h): 0 when not given; counted from the start of the job.
    double timeLimit = 0;
    bool stats = false;  // --stats: the noise estimate (relative standard error)
};

// Registers the render options on `cmd` (its positional "scene" included). Call the returned
// function first in cmd's callback: it records which of the options were given.
std::function<void()> AddRenderOptions(CLI::App *cmd, RenderArgs *args);

// One render around the render loop: the constructor checks the options, loads the scene,
// builds it (BVH included) and checks the output path, throwing SceneError or UsageError on
// bad input; Write writes the image and Report prints the statistics.
class RenderJob {
  public:
    // writer false (prism-mpi's ranks other than 0): the scene's warnings are not printed, so
    // each is printed once, and the output path is not checked (only rank 0 writes it).
    explicit RenderJob(const RenderArgs &args, bool writer = true);
    ~RenderJob();
    RenderJob(const RenderJob &) = delete;
    RenderJob &operator=(const RenderJob &) = delete;

    const RenderScene &Scene() const;
    // Renders the image: Render(), or with --time-limit RenderProgressive with the time left
    // since the job started.
    Image RenderImage(RenderStats *stats, const ProgressFn &progress, const volatile int *cancel);
    // Whether the output gets AOVs; RenderImage computes them from its own tiles. prism-mpi,
    // whose tiles render on other ranks, computes them on rank 0 with RenderAovs: the same
    // samples again (render/aov.h).
    bool HasAovs() const;
    void RenderAovs(const volatile int *cancel);
    const std::string &Output() const;
    // The progress display (empty with --quiet or --no-progress); its clock starts here.
    ProgressFn Progress();
    // Writes `img` (with the exposure and tone map) atomically; throws on a failed write.
    void Write(const Image &img);
    // Runs --verify and, unless --quiet, prints the statistics.
    void Report(const Image &img, const RenderStats &stats);

  private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace prism
