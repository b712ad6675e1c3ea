#include "tools/study/study_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace prism {

namespace {

// A number for the tables: a few significant digits, "inf" and "nan" spelled out.
std::string Num(double v, int digits = 3) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return fmt::format("{:.{}g}", v, digits);
}

// The setting of a row in words, for the Pareto sentences.
std::string SettingInWords(const StudyRow &r) {
    if (r.base) return "its own settings";
    const std::string &k = r.knob, &v = r.value;
    if (k == "spp") return v + (v == "1" ? " sample" : " samples") + " per pixel";
    if (k == "maxdepth") return "maxdepth " + v;
    if (k == "cutoff") return v == "0" ? "no ray-weight cutoff" : "a ray-weight cutoff of " + v;
    if (k == "precision") return v + " precision";
    if (k == "offset") {
        if (v == "errorbounds") return "error-bound ray offsets";
        if (v == "none") return "no ray offset";
        if (v.rfind("epsilon-", 0) == 0) return "a fixed ray offset of " + v.substr(8);
    }
    if (k == "tessellate") return "tessellated twins of " + v + " segments";
    if (k == "robust") return "Embree's ROBUST flag " + v;
    if (k == "bvh-quality") return "BVH quality " + v;
    if (k == "light-samples") return v + (v == "1" ? " light sample" : " light samples");
    if (k == "light-sampler")
        return "lights chosen " + std::string(v == "bvh" ? "by the light BVH" : "by " + v);
    return k + " " + v;
}

void AppendKnobTable(std::string &md, const std::vector<StudyRow> &rows, const std::string &knob) {
    md += fmt::format("## {}\n\n", knob);
    md +=
        "| value | render s | build s | rays | rmse | rel_l1 | max abs err | psnr dB | bad pixels "
        "| NaN |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const StudyRow &r : rows) {
        if (r.knob != knob) continue;
        const ImageError &e = r.error;
        md += fmt::format("| {} | {:.4f} | {:.4f} | {} | {} | {} | {} | {} | {} | {} |\n", r.value,
                          r.timeSeconds, r.buildSeconds, r.rays, Num(e.rmse), Num(e.relL1),
                          Num(e.maxAbs), Num(e.psnr, 4), e.badPixels, e.nanCount);
    }
    md += "\n";
}

// "spp, maxdepth and cutoff": the knobs that re-render one built scene.
std::string ReusingKnobs() {
    std::vector<std::string> names;
    for (StudyKnob k : AllStudyKnobs())
        if (KnobReusesScene(k)) names.push_back(KnobName(k));
    std::string s;
    for (size_t i = 0; i < names.size(); ++i)
        s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return s;
}

std::vector<std::string> KnobsInOrder(const std::vector<StudyRow> &rows) {
    std::vector<std::string> knobs;
    for (const StudyRow &r : rows)
        if (std::find(knobs.begin(), knobs.end(), r.knob) == knobs.end()) knobs.push_back(r.knob);
    return knobs;
}

}  // namespace

std::string StudyCsv(const std::vector<StudyRow> &rows) {
    std::string csv = std::string(StudyCsvHeader) + "\n";
    for (const StudyRow &r : rows) {
        const ImageError &e = r.error;
        csv += fmt::format("{},{},{:.6f},{:.6f},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{}\n", r.knob,
                           r.value, r.timeSeconds, r.buildSeconds, r.rays, e.rmse, e.relL1,
                           e.maxAbs, e.psnr, e.badPixels, e.nanCount);
    }
    return csv;
}

double StudyCost(const StudyRow &row) { return row.buildSeconds + row.timeSeconds; }

std::vector<size_t> ParetoFront(const std::vector<StudyRow> &rows) {
    std::vector<size_t> order;
    for (size_t i = 0; i < rows.size(); ++i)
        if (!std::isnan(rows[i].error.rmse)) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        double ca = StudyCost(rows[a]), cb = StudyCost(rows[b]);
        if (ca != cb) return ca < cb;
        return rows[a].error.rmse < rows[b].error.rmse;
    });
    std::vector<size_t> front;
    double best = Infinity;
    for (size_t i : order)
        if (rows[i].error.rmse < best * (1 - ParetoRelativeTolerance)) {
            best = rows[i].error.rmse;
            front.push_back(i);
        }
    return front;
}

