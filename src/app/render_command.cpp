#include <fmt/core.h>
#include <signal.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/aov_output.h"
#include "app/commands.h"
#include "app/common.h"
#include "app/render_options.h"
#include "assembly/build_scene.h"
#include "core/file_io.h"
#include "image/image_io.h"
#include "render/integrator.h"
#include "render/kernel.h"
#include "render/progressive.h"
#include "render/ray_tree.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "tools/study/target_error.h"
#include "tools/validate/tessellate.h"

namespace prism {

namespace {

// The output transform: the command line's, else the Film's, else the format's default. The
// exposure of an OBJ, glTF or PLY scene lit by its own lights (not the studio rig or --env)
// written to an 8-bit format defaults to auto: their emitters come in arbitrary units.
OutputTransform ChooseOutputTransform(const RenderArgs &a, const RenderScene &scene, bool linearOut,
                                      const Image &img) {
    OutputTransform t;
    t.exposure = a.exposureGiven ? a.exposure : scene.filmExposure;
    if (a.exposureGiven)
        t.autoExposure = a.exposureAuto;
    else if (scene.filmExposure == 0)
        t.autoExposure = !linearOut && scene.autoExposure8Bit && a.env.empty();
    ResolveAutoExposure(t, img);
    if (!a.toneMap.empty())
        ParseToneMap(a.toneMap, &t.toneMap);  // checked by CLI11
    else
        t.toneMap = scene.filmToneMap;
    return t;
}

// --target-error chooses spp, cutoff and light samples itself: giving one of them too is a
// usage error rather than a silent override either way.
void CheckTargetErrorArgs(const RenderArgs &a) {
    if (a.verify && a.targetError <= 0) throw UsageError("--verify needs --target-error");
    if (a.targetError <= 0) return;
    if (a.timeLimit > 0)
        throw UsageError(
            "--target-error and --time-limit both choose the samples per pixel; "
            "give one of them");
    for (auto [given, name] : {std::pair{a.sppGiven, "--spp"}, std::pair{a.cutoffGiven, "--cutoff"},
                               std::pair{a.lightSamplesGiven, "--light-samples"}})
        if (given)
            throw UsageError(std::string("--target-error chooses ") + (name + 2) +
                             " itself; drop " + name);
}

// --offset and --offset-epsilon: the epsilon alone implies `--offset epsilon`.
RayOffset ParseOffset(const std::string &mode, float epsilon) {
    RayOffset off;
    if (mode == "epsilon" || (mode.empty() && epsilon > 0))
        off.mode = OffsetMode::FixedEpsilon;
    else if (mode == "none")
        off.mode = OffsetMode::None;
    if (epsilon > 0) {
        if (off.mode != OffsetMode::FixedEpsilon)
            throw UsageError("--offset-epsilon needs --offset epsilon (not " + mode + ")");
        off.epsilon = epsilon;
    }
    return off;
}

BvhQuality ParseBvhQuality(const std::string &q) {
    if (q == "low") return BvhQuality::Low;
    if (q == "medium") return BvhQuality::Medium;
    if (q == "high") return BvhQuality::High;
    return BvhQuality::Auto;
}

const char *BvhQualityName(BvhQuality q) {
    switch (q) {
        case BvhQuality::Low:
            return "low";
        case BvhQuality::Medium:
            return "medium";
        case BvhQuality::High:
            return "high";
        default:
            return "auto";
    }
}

void PrintProgress(double f, std::chrono::steady_clock::time_point start, bool tty,
                   int *lastQuarter) {
    double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double eta = f > 0 ? elapsed * (1 - f) / f : 0;
    if (tty) {
        const int width = 40;
        int filled = int(f * width + 0.5);
        std::string bar(size_t(filled), '#');
        bar += std::string(size_t(width - filled), '.');
        std::fprintf(stderr, "\r[%s] %3.0f%%  %.1fs elapsed  ETA %.1fs ", bar.c_str(), 100 * f,
                     elapsed, eta);
        if (f >= 1) std::fprintf(stderr, "\n");
    } else {
        int q = int(f * 4);
        if (q > *lastQuarter) {
            *lastQuarter = q;
            std::fprintf(stderr, "render: %3.0f%% (%.1fs elapsed, ETA %.1fs)\n", 100.0 * q / 4,
                         elapsed, eta);
        }
    }
}

}  // namespace

struct RenderJob::State {
    RenderArgs a;
    std::optional<EnvironmentSpec> env;
    std::unique_ptr<ScopedReadConfinement> confined;
    BuildSettings opts;
    // One budget for everything this render holds: scene files and meshes (LoadScene), the
    // film, textures, meshes and BVH (BuildRenderScene); it lives until the render ends.
    std::unique_ptr<MemoryBudget> budget;
    std::unique_ptr<tbb::global_control> threadLimit;
    Diagnostics diag;
    SceneDescription desc;
    double parseSeconds = 0, setupSeconds = 0;
    std::optional<TargetChoice> target;
    std::optional<RenderScene> scene;
    std::string out;
    std::vector<Aov> aovs;                 // empty: no AOVs
    std::unique_ptr<AovOutput> aovOutput;  // with aovs: filled by the render
    std::chrono::steady_clock::time_point start;
    const std::chrono::steady_clock::time_point created = std::chrono::steady_clock::now();
    int lastQuarter = 0;

