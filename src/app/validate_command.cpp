// `prism validate [SCENE | --shape NAME|all] [--levels 8,16,...] [--rays N] [--seed S]
// [--out DIR] [--precision float|double]`: each analytic intersector against Embree triangles
// on its tessellated twins (docs/SHAPES.md). Exit status 3 when a disagreement lies
// outside the chord-error band, 4 when only a convergence slope is off (of mean |dt| or of the
// shading-normal error).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/commands.h"
#include "app/common.h"
#include "assembly/build_scene.h"
#include "assembly/shape_factory.h"
#include "core/file_io.h"
#include "core/output_file.h"
#include "image/image.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "tools/validate/tessellate.h"
#include "tools/validate/validate.h"

namespace prism {

namespace {

struct ValidateArgs {
    std::string scene, shape, levels = "8,16,32,64,128,256,512,1024", out = "validation";
    std::string precision = "double", python = "/usr/bin/python3", plotScript;
    int rays = 100000, imageLevel = 32, cameraRays = 65536;
    uint64_t seed = 1;
    bool quiet = false;
    std::string maxMemory;
    ConfineOption confine;
};

// Pixel-centre rays of the scene camera on a grid of at most `budget` rays.
std::vector<Ray> CameraRays(const RenderScene &scene, int budget, Vec2i *grid) {
    Vec2i res = scene.resolution;
    double scale = std::min(1.0, std::sqrt(double(budget) / (double(res.x) * res.y)));
    grid->x = std::max(1, int(res.x * scale));
    grid->y = std::max(1, int(res.y * scale));
    std::vector<Ray> rays;
    for (int y = 0; y < grid->y; ++y)
        for (int x = 0; x < grid->x; ++x) {
            Vec2f pFilm(float((x + 0.5) * res.x / grid->x), float((y + 0.5) * res.y / grid->y));
            rays.push_back(scene.camera->GenerateRay(pFilm, Vec2f(0.5f, 0.5f)));
        }
    return rays;
}

// Side by side: analytic | tessellated, and a heat map of the first-hit depth difference.
void WriteSceneImages(const SceneDescription &desc, const BuildSettings &base, int level,
                      const std::string &dir, Diagnostics &diag, bool quiet) {
    BuildSettings oa = base, ot = base;
    ot.replaceAnalyticShape = TessellateWith(level);
    RenderScene sa = BuildRenderScene(desc, oa, diag), st = BuildRenderScene(desc, ot, diag);
    RenderStats stats;
    Image ia = Render(sa, &stats), it = Render(st, &stats);
    Image both(ia.width * 2, ia.height, 3);
    for (int y = 0; y < ia.height; ++y)
        for (int x = 0; x < ia.width; ++x) {
            both.SetRGB(x, y, ia.GetRGB(x, y));
            both.SetRGB(x + ia.width, y, it.GetRGB(x, y));
        }
    WriteImage(dir + "/scene_side_by_side.png", both);
    // Depth difference per pixel centre, on a log colour scale from 1e-7 to 1e-1 of the
    // scene's depth; pixels where only one side hits are magenta.
    Image heat(sa.resolution.x, sa.resolution.y, 3);
    double maxLog = -1, minLog = -7;
    for (int y = 0; y < heat.height; ++y)
        for (int x = 0; x < heat.width; ++x) {
            Ray r = sa.camera->GenerateRay(Vec2f(x + 0.5f, y + 0.5f), Vec2f(0.5f, 0.5f));
            RawHit ha, ht;
            bool a = sa.accel->IntersectRaw(r, &ha), t = st.accel->IntersectRaw(r, &ht);
            RGB c(0.f);
            if (a != t) {
                c = RGB(1, 0, 1);
            } else if (a) {
                double rel = std::abs(double(ht.t) - double(ha.t)) / std::max(double(ha.t), 1e-30);
                double u =
                    rel > 0 ? Clamp((std::log10(rel) - minLog) / (maxLog - minLog), 0.0, 1.0) : 0;
                // Blue (agreement) to red (large difference) through yellow.
                c = u < 0.5 ? RGB(float(2 * u), float(2 * u), float(1 - 2 * u))
                            : RGB(1, float(2 - 2 * u), 0);
            }
            heat.SetRGB(x, y, c);
        }
    WriteImage(dir + "/scene_depth_diff.png", heat);
    if (!quiet)
        std::printf(
            "wrote %s/scene_side_by_side.png (analytic | tessellated n=%d) and "
            "%s/scene_depth_diff.png (log10 relative depth difference, -7 blue to -1 "
            "red; magenta: hit/miss)\n",
            dir.c_str(), level, dir.c_str());
}

int RunValidate(const ValidateArgs &a) {
    ValidateOptions opt;
    opt.levels = ParseLevels(a.levels);
    opt.rays = a.rays;
    opt.seed = a.seed;
    opt.precision = ParsePrecision(a.precision);
    if (!a.scene.empty() && !a.shape.empty()) throw UsageError("give a scene or --shape, not both");
    std::filesystem::create_directories(a.out);
    std::vector<ShapeReport> reports;
    auto report = [&](ShapeReport r) {
        std::printf("%s", FormatReport(r).c_str());
        std::fflush(stdout);
        reports.push_back(std::move(r));
    };

    if (a.scene.empty()) {
        std::vector<std::string> names;
        if (a.shape.empty() || a.shape == "all")
            names = CanonicalShapeNames();
        else
            names.push_back(a.shape);
        for (const std::string &n : names) {
            std::unique_ptr<AnalyticShape> s = MakeCanonicalShape(n);
            if (!s) {
                std::string all;
                for (const std::string &c : CanonicalShapeNames()) all += " " + c;
                throw UsageError("unknown shape \"" + n + "\" (known:" + all + ", all)");
            }
            report(ValidateShape(n, std::move(s), {}, opt));
        }
    } else {
        ScopedReadConfinement confined(ConfinementFolderFor(a.confine, a.scene));
        Diagnostics diag(!a.quiet);
        // One budget (--max-memory) for the scene and the three renders of it, which are alive
        // together.
        MemoryBudget budget(ParseMaxMemory(a.maxMemory));
        LoadOptions loadOpts;
        loadOpts.budget = &budget;
        SceneDescription desc = LoadScene(a.scene, diag, loadOpts);
        BuildSettings ro;
        ro.precision = opt.precision;
        ro.budget = &budget;
        RenderScene scene = BuildRenderScene(desc, ro, diag);
        Vec2i grid;
        std::vector<Ray> cam = CameraRays(scene, a.cameraRays, &grid);
        std::printf("%s: %zu camera rays (%dx%d grid) per shape on top of %d random rays\n",
                    a.scene.c_str(), cam.size(), grid.x, grid.y, opt.rays);
        ShapeFactoryContext ctx{desc, diag, opt.precision, &budget};
        int analyticCount = 0;
        for (const ShapeDesc &s : desc.shapes) {
            uint64_t usedBefore = budget.Used();
            ShapeGeometry g =
                CreateShapeGeometry(s, scene.renderFromWorld * s.worldFromObject, ctx);
            g.mesh.reset();  // only analytic shapes are validated
            budget.Release(budget.Used() - usedBefore);
            if (!g.analytic) continue;
            ++analyticCount;
            std::string name = "shape" + std::to_string(s.directiveIndex) + ":" + s.type;
            report(ValidateShape(name, std::move(g.analytic), cam, opt));
        }
        if (!desc.objects.empty())
            std::printf("note: shapes inside ObjectBegin/ObjectEnd instances are not validated\n");
        if (analyticCount == 0) std::printf("the scene has no analytic shapes\n");
        WriteSceneImages(desc, ro, a.imageLevel, a.out, diag, a.quiet);
    }

    std::string csv = a.out + "/results.csv";
    WriteFileAtomically(csv, ResultsCsv(reports));
    std::printf("wrote %s\n", csv.c_str());
    // The plot is a convenience: a missing matplotlib warns, the CSV stands.
    std::string script = FindToolScript(a.plotScript, "tools/plot_validation.py");
    std::string cmd = ShellQuote(a.python) + " " + ShellQuote(script) + " " + ShellQuote(csv) +
                      " " + ShellQuote(a.out);
    int rc = std::system(cmd.c_str());
    if (rc != 0)
        std::fprintf(stderr, "warning: plotting failed (%s); results.csv is complete\n",
                     cmd.c_str());
    int status = ValidationStatus(reports);
    if (status == ExitOutOfBand)
        std::printf("FAIL: disagreements outside the chord-error band (exit %d)\n", status);
    else if (status == ExitBadSlope)
        std::printf(
            "FAIL: a convergence slope is off: mean |dt| outside [-2.3, -1.7] or the "
            "shading-normal error falling slower than n^-1.7 (exit %d)\n",
            status);
    else
        std::printf("ok: every disagreement lies inside the chord-error band\n");
    return status;
}

}  // namespace

void AddValidateCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<ValidateArgs>();
    CLI::App *cmd = app.add_subcommand(
        "validate",
        "Cross-check the analytic intersectors against Embree triangles on their "
        "tessellations (exit 3: out-of-band disagreement, 4: bad convergence slope)");
    cmd->add_option("scene", args->scene, "Scene whose analytic shapes (and camera rays) to use");
    std::string shapeNames;
    for (const std::string &n : CanonicalShapeNames()) shapeNames += n + ", ";
    cmd->add_option("--shape", args->shape,
                    "Canonical shape: " + shapeNames + "or all (default without a scene)");
    cmd->add_option("--levels", args->levels, "Comma-separated segment counts around the axis");
    cmd->add_option("--rays", args->rays, "Random rays per shape")->check(CLI::Range(1, 100000000));
    cmd->add_option("--seed", args->seed, "Seed of the random rays");
    cmd->add_option("--out", args->out, "Output directory (results.csv, plots, scene images)");
    cmd->add_option("--precision", args->precision, "Arithmetic of the analytic intersectors")
        ->check(CLI::IsMember({"float", "double"}));
    cmd->add_option("--python", args->python, "Python with matplotlib for the plots");
    cmd->add_option("--plot-script", args->plotScript,
                    "Plot script (default tools/plot_validation.py)");
    cmd->add_option("--image-level", args->imageLevel, "Tessellation level of the scene renders")
        ->check(CLI::Range(3, 4096));
    cmd->add_option("--camera-rays", args->cameraRays, "Camera rays per shape (scene mode)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->add_flag("-q,--quiet", args->quiet, "No warnings");
    AddConfineOption(cmd, &args->confine);
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget, e.g. 512M or 8G (default: 75% of physical RAM); a scene that "
                    "needs more is refused");
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunValidate(*args); }); });
}

}  // namespace prism