std::vector<std::string> ParetoSentences(const StudyResult &result) {
    std::vector<std::string> lines;
    for (size_t i : ParetoFront(result.rows)) {
        const StudyRow &r = result.rows[i];
        lines.push_back(fmt::format("For RMSE <= {} this scene needs {} and costs {:.3g} seconds.",
                                    Num(r.error.rmse), SettingInWords(r), StudyCost(r)));
    }
    return lines;
}

std::string StudyReport(const StudyResult &result) {
    std::string md = fmt::format("# Accuracy study of {}\n\n", result.scene);
    md += fmt::format(
        "{}x{} pixels; each setting ran {} time{}, times are medians (render and BVH build "
        "apart).\n\n",
        result.resolution.x, result.resolution.y, result.repeats, result.repeats == 1 ? "" : "s");
    md += fmt::format(
        "**Reference:** {} samples per pixel, maxdepth {}, double precision, analytic shapes, "
        "error-bound ray offsets, no ray-weight cutoff, each light's own sample count "
        "(rendered in {:.3f} s).\n\n",
        result.referenceSpp, result.referenceMaxDepth, result.referenceSeconds);
    md += fmt::format(
        "**Base settings:** each knob is swept alone; the others keep the scene's own settings: "
        "{} samples per pixel, maxdepth {}, each light's own sample count, double precision, "
        "analytic shapes, error-bound offsets, no cutoff, ROBUST off, BVH quality chosen "
        "automatically. The settings of {} re-render one built scene; the other knobs rebuild "
        "it.\n\n",
        result.baseSpp, result.baseMaxDepth, ReusingKnobs());
    md +=
        "**Metrics** (against the reference, over every pixel's RGB components, linear "
        "radiance): `rmse` root mean square error; `rel_l1` the sum of absolute errors over the "
        "sum of the reference's absolute values; `max_abs_err` the largest absolute error; "
        "`psnr` 10 log10(1 / mse) with peak 1; `bad_pixels` pixels with a component off by more "
        "than 0.1 (acne, light leaks, missing reflections); `nan_count` NaN or infinite samples "
        "(written as 0). `rays` counts the rays one render traced.\n\n";

    for (const std::string &knob : KnobsInOrder(result.rows))
        AppendKnobTable(md, result.rows, knob);

    if (!result.skipped.empty()) {
        md += "## Knobs not studied\n\n";
        for (const SkippedKnob &s : result.skipped)
            md += fmt::format("- `{}`: {}.\n", KnobName(s.knob), s.reason);
        md += "\n";
    }

    md += "## Pareto front\n\n";
    md +=
        "The settings no other setting beats in both cost (BVH build + render) and rmse, over "
        "all the settings above (one knob changed at a time); a costlier setting counts only if it "
        "lowers the rmse by more than 0.5%.\n\n";
    std::vector<size_t> front = ParetoFront(result.rows);
    if (front.empty()) {
        md += "No settings were studied.\n\n";
    } else {
        md += "| knob | value | cost s | rmse | bad pixels |\n|---|---|---:|---:|---:|\n";
        for (size_t i : front) {
            const StudyRow &r = result.rows[i];
            md += fmt::format("| {} | {} | {:.4f} | {} | {} |\n", r.knob, r.value, StudyCost(r),
                              Num(r.error.rmse), r.error.badPixels);
        }
        md += "\n";
        for (const std::string &s : ParetoSentences(result)) md += "- " + s + "\n";
        md += "\n";
    }

    std::vector<std::string> plots = StudyPlotFiles(result.rows);
    if (!plots.empty()) {
        md += "## Plots\n\n";
        md +=
            "Written by tools/plot_study.py when python3 with matplotlib is available: render "
            "time against rmse for each knob, and every setting with the Pareto front.\n\n";
        for (const std::string &p : plots) md += fmt::format("![{}]({})\n", p, p);
        md += "\n";
    }
    return md;
}

std::vector<std::string> StudyPlotFiles(const std::vector<StudyRow> &rows) {
    std::vector<std::string> files;
    for (const std::string &knob : KnobsInOrder(rows)) files.push_back("time_" + knob + ".png");
    if (!rows.empty()) files.push_back("pareto.png");
    return files;
}

}  // namespace prism