    State(const RenderArgs &args, bool writer) : a(args), diag(writer && !args.quiet) {}
};

RenderJob::RenderJob(const RenderArgs &args, bool writer)
    : s_(std::make_unique<State>(args, writer)) {
    const RenderArgs &a = s_->a;
    BuildSettings &opts = s_->opts;
    CheckTargetErrorArgs(a);
    CheckAovOption(a.aov, a.output);
    std::optional<EnvironmentSpec> &env = s_->env;
    if (!a.env.empty())
        env = ParseEnvironment(a.env, a.envRotate, a.envMode);
    else if (a.envRotateGiven || !a.envMode.empty())
        throw UsageError("--env-rotate and --env-mode need --env");
    // The --env map is the operator's, not the scene's: --confine does not apply to it.
    std::vector<std::string> operatorFiles;
    if (env && !env->mapFile.empty()) operatorFiles.push_back(env->mapFile);
    s_->confined = std::make_unique<ScopedReadConfinement>(ConfinementFolderFor(a.confine, a.scene),
                                                           operatorFiles);
    opts.spp = a.spp;
    opts.maxDepth = a.maxDepth;
    if (!a.res.empty()) opts.resolution = ParseResolution(a.res);
    if (!a.crop.empty()) opts.crop = ParseCrop(a.crop);
    opts.precision = ParsePrecision(a.precision);
    if (!a.lookAt.empty()) opts.worldFromCamera = ParseLookAt(a.lookAt);
    opts.fovDeg = a.fov;
    opts.lightSamples = a.lightSamples;
    opts.integrator = a.integrator;
    opts.sampler = a.sampler;
    opts.lightSampler = a.lightSampler;
    opts.glossySamples = a.glossySamples;
    opts.textureFilter = a.textureFilter;
    opts.rayCutoff = a.cutoff;
    opts.offset = ParseOffset(a.offset, a.offsetEpsilon);
    opts.robust = a.robust;
    opts.bvhQuality = ParseBvhQuality(a.bvhQuality);
    opts.allEffects = a.effects == "all";
    s_->budget = std::make_unique<MemoryBudget>(ParseMaxMemory(a.maxMemory));
    opts.budget = s_->budget.get();
    LoadOptions loadOpts;
    loadOpts.budget = s_->budget.get();
    loadOpts.pbrt.pbrtVersion = PbrtVersionNumber(a.pbrtVersion);
    loadOpts.camera = a.camera;
    if (a.tessellate > 0) opts.replaceAnalyticShape = TessellateWith(a.tessellate);

    if (a.threads > 0)
        s_->threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(a.threads));

