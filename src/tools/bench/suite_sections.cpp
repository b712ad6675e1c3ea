// The measurements of `prism bench suite`, one function per section of the report.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "tools/bench/ceiling.h"
#include "tools/bench/knot.h"
#include "tools/bench/process.h"
#include "tools/bench/suite_internal.h"

namespace prism {

namespace {

namespace fs = std::filesystem;

void Progress(const std::string &s) { std::fprintf(stderr, "bench: %s\n", s.c_str()); }

std::string Ms(double s) { return fmt::format("{:.1f} ms", s * 1e3); }
std::string Sec(double s) { return fmt::format("{:.3f} s", s); }

// A `prism render` child; throws when it fails.
ChildRun RunPrism(const SuiteContext &ctx, const std::vector<std::string> &args) {
    std::vector<std::string> argv{ctx.prism};
    argv.insert(argv.end(), args.begin(), args.end());
    ChildRun r = RunChild(argv);
    if (r.exitStatus != 0)
        throw std::runtime_error(
            fmt::format("`{}` failed (exit {}): {}", fmt::join(argv, " "), r.exitStatus, r.err));
    return r;
}

std::vector<std::string> PrismWhittedArgs(const SuiteContext &ctx, int spp, int threads) {
    return {"render",       ctx.whittedScene,
            "-o",           ctx.tmp + "/whitted_prism.png",
            "--res",        ctx.povRes,
            "--spp",        std::to_string(spp),
            "--threads",    std::to_string(threads),
            "--no-progress"};
}

}  // namespace

void MeasureCeilingSection(SuiteContext &ctx) {
    int w = ctx.options.quick ? 800 : 1600, h = ctx.options.quick ? 600 : 1200;
    Progress(fmt::format("knot ceiling at {}x{}", w, h));
    KnotFiles kf = WriteKnotScene(ctx.tmp + "/knot", 2000, 100, false);
    CeilingOptions co;
    co.scene = kf.pbrt;
    co.width = w;
    co.height = h;
    co.spp = 1;
    co.repeats = ctx.ceilingRepeats;
    CeilingResult r = RunCeiling(co, stderr);
    ctx.markdown += fmt::format(
        "## Render kernel against Embree's ceiling\n\n"
        "Knot (nu 2000, nv 100: {} triangles), {}x{}, 1 spp, matte, one point light, {} threads; "
        "median of {} interleaved repeats (`prism bench ceiling`). The ceiling traces the same "
        "camera rays (the render's 16-ray packets of 4x4 pixels) and one shadow ray per hit "
        "(rtcOccluded1, as the render) with no shading; "
        "{:.0f}% of the camera rays hit.\n\n"
        "| ceiling | render | ratio render/ceiling |\n|---|---|---|\n"
        "| {:.2f} Mrays/s | {:.2f} Mrays/s | {:.2f} |\n\n",
        kf.triangles, r.width, r.height, r.threads, r.repeats.size(), 100 * r.hitFraction,
        r.ceilingMrays, r.renderMrays, r.Ratio());
    ctx.Add("ceiling", "knot ceiling", r.ceilingMrays, "Mrays/s");
    ctx.Add("ceiling", "knot render", r.renderMrays, "Mrays/s");
    ctx.Add("ceiling", "knot ratio render/ceiling", r.Ratio(), "", ">= 0.75");
}

void MeasurePovRaySection(SuiteContext &ctx) {
    ctx.markdown +=
        fmt::format("## Against POV-Ray 3.7 (Whitted scene, {}, depth 5)\n\n", ctx.povRes);
    std::string pbrt = ctx.sharedDir + "/peers/whitted.pbrt",
                pov = ctx.sharedDir + "/peers/whitted.pov";
    if (!OnPath("povray") || !fs::exists(pbrt) || !fs::exists(pov)) {
        ctx.markdown += fmt::format("Skipped: {}.\n\n", !OnPath("povray")
                                                            ? "`povray` is not on PATH"
                                                            : pbrt + " or whitted.pov is missing");
        return;
    }
    std::string dir = ctx.tmp + "/pov";
    fs::create_directories(dir);
    fs::copy_file(pbrt, dir + "/whitted.pbrt", fs::copy_options::overwrite_existing);
    fs::copy_file(pov, dir + "/whitted.pov", fs::copy_options::overwrite_existing);
    ctx.whittedScene = dir + "/whitted.pbrt";
    ctx.markdown += fmt::format(
        "../shared/peers/whitted.pbrt against whitted.pov, medians of {} interleaved runs "
        "(Prism, POV-Ray, Prism, ...). Whole process: wall time of the child from spawn to exit. "
        "Render phase: Prism's `render` time against POV-Ray's Trace Time. Without anti-aliasing: "
        "Prism `--spp 1`, POV-Ray `-A`; with: Prism `--spp 4`, POV-Ray `+A0.0 +AM2 +R2`. "
        "Speed-up = POV-Ray time / Prism time.\n\n"
        "| anti-aliasing | threads | Prism whole | POV-Ray whole | speed-up | Prism render | "
        "POV-Ray Trace Time | speed-up |\n|---|---|---|---|---|---|---|---|\n",
        ctx.povRuns);
    for (bool aa : {false, true}) {
        for (int threads : {1, 2}) {
            Progress(
                fmt::format("POV-Ray comparison, {}, {} thread(s)", aa ? "AA" : "no AA", threads));
            std::vector<double> pw, vw, pr, vt;
            for (int i = 0; i < ctx.povRuns; ++i) {
                ChildRun p = RunPrism(ctx, PrismWhittedArgs(ctx, aa ? 4 : 1, threads));
                PrismRenderStats ps = ParsePrismStats(p.err);
                std::string w = ctx.povRes.substr(0, ctx.povRes.find('x'));
                std::string h = ctx.povRes.substr(ctx.povRes.find('x') + 1);
                std::vector<std::string> argv{"povray", "-D", "+W" + w, "+H" + h, "+FN"};
                if (aa) {
                    argv.insert(argv.end(), {"+A0.0", "+AM2", "+R2"});
                } else {
                    argv.push_back("-A");
                }
                argv.insert(argv.end(), {"+WT" + std::to_string(threads), "+Iwhitted.pov",
                                         "+O" + dir + "/whitted_pov.png"});
                ChildRun v = RunChild(argv, dir);
                double trace = ParsePovTime(v.err, "Trace Time");
                if (v.exitStatus != 0 || trace < 0 || ps.render < 0)
                    throw std::runtime_error("POV-Ray or Prism run failed: " +
                                             v.err.substr(0, 2000));
                pw.push_back(p.wallSeconds);
                vw.push_back(v.wallSeconds);
                pr.push_back(ps.render);
                vt.push_back(trace);
            }
            double spw = Median(vw) / Median(pw), spr = Median(vt) / Median(pr);
            ctx.markdown +=
                fmt::format("| {} | {} | {} | {} | {:.2f}x | {} | {} | {:.2f}x |\n",
                            aa ? "4 spp / +A0.0 +AM2" : "none", threads, Sec(Median(pw)),
                            Sec(Median(vw)), spw, Sec(Median(pr)), Sec(Median(vt)), spr);
            std::string key = fmt::format("whitted {} {}T", aa ? "aa" : "noaa", threads);
            ctx.Add("povray", key + " prism whole", Median(pw), "s");
            ctx.Add("povray", key + " povray whole", Median(vw), "s");
            ctx.Add("povray", key + " whole speed-up", spw, "x", threads == 2 ? ">= 4" : "");
            ctx.Add("povray", key + " prism render", Median(pr), "s");
            ctx.Add("povray", key + " povray trace", Median(vt), "s");
            ctx.Add("povray", key + " render speed-up", spr, "x", threads == 2 ? ">= 2" : "");
        }
    }
    ctx.markdown += "\n";
}

void MeasureThreadScalingSection(SuiteContext &ctx) {
    if (ctx.whittedScene.empty()) {
        std::string shared = ctx.sharedDir + "/peers/whitted.pbrt";
        ctx.whittedScene = fs::exists(shared) ? shared : ctx.sourceDir + "/scenes/whitted.pbrt";
    }
    // Prism's runs alone, every thread count interleaved: the runs of the POV-Ray comparison
    // were used before, but each follows a POV-Ray run, and their 2-thread rates moved with
    // it (1.68 to 1.93 between suite runs of one kernel). The counts are 1, 2, 4, ... up to
    // the machine's (and the machine's own count), so the section runs unchanged on a larger
    // machine.
    Progress("thread scaling");
    const int cores = std::max(1, int(std::thread::hardware_concurrency()));
    std::vector<int> counts{1};
    while (counts.back() * 2 <= cores) counts.push_back(counts.back() * 2);
    if (counts.back() != cores) counts.push_back(cores);
    std::vector<std::vector<double>> rates(counts.size());
    for (int i = 0; i < ctx.scalingRuns; ++i)
        for (size_t k = 0; k < counts.size(); ++k) {
            ChildRun p = RunPrism(ctx, PrismWhittedArgs(ctx, 1, counts[k]));
            rates[k].push_back(ParsePrismStats(p.err).mrays);
        }
    ctx.whittedMrays1 = rates[0];
    ctx.whittedMrays2 = counts.size() > 1 ? rates[1] : std::vector<double>{};
    const double r1 = Median(rates[0]);
    std::string header = "| |", rule = "|---|", rateRow = "| render-phase rays |",
                ratioRow = "| to 1 thread |";
    for (size_t k = 0; k < counts.size(); ++k) {
        const double r = Median(rates[k]);
        header += fmt::format(" {} thread{} |", counts[k], counts[k] == 1 ? "" : "s");
        rule += "---|";
        rateRow += fmt::format(" {:.2f} Mrays/s |", r);
        ratioRow += fmt::format(" {:.2f} |", r1 > 0 ? r / r1 : 0);
        ctx.Add("threads", fmt::format("whitted render {}T", counts[k]), r, "Mrays/s");
        if (k > 0)
            ctx.Add("threads", fmt::format("whitted {}T/1T", counts[k]), r1 > 0 ? r / r1 : 0, "",
                    counts[k] == 2 ? ">= 1.9" : "");
    }
    ctx.markdown += fmt::format(
        "## Thread scaling (render phase)\n\n{} at {}, 1 spp: render-phase ray rate, median "
        "of {} runs of each, the thread counts interleaved (Prism only; {} cores).\n\n"
        "{}\n{}\n{}\n{}\n\n",
        fs::path(ctx.whittedScene).filename().string(), ctx.povRes, rates[0].size(), cores, header,
        rule, rateRow, ratioRow);
}

void MeasureStartupSection(SuiteContext &ctx) {
    Progress("start-up");
    std::string scene = ctx.sourceDir + "/scenes/whitted.pbrt";
    std::vector<double> help, tiny;
    for (int i = 0; i < ctx.startupRuns; ++i) {
        help.push_back(RunPrism(ctx, {"--help"}).wallSeconds);
        tiny.push_back(
            RunPrism(ctx, {"render", scene, "--res", "8x6", "-o", ctx.tmp + "/tiny.png", "--quiet"})
                .wallSeconds);
    }
    ctx.markdown += fmt::format(
        "## Start-up (whole process, median of {})\n\n| `prism --help` | `prism render "
        "scenes/whitted.pbrt --res 8x6` |\n|---|---|\n| {} | {} |\n\n",
        ctx.startupRuns, Ms(Median(help)), Ms(Median(tiny)));
    ctx.Add("startup", "prism --help", Median(help) * 1e3, "ms", "< 30");
    ctx.Add("startup", "render whitted 8x6", Median(tiny) * 1e3, "ms", "< 30");
}

void MeasureMemorySection(SuiteContext &ctx) {
    Progress("1M-triangle load, BVH and memory");
    // The mesh is generated by a child: this process must stay small, because a spawned
    // child's ru_maxrss includes the spawning process's peak RSS at exec (Linux's exec_mmap
    // records the old mm's high-water mark), which RunSuite keeps low by measuring this first.
    std::string dir = ctx.tmp + "/big";
    RunPrism(ctx, {"bench", "knot", dir, "--nu", "5000", "--nv", "100"});
    KnotFiles kf;
    kf.pbrt = dir + "/knot.pbrt";
    kf.triangles = size_t(5000) * 100 * 2 + 2;
    std::string empty = WriteEmptyScene(dir);
    std::vector<double> load, bvh, rssKnot, rssEmpty;
    for (int i = 0; i < ctx.memoryRuns; ++i) {
        for (bool isKnot : {false, true}) {
            ChildRun r = RunPrism(ctx, {"render", isKnot ? kf.pbrt : empty, "--res", "8x6", "-o",
                                        ctx.tmp + "/big.png", "--no-progress"});
            if (!isKnot) {
                rssEmpty.push_back(double(r.maxRssKiB));
                continue;
            }
            PrismRenderStats s = ParsePrismStats(r.err);
            rssKnot.push_back(double(r.maxRssKiB));
            load.push_back(s.parse + s.setup);
            bvh.push_back(s.bvh);
        }
    }
    double extra = (Median(rssKnot) - Median(rssEmpty)) * 1024.0;
    double perTri = extra / double(kf.triangles);
    ctx.markdown += fmt::format(
        "## Large mesh: {} triangles (knot nu 5000 nv 100, binary PLY)\n\n`prism render` at 8x6, "
        "median of {}; peak RSS (ru_maxrss of each child) above the same render of an empty "
        "scene.\n\n| load (parse + setup) | BVH build | peak RSS | empty-scene RSS | bytes per "
        "triangle |\n|---|---|---|---|---|\n| {} | {} | {:.1f} MiB | {:.1f} MiB | {:.1f} |\n\n",
        kf.triangles, ctx.memoryRuns, Sec(Median(load)), Sec(Median(bvh)), Median(rssKnot) / 1024,
        Median(rssEmpty) / 1024, perTri);
    ctx.Add("memory", "1M load", Median(load), "s");
    ctx.Add("memory", "1M BVH build", Median(bvh), "s");
    ctx.Add("memory", "1M peak RSS", Median(rssKnot) / 1024, "MiB");
    ctx.Add("memory", "empty peak RSS", Median(rssEmpty) / 1024, "MiB");
    ctx.Add("memory", "bytes per triangle", perTri, "B", "<= 100");
}

// `prism batch` over ../shared/scenes: its wall time against the sum of the render phases its
// children report (report.json), i.e. what the batch costs beyond rendering. Skipped by --quick
// (the scenes render at their own resolutions: a few minutes).
void MeasureBatchSection(SuiteContext &ctx) {
    ctx.markdown += "## `prism batch` over ../shared/scenes\n\n";
    std::string scenes = ctx.sharedDir + "/scenes";
    if (ctx.options.quick || !fs::is_directory(scenes)) {
        ctx.markdown += ctx.options.quick ? "Skipped by --quick.\n\n"
                                          : "Skipped: " + scenes + " not found.\n\n";
        return;
    }
    Progress("batch over " + scenes);
    std::string out = ctx.tmp + "/batch";
    ChildRun r = RunChild({ctx.prism, "batch", scenes, "-o", out, "--force", "--quiet"});
    std::string report;
    std::FILE *f = std::fopen((out + "/report.json").c_str(), "r");
    if (f) {
        char buf[4096];
        size_t n;
        while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) report.append(buf, n);
        std::fclose(f);
    }
    double wall = 0, render = 0;
    size_t k = report.find("\"wall_seconds\": ");
    if (k != std::string::npos)
        std::sscanf(report.c_str() + k, "\"wall_seconds\": %lf, \"render_seconds\": %lf", &wall,
                    &render);
    int ok = 0;
    for (size_t p = report.find("\"status\": \"ok\""); p != std::string::npos;
         p = report.find("\"status\": \"ok\"", p + 1))
        ++ok;
    double ratio = render > 0 ? wall / render : 0;
    ctx.markdown += fmt::format(
        "`prism batch {} -o OUT --force` (one scene at a time, each with every core; exit {}): "
        "{} scenes rendered.\n\n| batch wall time | sum of render phases | ratio |\n|---|---|---|\n"
        "| {} | {} | {:.3f} |\n\n",
        scenes, r.exitStatus, ok, Sec(wall), Sec(render), ratio);
    ctx.Add("batch", "batch wall time", wall, "s");
    ctx.Add("batch", "sum of render phases", render, "s");
    ctx.Add("batch", "batch wall / render phases", ratio, "", "<= 1.10");
}

}  // namespace prism
