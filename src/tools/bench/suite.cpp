#include "tools/bench/suite.h"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/file_io.h"
#include "core/output_file.h"
#include "tools/bench/process.h"
#include "tools/bench/suite_internal.h"

namespace prism {

namespace {

namespace fs = std::filesystem;

std::string CpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            size_t c = line.find(':');
            if (c != std::string::npos) return line.substr(line.find_first_not_of(" \t", c + 1));
        }
    }
    return "unknown CPU";
}

std::string LoadAverage() {
    std::ifstream in("/proc/loadavg");
    double a = 0, b = 0, c = 0;
    if (!(in >> a >> b >> c)) return "unknown";
    return fmt::format("{:.2f} {:.2f} {:.2f}", a, b, c);
}

std::string GitCommit(const std::string &sourceDir) {
    std::string c =
        CommandOutput("git -C " + ShellQuote(sourceDir) + " rev-parse --short HEAD 2>/dev/null");
    if (c.empty()) return "unknown";
    std::string dirty = CommandOutput("git -C " + ShellQuote(sourceDir) +
                                      " status --porcelain --untracked-files=no 2>/dev/null");
    return dirty.empty() ? c : c + " (with uncommitted changes)";
}

// Through AtomicOutputFile (core/output_file.h), as every output: a new temporary file beside
// `path` (never through a symbolic link), renamed over it once complete.
void WriteText(const std::string &path, const std::string &text) {
    WriteFileAtomically(path, text);
}

std::string FormatValue(double v) {
    return std::abs(v) >= 100 ? fmt::format("{:.0f}", v) : fmt::format("{:.2f}", v);
}

}  // namespace

void SuiteContext::Add(const std::string &section, const std::string &name, double value,
                       const std::string &unit, const std::string &target) {
    metrics.push_back({section, name, value, unit, target,
                       target.empty() ? std::string() : TargetStatus(value, target)});
}

PrismRenderStats ParsePrismStats(const std::string &text) {
    PrismRenderStats s;
    size_t t = text.find("time: parse ");
    if (t != std::string::npos)
        std::sscanf(text.c_str() + t, "time: parse %lfs, setup %lfs, BVH build %lfs, render %lfs",
                    &s.parse, &s.setup, &s.bvh, &s.render);
    size_t m = text.find(" Mrays/s");
    if (m != std::string::npos) {
        size_t b = text.rfind(' ', m - 1);
        if (b != std::string::npos) s.mrays = std::atof(text.c_str() + b + 1);
    }
    return s;
}

double ParsePovTime(const std::string &text, const std::string &label) {
    size_t t = text.find(label + ":");
    if (t == std::string::npos) return -1;
    size_t open = text.find('(', t), eol = text.find('\n', t);
    if (open == std::string::npos || (eol != std::string::npos && open > eol)) return -1;
    return std::atof(text.c_str() + open + 1);
}

std::string TargetStatus(double value, const std::string &target) {
    std::istringstream in(target);
    std::string op;
    double x = 0;
    if (!(in >> op >> x)) return "";
    bool ok = op == ">="   ? value >= x
              : op == "<=" ? value <= x
              : op == "<"  ? value < x
              : op == ">"  ? value > x
                           : false;
    return ok ? "met" : "missed";
}

std::string MetricsCsv(const std::vector<BenchMetric> &metrics) {
    std::string s = "section,metric,value,unit,target,status\n";
    for (const BenchMetric &m : metrics)
        s += fmt::format("{},{},{:.6g},{},{},{}\n", m.section, m.name, m.value, m.unit, m.target,
                         m.status);
    return s;
}

const std::vector<std::string> &SuiteSectionNames() {
    static const std::vector<std::string> names{"ceiling", "povray", "threads",    "startup",
                                                "memory",  "batch",  "equal-error"};
    return names;
}