    Diagnostics &diag = s_->diag;
    auto t0 = std::chrono::steady_clock::now();
    s_->desc = LoadScene(a.scene, diag, loadOpts);
    SceneDescription &desc = s_->desc;
    if (env) AddEnvironment(desc, *env);
    s_->parseSeconds = SecondsSince(t0);
    if (a.targetError > 0) {
        // The pilot takes seconds: a bad -o must fail before it (the Film's filename is
        // checked after the build, as without --target-error).
        if (!a.output.empty() && writer) CheckOutputPath(a.output);
        TargetOptions to;
        to.target = a.targetError;
        s_->target = ChooseTargetSettings(desc, opts, to, diag);
        opts = ApplyTargetChoice(opts, *s_->target);
        if (!a.quiet && writer) std::fprintf(stderr, "%s\n", DescribeChoice(*s_->target).c_str());
    }
    auto t1 = std::chrono::steady_clock::now();
    opts.estimateNoise = a.stats;
    s_->scene.emplace(BuildRenderScene(desc, opts, diag));
    diag.Flush();  // "and N more warnings like ..." before the render's own lines
    const RenderScene &scene = *s_->scene;
    // Scene setup: meshes read (PLY), textures decoded, materials and lights built.
    s_->setupSeconds = SecondsSince(t1) - scene.buildSeconds;

    std::string &out = s_->out;
    out = a.output;
    if (out.empty()) {
        out = scene.outputFilename;
        // An untrusted scene names no output outside the confined folder either.
        if (!out.empty() && writer) CheckOutputConfinement(out, desc.film);
    }
    if (out.empty()) out = std::filesystem::path(a.scene).stem().string() + ".png";
    if (writer) CheckOutputPath(out);  // before rendering: a long render must not fail at the end
    s_->aovs = ChooseAovs(a.aov, scene, out, s_->diag);
    if (!s_->aovs.empty()) s_->aovOutput = std::make_unique<AovOutput>(desc, scene, s_->aovs);
}

RenderJob::~RenderJob() = default;

const RenderScene &RenderJob::Scene() const { return *s_->scene; }

Image RenderJob::RenderImage(RenderStats *stats, const ProgressFn &progress,
                             const volatile int *cancel) {
    const RenderArgs &a = s_->a;
    AovFrame *aovs = s_->aovOutput ? &s_->aovOutput->Frame() : nullptr;
    if (a.timeLimit <= 0) {
        RenderOptions options;
        options.sampler = s_->scene->sampler;
        options.progress = progress;
        options.cancel = cancel;
        options.aovs = aovs;
        // Whole-frame integrators' intermediate images (sppm "imagewritefrequency"), written
        // as the final image is: atomically, with the same exposure and tone map.
        options.intermediate = [this](const Image &img) { Write(img); };
        return Render(*s_->scene, options, stats);
    }
    TimeLimit limit;
    limit.seconds = a.timeLimit - SecondsSince(s_->created);
    // --spp caps the passes; without it they go on until the time runs out.
    limit.maxSpp = a.sppGiven ? s_->scene->sampler.spp : MaxProgressiveSpp;
    return RenderProgressive(*s_->scene, limit, stats, progress, cancel, aovs);
}
bool RenderJob::HasAovs() const { return s_->aovOutput != nullptr; }

void RenderJob::RenderAovs(const volatile int *cancel) {
    if (!s_->aovOutput) return;
    RenderOptions options;
    options.sampler = s_->scene->sampler;
    options.cancel = cancel;
    options.aovs = &s_->aovOutput->Frame();
    Render(*s_->scene, options, nullptr);
}

const std::string &RenderJob::Output() const { return s_->out; }

ProgressFn RenderJob::Progress() {
    s_->start = std::chrono::steady_clock::now();
    s_->lastQuarter = 0;
    if (s_->a.quiet || s_->a.noProgress) return {};
    bool tty = isatty(STDERR_FILENO);
    State *s = s_.get();
    return [s, tty](double f) { PrintProgress(f, s->start, tty, &s->lastQuarter); };
}

void RenderJob::Write(const Image &img) {
    const std::string &out = s_->out;
    const bool linearOut = IsLinearImageExtension(LowerExtension(out));
    const OutputTransform outTransform = ChooseOutputTransform(s_->a, *s_->scene, linearOut, img);
    // A film in another colour space than sRGB says so in an EXR's header: the image written
    // carries its chromaticities (a copy only where none is made anyway).
    const std::optional<std::array<float, 8>> &chroma = s_->scene->filmChromaticities;
    const bool tag = chroma && !img.chromaticities;
    const bool plain =
        outTransform.exposure == 0 && (linearOut || outTransform.toneMap == ToneMap::None);
    if (plain && !s_->aovOutput && !tag) {
        WriteImage(out, img);
        return;
    }
    Image toWrite = img;  // --verify compares the linear render
    if (tag) toWrite.chromaticities = chroma;
    if (s_->aovOutput) {
        // The AOVs the render computed from its own tiles.
        ApplyOutputTransform(toWrite, outTransform, true);
        s_->aovOutput->Write(out, toWrite, std::exp2(outTransform.exposure));
    } else {
        if (!plain) ApplyOutputTransform(toWrite, outTransform, linearOut);
        WriteImage(out, toWrite);
    }
}

