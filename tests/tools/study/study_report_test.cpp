// The outputs of `prism study` (tools/study/study_report.h): results.csv, the Pareto front, the
// sentences and report.md, on rows made up here.
#include "tools/study/study_report.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

StudyRow MakeRow(const std::string &knob, const std::string &value, double time, double build,
                 double rmse) {
    StudyRow r;
    r.knob = knob;
    r.value = value;
    r.timeSeconds = time;
    r.buildSeconds = build;
    r.rays = 100;
    r.error.rmse = rmse;
    r.error.relL1 = rmse * 2;
    r.error.maxAbs = rmse * 10;
    r.error.psnr = rmse > 0 ? 10 * std::log10(1 / (rmse * rmse)) : Infinity;
    return r;
}

TEST(StudyReport, CsvColumnsAndInfinity) {
    std::vector<StudyRow> rows{MakeRow("spp", "1", 0.5, 0.25, 0.1),
                               MakeRow("offset", "errorbounds", 1, 0.25, 0)};
    rows[1].error.badPixels = 7;
    rows[1].error.nanCount = 2;
    std::string csv = StudyCsv(rows);
    EXPECT_EQ(csv,
              "knob,value,time_s,build_s,rays,rmse,rel_l1,max_abs_err,psnr,bad_pixels,nan_count\n"
              "spp,1,0.500000,0.250000,100,0.1,0.2,1,20,0,0\n"
              "offset,errorbounds,1.000000,0.250000,100,0,0,0,inf,7,2\n");
}

TEST(StudyReport, ParetoFrontByCostAndRmse) {
    std::vector<StudyRow> rows{
        MakeRow("spp", "1", 1, 0, 0.10),            // front
        MakeRow("spp", "4", 4, 0, 0.05),            // front
        MakeRow("spp", "16", 16, 0, 0.01),          // front
        MakeRow("robust", "on", 5, 0, 0.06),        // dominated by spp 4
        MakeRow("tessellate", "8", 2, 3, 0.2),      // dominated: cost 5
        MakeRow("offset", "none", 4.5, 0, 0.0499),  // within 0.5% of spp 4: not better
        MakeRow("cutoff", "1e-2", 0.5, 0, NAN),     // NaN: left out
    };
    std::vector<size_t> front = ParetoFront(rows);
    EXPECT_EQ(front, (std::vector<size_t>{0, 1, 2}));
    EXPECT_DOUBLE_EQ(StudyCost(rows[4]), 5);
}

TEST(StudyReport, SentencesAndTables) {
    StudyResult r;
    r.scene = "scenes/x.pbrt";
    r.resolution = {32, 24};
    r.repeats = 3;
    r.referenceSpp = 256;
    r.referenceMaxDepth = 16;
    r.baseSpp = 4;
    r.baseMaxDepth = 5;
    r.rows = {MakeRow("spp", "1", 0.1, 0.01, 0.1), MakeRow("spp", "4", 0.4, 0.01, 0.05),
              MakeRow("light-samples", "8", 0.2, 0.02, 0.07)};
    r.rows[1].base = true;
    r.skipped.push_back({StudyKnob::Precision, "the scene has no analytic shapes"});
    std::vector<std::string> s = ParetoSentences(r);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s[0], "For RMSE <= 0.1 this scene needs 1 sample per pixel and costs 0.11 seconds.");
    EXPECT_EQ(s[1], "For RMSE <= 0.07 this scene needs 8 light samples and costs 0.22 seconds.");
    EXPECT_EQ(s[2], "For RMSE <= 0.05 this scene needs its own settings and costs 0.41 seconds.");

    std::string md = StudyReport(r);
    EXPECT_NE(md.find("# Accuracy study of scenes/x.pbrt"), std::string::npos);
    EXPECT_NE(md.find("## spp\n"), std::string::npos);
    EXPECT_NE(md.find("## light-samples\n"), std::string::npos);
    EXPECT_NE(md.find("| 4 | 0.4000 | 0.0100 | 100 | 0.05 |"), std::string::npos) << md;
    EXPECT_NE(md.find("- `precision`: the scene has no analytic shapes."), std::string::npos);
    EXPECT_NE(md.find("## Pareto front"), std::string::npos);
    EXPECT_NE(md.find("- " + s[0]), std::string::npos);
    EXPECT_NE(md.find("256 samples per pixel, maxdepth 16"), std::string::npos);
    EXPECT_NE(md.find("![pareto.png](pareto.png)"), std::string::npos);
    EXPECT_EQ(StudyPlotFiles(r.rows),
              (std::vector<std::string>{"time_spp.png", "time_light-samples.png", "pareto.png"}));
}

}  // namespace
}  // namespace prism