int RunSuite(const SuiteOptions &options) {
    SuiteContext ctx;
    ctx.options = options;
    ctx.prism = SelfExecutable();
    ctx.sourceDir = PRISM_SOURCE_DIR;
    ctx.sharedDir = options.sharedDir;
    if (ctx.sharedDir.empty()) {
        const char *env = std::getenv("PRISM_SHARED_DIR");
        ctx.sharedDir = env ? env : ctx.sourceDir + "/../shared";
    }
    if (options.quick) {
        ctx.povRuns = 1;
        ctx.scalingRuns = 1;
        ctx.startupRuns = 5;
        ctx.memoryRuns = 1;
        ctx.ceilingRepeats = 1;
        ctx.povRes = "400x300";
    }
    char tmpl[] = "/tmp/prism-bench-XXXXXX";
    if (!mkdtemp(tmpl)) throw std::runtime_error("cannot create a temporary directory");
    ctx.tmp = tmpl;
    struct Cleanup {
        std::string dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{ctx.tmp};

    auto t0 = std::chrono::steady_clock::now();
    std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::string head = fmt::format(
        "# prism bench suite{}\n\n- date: {}\n- machine: {}, {} cores; load average at start {}\n"
        "- commit: {}\n- command: `{}`\n\n",
        options.quick ? " (quick)" : "", date, CpuModel(), std::thread::hardware_concurrency(),
        LoadAverage(), GitCommit(ctx.sourceDir), options.commandLine);

    // Memory first, while this process is small (see MeasureMemorySection), then start-up;
    // the report lists the sections in the order.
    using Section = void (*)(SuiteContext &);
    const std::vector<std::pair<int, Section>> order{
        {4, MeasureMemorySection},    {3, MeasureStartupSection},       {0, MeasureCeilingSection},
        {1, MeasurePovRaySection},    {2, MeasureThreadScalingSection}, {5, MeasureBatchSection},
        {6, MeasureEqualErrorSection}};
    std::vector<std::string> sections(order.size());
    std::vector<std::vector<BenchMetric>> sectionMetrics(order.size());
    for (const auto &[slot, measure] : order) {
        const std::string &name = SuiteSectionNames()[size_t(slot)];
        if (!options.only.empty() &&
            std::find(options.only.begin(), options.only.end(), name) == options.only.end())
            continue;
        ctx.markdown.clear();
        ctx.metrics.clear();
        measure(ctx);
        sections[size_t(slot)] = ctx.markdown;
        sectionMetrics[size_t(slot)] = ctx.metrics;
    }
    ctx.markdown.clear();
    ctx.metrics.clear();
    for (size_t i = 0; i < sections.size(); ++i) {
        ctx.markdown += sections[i];
        ctx.metrics.insert(ctx.metrics.end(), sectionMetrics[i].begin(), sectionMetrics[i].end());
    }

    std::string targets = "## Targets\n\n| target | measured | status |\n|---|---|---|\n";
    for (const BenchMetric &m : ctx.metrics) {
        if (m.target.empty()) continue;
        std::string unit = m.unit.empty() ? "" : " " + m.unit;
        targets += fmt::format("| {} {}{} | {}{} | {} |\n", m.name, m.target, unit,
                               FormatValue(m.value), unit, m.status);
    }
    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::string report =
        head + ctx.markdown + targets +
        fmt::format("\nSuite time {:.0f} s; load average at the end {}.\n", total, LoadAverage());
    std::fputs(report.c_str(), stdout);
    std::fflush(stdout);

    if (!options.outDir.empty()) {
        fs::create_directories(options.outDir);
        std::string csv = options.outDir + "/results.csv";
        WriteText(csv, MetricsCsv(ctx.metrics));
        WriteText(options.outDir + "/report.md", report);
        std::fprintf(stderr, "wrote %s and report.md\n", csv.c_str());
        std::string script = ctx.sourceDir + "/tools/plot_bench.py";
        // Debian's python3 (python3-matplotlib), as prism validate uses; else PATH's.
        std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
        std::string cmd = python + " " + ShellQuote(script) + " " + ShellQuote(csv) + " " +
                          ShellQuote(options.outDir);
        if (std::system(cmd.c_str()) != 0)
            std::fprintf(stderr, "warning: plotting failed (%s); results.csv is complete\n",
                         cmd.c_str());
    }
    return 0;
}

}  // namespace prism