void RenderJob::Report(const Image &img, const RenderStats &stats) {
    const RenderArgs &a = s_->a;
    const RenderScene &scene = *s_->scene;
    const SceneDescription &desc = s_->desc;
    const BuildSettings &opts = s_->opts;
    const std::string &out = s_->out;
    const bool linearOut = IsLinearImageExtension(LowerExtension(out));
    const OutputTransform outTransform = ChooseOutputTransform(a, scene, linearOut, img);
    if (s_->target && a.verify) {
        TargetVerification v = VerifyTarget(desc, opts, *s_->target, img, s_->diag);
        std::fprintf(stderr, "%s\n", DescribeVerification(*s_->target, v).c_str());
    }
    // The ray tree's budget (render/ray_tree.h) cut some trees short: the image is not what
    // an unbounded render would make, so say so even when quiet.
    if (stats.rays.treeBudget > 0)
        std::fprintf(stderr,
                     "warning: %llu secondary rays not traced: ray trees reached their budget of "
                     "%llu rays per camera sample (surfaces that split every ray, such as nested "
                     "glass, at maxdepth %d)\n",
                     (unsigned long long)stats.rays.treeBudget, (unsigned long long)kRayTreeBudget,
                     scene.trace.maxDepth);
    if (!a.quiet) {
        const RayCounters &r = stats.rays;
        std::fprintf(stderr,
                     "%s: %dx%d, %d spp, maxdepth %d, %s precision, %s integrator\n"
                     "time: parse %.3fs, setup %.3fs, BVH build %.3fs, render %.3fs\n"
                     "rays: camera %llu, shadow %llu, reflection %llu, refraction %llu, "
                     "pass-through %llu, glossy %llu%s; %.2f Mrays/s\n",
                     EscapeControlChars(out).c_str(),  // a Film "filename" is the scene's
                     scene.pixelBounds.pMax.x - scene.pixelBounds.pMin.x,
                     scene.pixelBounds.pMax.y - scene.pixelBounds.pMin.y, stats.spp,
                     scene.trace.maxDepth, a.precision.c_str(), scene.IntegratorName(),
                     s_->parseSeconds, s_->setupSeconds, scene.buildSeconds, stats.renderSeconds,
                     (unsigned long long)r.camera, (unsigned long long)r.shadow,
                     (unsigned long long)r.reflection, (unsigned long long)r.refraction,
                     (unsigned long long)r.passThrough, (unsigned long long)r.glossy,
                     r.subsurface ? fmt::format(", subsurface {}", r.subsurface).c_str() : "",
                     stats.renderSeconds > 0 ? r.Total() / stats.renderSeconds * 1e-6 : 0.0);
        // The accuracy knobs, when any differs from Prism's defaults.
        if (opts.rayCutoff > 0 || opts.offset.mode != OffsetMode::ErrorBounds || opts.robust ||
            opts.bvhQuality != BvhQuality::Auto) {
            std::string off = opts.offset.mode == OffsetMode::ErrorBounds ? "error bounds"
                              : opts.offset.mode == OffsetMode::None
                                  ? "none"
                                  : fmt::format("epsilon {:g}", opts.offset.epsilon);
            std::fprintf(stderr,
                         "accuracy: ray cutoff %g (rays saved by cutoff %llu), offset %s, BVH %s "
                         "quality%s\n",
                         double(opts.rayCutoff), (unsigned long long)r.cutoff, off.c_str(),
                         BvhQualityName(scene.accel->BuildQuality()),
                         scene.accel->Robust() ? ", robust" : "");
        }
        if (outTransform.exposure != 0 || outTransform.toneMap != ToneMap::None ||
            !a.toneMap.empty())
            std::fprintf(stderr, "output: exposure %+g EV%s, tone map %s\n",
                         double(outTransform.exposure), outTransform.autoExposure ? " (auto)" : "",
                         linearOut ? "none (linear output)" : ToneMapName(outTransform.toneMap));
        std::string on;
        for (size_t e = 0; e < size_t(Effect::Count); ++e)
            if (scene.features.effects.Has(Effect(e)))
                on += std::string(on.empty() ? "" : ", ") + EffectName(Effect(e));
        // Only the Whitted and distribution integrators run the effect kernel.
        const std::string kernelName =
            scene.integrator->Traits().effectKernel
                ? KernelMaskName(stats.kernelMask)
                : std::string("none (") + scene.IntegratorName() + " integrator)";
        std::fprintf(stderr, "effects: %s; kernel: %s\n", on.empty() ? "none" : on.c_str(),
                     kernelName.c_str());
        if (const std::string s = scene.integrator->Summary(); !s.empty())
            std::fprintf(stderr, "%s\n", s.c_str());
        if (!stats.passSpp.empty()) {
            std::string passes;
            for (int n : stats.passSpp) passes += (passes.empty() ? "" : "+") + std::to_string(n);
            std::fprintf(stderr, "time limit %gs: %zu passes (%s = %d spp)\n", a.timeLimit,
                         stats.passSpp.size(), passes.c_str(), stats.spp);
        }
        if (a.stats) {
            std::optional<double> rse = RelativeStandardError(img, stats);
            if (rse)
                std::fprintf(stderr,
                             "noise: relative standard error %.4g (estimated from the even and "
                             "odd samples of %llu pixels)\n",
                             *rse, (unsigned long long)stats.noisePixels);
            else
                std::fprintf(stderr, "noise: no estimate (it needs at least 2 spp)\n");
        }
        if (stats.nonFiniteSamples > 0)
            std::fprintf(stderr,
                         "warning: %llu NaN/Inf samples were written as 0 (first at pixel %d,%d)\n",
                         (unsigned long long)stats.nonFiniteSamples, stats.firstNonFinitePixel->x,
                         stats.firstNonFinitePixel->y);
    }
}

