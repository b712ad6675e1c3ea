// `prism study SCENE [--knob NAME ...|all] [--res WxH] [--repeats N] [--threads N] [--out DIR]`:
// what each kind of accuracy costs in time on the scene (tools/study/study.h). Writes results.csv
// and report.md to DIR once every setting has run (nothing on bad input), then the plots through
// tools/plot_study.py when python3 with matplotlib is available.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/commands.h"
#include "app/common.h"
#include "core/memory.h"
#include "core/output_file.h"
#include "scene/load_scene.h"
#include "tools/study/study.h"
#include "tools/study/study_report.h"

namespace prism {

namespace {

struct StudyArgs {
    std::string scene, res, out = "study", maxMemory, levels = "8,16,32,64,128";
    std::string python, plotScript;  // python: empty tries python3, then /usr/bin/python3
    std::vector<std::string> knobs;
    int repeats = 3, threads = 0, spp = 0, refSpp = 256;
    bool quiet = false;
};

std::string KnownKnobs() {
    std::string s;
    for (StudyKnob k : AllStudyKnobs()) s += std::string(KnobName(k)) + ", ";
    return s + "all";
}

// --knob values, each possibly a comma-separated list; "all" (or none) is every knob.
std::vector<StudyKnob> ParseKnobs(const std::vector<std::string> &args) {
    std::vector<StudyKnob> knobs;
    for (const std::string &arg : args) {
        std::stringstream in(arg);
        std::string name;
        while (std::getline(in, name, ',')) {
            if (name == "all") {
                for (StudyKnob k : AllStudyKnobs()) knobs.push_back(k);
                continue;
            }
            std::optional<StudyKnob> k = ParseKnobName(name);
            if (!k)
                throw UsageError("--knob: unknown knob \"" + name + "\" (known: " + KnownKnobs() +
                                 ")");
            knobs.push_back(*k);
        }
    }
    return knobs;
}

// The plots are a convenience: without python3 and matplotlib the command warns and the CSV
// and report stand.
void WritePlots(const StudyArgs &a, const std::string &csv) {
    std::vector<std::string> candidates{a.python};
    if (a.python.empty()) candidates = {"python3", "/usr/bin/python3"};
    std::string python;
    for (const std::string &p : candidates) {
        std::string probe = ShellQuote(p) + " -c 'import matplotlib' >/dev/null 2>&1";
        if (std::system(probe.c_str()) == 0) {
            python = p;
            break;
        }
    }
    if (python.empty()) {
        std::fprintf(stderr,
                     "warning: no python3 with matplotlib (%s): plots skipped (results.csv and "
                     "report.md are complete)\n",
                     a.python.empty() ? "tried python3 and /usr/bin/python3" : a.python.c_str());
        return;
    }
    std::string cmd = ShellQuote(python) + " " +
                      ShellQuote(FindToolScript(a.plotScript, "tools/plot_study.py")) + " " +
                      ShellQuote(csv) + " " + ShellQuote(a.out);
    if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr,
                     "warning: plotting failed (%s); results.csv and report.md are complete\n",
                     cmd.c_str());
}

int RunStudyCommand(const StudyArgs &a) {
    namespace fs = std::filesystem;
    if (a.scene.empty()) {
        for (const std::string &k : a.knobs)
            if (!ParseKnobName(k) && k != "all")
                throw UsageError("no scene: \"" + k +
                                 "\" was read as a --knob; give the scene first: prism study "
                                 "SCENE --knob NAME ...");
        throw UsageError("a scene file is required: prism study SCENE [--knob NAME ...]");
    }
    StudyOptions opt;
    opt.knobs = ParseKnobs(a.knobs);
    if (!a.res.empty()) opt.resolution = ParseResolution(a.res);
    opt.repeats = a.repeats;
    opt.referenceSpp = a.refSpp;
    opt.baseSpp = a.spp;
    opt.tessellateLevels = ParseLevels(a.levels);
    opt.maxMemory = ParseMaxMemory(a.maxMemory);
    std::error_code ec;
    if (fs::exists(a.out, ec) && !fs::is_directory(a.out, ec))
        throw UsageError("--out \"" + a.out + "\" exists and is not a directory");

    std::unique_ptr<tbb::global_control> threadLimit;
    if (a.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(a.threads));

    Diagnostics diag(!a.quiet);
    MemoryBudget budget(opt.maxMemory);
    LoadOptions loadOpts;
    loadOpts.budget = &budget;
    SceneDescription desc = LoadScene(a.scene, diag, loadOpts);
    if (!a.quiet)
        std::fprintf(stderr, "study: reference render (%d spp), then the settings\n",
                     opt.referenceSpp);
    StudyProgress progress;
    if (!a.quiet)
        progress = [](int i, int n, const StudySetting &s) {
            std::fprintf(stderr, "study: setting %d of %d: %s = %s\n", i, n, KnobName(s.knob),
                         s.value.c_str());
        };
    StudyResult result = RunStudy(desc, a.scene, opt, diag, progress);
    for (const SkippedKnob &s : result.skipped)
        std::fprintf(stderr, "study: knob %s skipped: %s\n", KnobName(s.knob), s.reason.c_str());

    fs::create_directories(a.out);
    std::string csv = (fs::path(a.out) / "results.csv").string();
    std::string report = (fs::path(a.out) / "report.md").string();
    WriteFileAtomically(csv, StudyCsv(result.rows));
    WriteFileAtomically(report, StudyReport(result));
    for (const std::string &s : ParetoSentences(result)) std::printf("%s\n", s.c_str());
    std::printf("wrote %s and %s\n", csv.c_str(), report.c_str());
    std::fflush(stdout);
    if (!result.rows.empty()) WritePlots(a, csv);
    if (!a.quiet) std::fprintf(stderr, "study: %zu settings done\n", result.rows.size());
    return ExitOk;
}

}  // namespace

void AddStudyCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<StudyArgs>();
    CLI::App *cmd = app.add_subcommand(
        "study",
        "Measure what each accuracy knob costs in time: error against a reference render, "
        "results.csv, report.md and plots");
    // Not required by CLI11: `--knob` takes every word after it, so a scene given after the
    // knobs is read as a knob, and RunStudyCommand says so.
    cmd->add_option("scene", args->scene, "Scene file");
    cmd->add_option("--knob", args->knobs,
                    "Knobs to study (default all; names or comma-separated lists, after the "
                    "scene): " +
                        KnownKnobs())
        ->delimiter(',');
    cmd->add_option("--res", args->res, "Resolution WxH (overrides the Film)");
    cmd->add_option("--repeats", args->repeats, "Runs per setting; times are medians")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--out", args->out, "Output directory (results.csv, report.md, plots)");
    cmd->add_option("--spp", args->spp,
                    "Samples per pixel while the other knobs are swept (default: the scene's)")
        ->check(CLI::Range(1, 1 << 16));
    cmd->add_option("--ref-spp", args->refSpp, "Samples per pixel of the reference render")
        ->check(CLI::Range(1, 1 << 16));
    cmd->add_option("--levels", args->levels, "Segment counts of the tessellate knob");
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget, e.g. 512M or 8G (default: 75% of physical RAM)");
    cmd->add_option(
        "--python", args->python,
        "Python with matplotlib for the plots (default: python3, else /usr/bin/python3)");
    cmd->add_option("--plot-script", args->plotScript, "Plot script (default tools/plot_study.py)");
    cmd->add_flag("-q,--quiet", args->quiet, "No progress or warnings");
    cmd->callback(
        [args, exitCode] { *exitCode = RunGuarded([&] { return RunStudyCommand(*args); }); });
}

}  // namespace prism
