// prism bench: ceiling (render against Embree's traversal rate), knot (the benchmark scene),
// suite (the whole performance table as Markdown). The work lives in src/tools/bench.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <memory>

#include "app/commands.h"
#include "app/common.h"
#include "tools/bench/ceiling.h"
#include "tools/bench/knot.h"
#include "tools/bench/suite.h"

namespace prism {

namespace {

struct BenchArgs {
    std::string scene, res, traversal = "packet", outDir;
    int threads = 0, repeats = 3, spp = 0;
    int nu = 2000, nv = 100;
    bool pov = false, quick = false;
};

int RunCeilingCommand(const BenchArgs &a) {
    CeilingOptions o;
    o.scene = a.scene;
    if (!a.res.empty()) {
        Vec2i r = ParseResolution(a.res);
        o.width = r.x;
        o.height = r.y;
    }
    o.threads = a.threads;
    o.repeats = a.repeats;
    o.spp = a.spp;
    if (a.traversal == "single")
        o.traversal = CeilingTraversal::Single;
    else if (a.traversal == "packet")
        o.traversal = CeilingTraversal::Packet16;
    else
        throw UsageError("--traversal must be single or packet, not " + a.traversal);
    CeilingResult r = RunCeiling(o, stdout);
    std::printf("%s\n", CeilingSummary(r).c_str());
    return ExitOk;
}

int RunKnotCommand(const BenchArgs &a) {
    KnotFiles kf = WriteKnotScene(a.outDir, a.nu, a.nv, a.pov);
    std::printf(
        "knot: %zu vertices, %zu triangles (with the 2 ground triangles)\nwrote %s, %s%s%s\n",
        kf.vertices, kf.triangles, kf.pbrt.c_str(), kf.ply.c_str(),
        a.pov ? (", " + kf.pov).c_str() : "", a.pov ? (", " + kf.povInclude).c_str() : "");
    return ExitOk;
}

// The command line as typed, for the report.
std::string CommandLine() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::string s, arg;
    while (std::getline(in, arg, '\0')) s += (s.empty() ? "" : " ") + arg;
    return s.empty() ? "prism bench suite" : s;
}

}  // namespace

void AddBenchCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<BenchArgs>();
    CLI::App *bench =
        app.add_subcommand("bench", "Performance benchmarks (see docs/BENCHMARKS.md)");
    bench->require_subcommand(1);

    CLI::App *ceil = bench->add_subcommand(
        "ceiling",
        "Render SCENE, then trace the same camera rays and one shadow ray per hit "
        "and light through Embree with no shading; print both ray rates");
    ceil->add_option("scene", args->scene, "Scene file")->required();
    ceil->add_option("--res", args->res, "Resolution WxH (overrides the Film)");
    ceil->add_option("--threads", args->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    ceil->add_option("--repeats", args->repeats, "Interleaved repeats (medians reported)")
        ->check(CLI::Range(1, 1000));
    ceil->add_option("--spp", args->spp, "Samples per pixel (overrides the Sampler)")
        ->check(CLI::Range(1, 1 << 16));
    ceil->add_option("--traversal", args->traversal,
                     "Ceiling camera rays: packet (16-ray packets, default) or single");
    ceil->callback(
        [args, exitCode] { *exitCode = RunGuarded([&] { return RunCeilingCommand(*args); }); });

    CLI::App *knot = bench->add_subcommand(
        "knot",
        "Write the knot benchmark scene (knot.pbrt + knot.ply; like ../shared/peers/gen_knot.py)");
    knot->add_option("outdir", args->outDir, "Output directory")->required();
    knot->add_option("--nu", args->nu, "Segments along the knot")->check(CLI::Range(3, 1 << 20));
    knot->add_option("--nv", args->nv, "Segments around the tube")->check(CLI::Range(3, 1 << 16));
    knot->add_flag("--pov", args->pov, "Also write knot.pov + knot_mesh.inc for POV-Ray");
    knot->callback(
        [args, exitCode] { *exitCode = RunGuarded([&] { return RunKnotCommand(*args); }); });

    CLI::App *suite = bench->add_subcommand(
        "suite",
        "The performance table of issue 10 as Markdown (ceiling, POV-Ray, threads, "
        "start-up, memory)");
    suite->add_flag("--quick", args->quick, "Smaller images, fewer runs (well under a minute)");
    suite->add_option("--out", args->outDir, "Also write results.csv, report.md and plots here");
    suite->callback([args, exitCode] {
        *exitCode = RunGuarded([&] {
            SuiteOptions o;
            o.quick = args->quick;
            o.outDir = args->outDir;
            o.commandLine = CommandLine();
            return RunSuite(o);
        });
    });
}

}  // namespace prism