namespace {

// SIGINT during a render sets this flag: the renderer stops within a camera packet (it is
// read between tiles and inside them, render/renderer.h TileDriver) and nothing is
// written. During the final write the signal is deferred, so the output is either complete or
// absent.
volatile sig_atomic_t g_cancel = 0;
void OnInterrupt(int) { g_cancel = 1; }

int RunRender(const RenderArgs &a) {
    RenderJob job(a);
    ProgressFn progress = job.Progress();
    RenderStats stats;
    struct sigaction sa {
    }, old{};
    sa.sa_handler = OnInterrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old);
    sigaction(SIGTERM, &sa, nullptr);
    Image img = job.RenderImage(&stats, progress, &g_cancel);
    if (stats.timedOut && !g_cancel) {
        std::fprintf(stderr,
                     "error: the time limit of %gs (--time-limit) ran out before the first "
                     "pass finished: no image written\n",
                     a.timeLimit);
        return ExitInternal;
    }
    if (stats.cancelled || g_cancel) {
        std::fprintf(stderr, "interrupted: no image written\n");
        return ExitInterrupted;
    }
    job.Write(img);
    sigaction(SIGINT, &old, nullptr);
    job.Report(img, stats);
    return ExitOk;
}

}  // namespace

std::function<void()> AddRenderOptions(CLI::App *cmd, RenderArgs *args) {
    cmd->add_option("scene", args->scene, "Scene file")->required();
    cmd->add_option("-o,--output", args->output,
                    "Output image (.exr linear float, .png sRGB); default: the Film's filename");
    CLI::Option *spp =
        cmd->add_option("--spp", args->spp, "Samples per pixel (overrides the Sampler)")
            ->check(CLI::Range(1, 1 << 16));
    cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--res", args->res, "Resolution WxH (overrides the Film)");
    cmd->add_option("--maxdepth", args->maxDepth,
                    "Maximum specular depth (overrides the Integrator)")
        ->check(CLI::Range(0, 1000));
    cmd->add_option("--integrator", args->integrator,
                    "whitted (pbrt-v3's: no glossy rays), distribution (Whitted plus glossy "
                    "reflection and transmission), directlighting, path, volpath or "
                    "ambientocclusion (ao) (pbrt-v3's); "
                    "default: the scene's Integrator (OBJ and glTF: distribution)")
        ->check(CLI::IsMember(IntegratorNames()));
    cmd->add_option("--sampler", args->sampler,
                    "Draw the samples as this pbrt sampler does, keeping the scene's count: "
                    "zsobol, paddedsobol, 02sequence, stratified, independent, ... "
                    "(docs/USAGE.md \"Samplers\"); default: the scene's Sampler")
        ->check(CLI::IsMember(SamplerNames()));
    cmd->add_option("--light-sampler", args->lightSampler,
                    "How the path integrators choose the light of each shadow ray: bvh (by "
                    "importance at the point, the default), power or uniform; default: the "
                    "Integrator's \"lightsampler\"/\"lightsamplestrategy\"")
        ->check(CLI::IsMember({"bvh", "power", "uniform"}));
    cmd->add_option("--glossy-samples", args->glossySamples,
                    "Glossy rays per glossy lobe at the first glossy bounce, 1 deeper down "
                    "(distribution integrator; overrides \"glossysamples\", default 8)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--texture-filter", args->textureFilter,
                    "Image-texture lookups for every imagemap: ewa, trilinear, bilinear (finest "
                    "level), point, or none (bilinear, and checkerboards point-sampled: no "
                    "footprint filtering); default: each texture's \"filter\" (EWA)")
        ->check(CLI::IsMember(TextureFilterNames));
    cmd->add_option("--crop", args->crop,
                    "Crop window x0,x1,y0,y1 in [0,1] (like Film \"cropwindow\")");
    cmd->add_option("--precision", args->precision, "Arithmetic of the analytic intersectors")
        ->check(CLI::IsMember({"float", "double"}));
    CLI::Option *lightSamples =
        cmd->add_option("--light-samples", args->lightSamples,
                        "Shadow rays per area/infinite light (overrides nsamples)")
            ->check(CLI::Range(1, 4096));
    CLI::Option *cutoff =
        cmd->add_option(
               "--cutoff", args->cutoff,
               "Ray-weight cutoff: trace a reflected or refracted ray only if its throughput "
               "exceeds this (default 0: every ray)")
            ->check(CLI::Range(0.0, 1e30));
    cmd->add_option("--offset", args->offset,
                    "How secondary rays leave a surface: errorbounds (default), epsilon or none")
        ->check(CLI::IsMember({"errorbounds", "epsilon", "none"}));
    cmd->add_option("--offset-epsilon", args->offsetEpsilon,
                    "Distance along the normal for --offset epsilon, in scene units (default 1e-4)")
        ->check(CLI::Range(1e-30, 1e30));
    cmd->add_flag("--robust", args->robust,
                  "Build the BVH with Embree's ROBUST flag (watertight triangle traversal)");
    cmd->add_option("--bvh-quality", args->bvhQuality,
                    "Embree build quality: auto (default: by triangles and samples), low, "
                    "medium or high")
        ->check(CLI::IsMember({"auto", "low", "medium", "high"}));
    cmd->add_option(
        "--lookat", args->lookAt,
        "Camera ex,ey,ez,lx,ly,lz,ux,uy,uz as pbrt's LookAt, unmirrored in right-handed OBJ/glTF "
        "worlds (replaces the scene's camera)");
    cmd->add_option("--camera", args->camera,
                    "glTF: view through this camera, by name or index (default: the first the "
                    "scene reaches)");
    cmd->add_option("--fov", args->fov, "Field of view in degrees on the shorter image axis")
        ->check(CLI::Range(0.001, 179.999));
    cmd->add_option(
           "--tessellate", args->tessellate,
           "Replace every analytic shape by its triangle twin with N segments around the axis")
        ->check(CLI::Range(3, 4096));
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget, e.g. 512M or 8G (default: 75% of physical RAM), for scene "
                    "files, meshes, BVH, textures and film together; more is an error");
    AddConfineOption(cmd, &args->confine);
    AddPbrtVersionOption(cmd, &args->pbrtVersion);
    cmd->add_option("--effects", args->effects,
                    "Kernel: \"scene\" (specialized for the scene's effects; `prism info` lists "
                    "them) or \"all\" (the general kernel: the same image, for comparison)")
        ->check(CLI::IsMember({"scene", "all"}));
    cmd->add_flag("-q,--quiet", args->quiet, "No progress, statistics or warnings");
    cmd->add_flag("--no-progress", args->noProgress,
                  "No progress display (statistics and warnings stay)");
    cmd->add_option("--target-error", args->targetError,
                    "Choose spp, cutoff and light samples by a pilot study to reach this "
                    "relative RMSE against a reference (docs/ACCURACY.md)")
        ->check(CLI::Range(1e-6, 1e6));
    cmd->add_option("--time-limit", args->timeLimit,
                    "Render in progressive passes until S seconds have passed since the start "
                    "(loading included), or --spp samples are reached if given; a pass the "
                    "deadline cuts off is dropped, and if none finished nothing is written "
                    "(exit 1)")
        ->check(CLI::Range(1e-3, 1e9));
    cmd->add_flag("--stats", args->stats,
                  "Also print the image's noise: its relative standard error, estimated from "
                  "each pixel's even and odd samples");
    cmd->add_flag("--verify", args->verify,
                  "With --target-error: render a reference too and report the error reached");
    CLI::Option *exposure =
        cmd->add_option("--exposure", args->exposureText,
                        "Exposure in EV: every output is scaled by 2^EV; auto: the EV that maps "
                        "the image's log-average luminance to 0.18 (default: the Film's "
                        "\"exposure\", else auto for 8-bit outputs of OBJ, glTF and PLY scenes "
                        "lit by their own lights, else 0)")
            ->check(CheckExposureText);
    cmd->add_option("--tonemap", args->toneMap,
                    "Tone map of 8-bit outputs (PNG, JPEG, ...): none (clamp), neutral (Khronos "
                    "PBR Neutral), aces (Hill's ACES fit) or filmic (Hable); default: the Film's "
                    "\"tonemap\", else none for pbrt scenes and neutral for OBJ, glTF and PLY. "
                    "EXR, PFM and HDR stay linear")
        ->check(CLI::IsMember({"none", "neutral", "aces", "filmic"}));
    cmd->add_option("--env", args->env,
                    "Environment light: an equirectangular FILE.exr|hdr (importance-sampled) or a "
                    "uniform radiance R,G,B");
    CLI::Option *envRotate = cmd->add_option(
        "--env-rotate", args->envRotate,
        "Turn the --env map by DEG about the up axis (counterclockwise seen from above)");
    cmd->add_option("--env-mode", args->envMode,
                    "replace (default: the scene's light sources and the studio rig are dropped) "
                    "or add (the environment joins them)")
        ->check(CLI::IsMember({"replace", "add"}));
    cmd->add_option("--aov", args->aov,
                    "Write AOV layers beside RGB into the .exr output: all, or a list of depth, "
                    "P, N, Ng, albedo, uv, shape_id, primitive_id, instance_id, material_id, "
                    "direct, indirect, variance (default: the Film's \"aovs\")");
    return [args, spp, cutoff, lightSamples, exposure, envRotate] {
        args->exposureGiven = exposure->count() > 0;
        if (args->exposureGiven)  // checked by CheckExposureText
            ParseExposure(args->exposureText, &args->exposure, &args->exposureAuto);
        args->envRotateGiven = envRotate->count() > 0;
        args->sppGiven = spp->count() > 0;
        args->cutoffGiven = cutoff->count() > 0;
        args->lightSamplesGiven = lightSamples->count() > 0;
    };
}

void AddRenderCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App *cmd = app.add_subcommand(
        "render", "Render a scene (.pbrt, .obj, .gltf, .glb, .ply, .stl) to an image");
    std::function<void()> recordGiven = AddRenderOptions(cmd, args.get());
    cmd->callback([args, exitCode, recordGiven] {
        recordGiven();
        *exitCode = RunGuarded([&] { return RunRender(*args); });
    });
}

int RenderDefaultScene() {
    RenderArgs a;
    a.scene = FindDefaultScene();
    a.output = "whitted.png";
    return RunGuarded([&] { return RunRender(a); });
}

}  // namespace prism
