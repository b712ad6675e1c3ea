// The sections of `prism bench suite` (suite_sections.cpp), run by RunSuite (suite.cpp).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/suite.h"

namespace prism {

struct SuiteContext {
    SuiteOptions options;
    std::string prism;      // this executable
    std::string tmp;        // scratch directory, removed at the end
    std::string sharedDir;  // ../shared
    std::string sourceDir;  // the source tree (scenes/whitted.pbrt)
    int povRuns = 5, scalingRuns = 7, startupRuns = 20, memoryRuns = 3, ceilingRepeats = 3;
    std::string povRes = "800x600";  // POV-Ray comparison and thread scaling
    std::string markdown;            // the section being measured (RunSuite collects them)
    std::vector<BenchMetric> metrics;
    // Render-phase rates (Mrays/s) of the Whitted scene at 1 spp by thread count, from the
    // POV-Ray comparison; the thread-scaling section measures them itself when empty.
    std::vector<double> whittedMrays1, whittedMrays2;
    std::string whittedScene;

    void Add(const std::string &section, const std::string &name, double value,
             const std::string &unit, const std::string &target = "");
};

void MeasureCeilingSection(SuiteContext &ctx);
void MeasurePovRaySection(SuiteContext &ctx);
void MeasureThreadScalingSection(SuiteContext &ctx);
void MeasureStartupSection(SuiteContext &ctx);
void MeasureMemorySection(SuiteContext &ctx);
void MeasureBatchSection(SuiteContext &ctx);
void MeasureEqualErrorSection(SuiteContext &ctx);  // suite_equal_error.cpp

}  // namespace prism
