// The outputs of `prism study`: results.csv, the Pareto front and report.md (as strings; the
// app writes them atomically). Neither needs Python; tools/plot_study.py draws the plots.
#pragma once

#include <string>
#include <vector>

#include "tools/study/study.h"

namespace prism {

// The header of results.csv, without the newline.
inline constexpr const char *StudyCsvHeader =
    "knob,value,time_s,build_s,rays,rmse,rel_l1,max_abs_err,psnr,bad_pixels,nan_count";

// results.csv: the header and one line per row. Infinite values are written "inf".
std::string StudyCsv(const std::vector<StudyRow> &rows);

// The cost of a row on the Pareto front: BVH build plus render, in seconds.
double StudyCost(const StudyRow &row);

// Indices of the Pareto-optimal rows (no other row is at most as costly with at most the
// rmse, and better in one): by increasing cost, so by decreasing rmse. A costlier row counts
// as better only if it lowers the rmse by more than ParetoRelativeTolerance (settings that
// render the same image up to noise in the last digits do not crowd the front). Rows with a
// NaN rmse are left out.
inline constexpr double ParetoRelativeTolerance = 0.005;
std::vector<size_t> ParetoFront(const std::vector<StudyRow> &rows);

// "For RMSE <= x this scene needs S and costs t seconds.", one line per front row; S is the
// row's setting in words ("16 samples per pixel", "its own settings" for a base row), the
// other knobs keeping the base settings.
std::vector<std::string> ParetoSentences(const StudyResult &result);

// report.md: the settings, the metrics' definitions, a table per knob, the skipped knobs with
// their reasons, the Pareto front and its sentences, and the plots' file names.
std::string StudyReport(const StudyResult &result);

// The PNG files tools/plot_study.py writes for these rows (one per knob, then pareto.png).
std::vector<std::string> StudyPlotFiles(const std::vector<StudyRow> &rows);

}  // namespace prism
