// prism bench: ceiling (render against Embree's traversal rate), compare (equal-error time
// against pbrt-v3 and pbrt-v4), knot (the benchmark scene), suite (the whole performance table
// as Markdown). The work lives in src/tools/bench.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "app/commands.h"
#include "app/common.h"
#include "tools/bench/ceiling.h"
#include "tools/bench/compare.h"
#include "tools/bench/knot.h"
#include "tools/bench/suite.h"

namespace prism {

namespace {

struct BenchArgs {
    std::string scene, res, traversal = "packet", outDir;
    int threads = 0, repeats = 3, spp = 0;
    int nu = 2000, nv = 100;
    bool pov = false, quick = false;
    // compare
    std::vector<std::string> against, only;
    std::string reference, sppList;
    double targetError = 0;
    int referenceSpp = 0, targetSpp = 0;
    bool ownReference = false;
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

// --against NAME=PATH: pbrt-v3 or pbrt-v4, an executable.
CompareRenderer ParseAgainst(const std::string &spec) {
    const size_t eq = spec.find('=');
    const std::string name = spec.substr(0, eq);
    if (eq == std::string::npos || (name != "pbrt-v3" && name != "pbrt-v4"))
        throw UsageError("--against takes pbrt-v3=PATH or pbrt-v4=PATH, not \"" + spec + "\"");
    CompareRenderer r;
    r.name = name;
    r.kind = name == "pbrt-v3" ? CompareKind::PbrtV3 : CompareKind::PbrtV4;
    r.path = std::filesystem::absolute(spec.substr(eq + 1)).string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(r.path, ec) || access(r.path.c_str(), X_OK) != 0)
        throw UsageError("--against " + name + ": \"" + spec.substr(eq + 1) +
                         "\" is not an executable file");
    return r;
}

// --spp "4,8,16": the ladder, each count from 1 to 2^16.
std::vector<int> ParseSppList(const std::string &s) {
    std::vector<int> out;
    size_t pos = 0;
    while (pos <= s.size()) {
        size_t comma = s.find(',', pos);
        if (comma == std::string::npos) comma = s.size();
        const std::string item = s.substr(pos, comma - pos);
        char *end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < 1 || v > (1 << 16))
            throw UsageError("--spp takes counts from 1 to 65536 separated by commas, not \"" + s +
                             "\"");
        out.push_back(int(v));
        pos = comma + 1;
    }
    return out;
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

    CLI::App *cmp = bench->add_subcommand(
        "compare",
        "Time to equal error: render SCENE with Prism and each --against renderer at a ladder "
        "of sample counts, fit error against CPU time, print each one's time to the target");
    cmp->add_option("scene", args->scene, "Scene file")->required();
    cmp->add_option("--against", args->against,
                    "A reference renderer, pbrt-v3=PATH or pbrt-v4=PATH (repeatable; the first "
                    "renders the reference image)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmp->add_option("--threads", args->threads, "Threads of every renderer (default 1)")
        ->check(CLI::Range(1, 4096));
    cmp->add_option("--target-error", args->targetError,
                    "Relative RMSE to reach (default: the first reference renderer's at the "
                    "scene's own spp)")
        ->check(CLI::PositiveNumber);
    cmp->add_flag("--own-reference", args->ownReference,
                  "Measure each renderer against its own --reference-spp image (noise alone; "
                  "the references' differences are printed)");
    cmp->add_option("--target-spp", args->targetSpp,
                    "The count whose error is the default target (default: the file's)")
        ->check(CLI::Range(1, 1 << 16));
    cmp->add_option("--out", args->outDir,
                    "Keep compare.csv, fit.csv, compare.png and the images here");
    cmp->add_option("--reference", args->reference,
                    "A converged image to measure against (default: rendered)")
        ->check(CLI::ExistingFile);
    cmp->add_option("--reference-spp", args->referenceSpp,
                    "Samples per pixel of the rendered reference (default 8 x the ladder's top)")
        ->check(CLI::Range(1, 1 << 20));
    cmp->add_option("--spp", args->sppList,
                    "The ladder, e.g. 4,8,16 (default: the scene's spp /8 /4 /2 x1 x2)");
    cmp->add_option("--repeats", args->repeats, "Interleaved repeats (medians reported)")
        ->check(CLI::Range(1, 1000));
    cmp->add_option("--res", args->res,
                    "Every renderer's image size WxH (default: the file's; pbrt gets its Film "
                    "rewritten)");
    cmp->callback([args, exitCode] {
        *exitCode = RunGuarded([&] {
            CompareOptions o;
            o.scene = args->scene;
            for (const std::string &a : args->against) o.against.push_back(ParseAgainst(a));
            o.threads = args->threads > 0 ? args->threads : 1;
            o.targetError = args->targetError;
            o.outDir = args->outDir;
            if (!o.outDir.empty() && std::filesystem::exists(o.outDir))
                CheckWritableDirectory(o.outDir);
            o.reference = args->reference;
            o.referenceSpp = args->referenceSpp;
            o.targetSpp = args->targetSpp;
            o.ownReference = args->ownReference;
            if (!args->sppList.empty()) o.spp = ParseSppList(args->sppList);
            o.repeats = args->repeats;
            if (!args->res.empty()) {
                const Vec2i r = ParseResolution(args->res);
                o.width = r.x;
                o.height = r.y;
            }
            o.commandLine = CommandLine();
            o.sourceDir = PRISM_SOURCE_DIR;
            return RunCompare(o, stdout);
        });
    });

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
    suite
        ->add_option("--only", args->only,
                     "Run only these sections: ceiling, povray, threads, startup, memory, "
                     "batch, equal-error (repeatable)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(CLI::IsMember(SuiteSectionNames()));
    suite->callback([args, exitCode] {
        *exitCode = RunGuarded([&] {
            SuiteOptions o;
            o.quick = args->quick;
            o.only = args->only;
            o.outDir = args->outDir;
            o.commandLine = CommandLine();
            return RunSuite(o);
        });
    });
}

}  // namespace prism
