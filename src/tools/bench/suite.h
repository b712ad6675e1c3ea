// `prism bench suite`: the performance table of issue 10 from one run, as Markdown on stdout
// (progress on stderr); with an output directory also results.csv, report.md and plots.
#pragma once

#include <string>
#include <vector>

namespace prism {

struct SuiteOptions {
    bool quick = false;             // smaller images and fewer runs: well under a minute
    std::string outDir;             // "" : report on stdout only
    std::string commandLine;        // quoted in the report
    std::string sharedDir;          // ../shared (peers/whitted.pbrt, whitted.pov); "" : the default
    std::vector<std::string> only;  // section names (SuiteSectionNames); empty: all
};

// One measured value, as written to results.csv.
struct BenchMetric {
    std::string section, name;
    double value = 0;
    std::string unit;
    std::string target;  // e.g. ">= 0.75"; "" : no target
    std::string status;  // "met", "missed" or ""
};

// The sections, in the report's order: ceiling, povray, threads, startup, memory, batch,
// equal-error.
const std::vector<std::string> &SuiteSectionNames();

// Runs the suite; returns the exit status (0, also when targets are missed).
int RunSuite(const SuiteOptions &options);

// --- pieces, exposed for the tests -----------------------------------------------------------

// Seconds and rates parsed from `prism render`'s statistics (stderr); negative when missing.
struct PrismRenderStats {
    double parse = -1, setup = -1, bvh = -1, render = -1, mrays = -1;
};
PrismRenderStats ParsePrismStats(const std::string &stderrText);
// POV-Ray's "Trace Time" / "Parse Time" in seconds from its statistics; negative when missing.
double ParsePovTime(const std::string &stderrText, const std::string &label);
// "met" when value satisfies target (">= x", "<= x", "< x"), else "missed".
std::string TargetStatus(double value, const std::string &target);
// results.csv text.
std::string MetricsCsv(const std::vector<BenchMetric> &metrics);

}  // namespace prism
