// The suite's equal-error section: `prism bench compare` on the shared scenes against pbrt-v4
// and pbrt-v3 (../shared/tools), one thread each, the time each renderer needs to reach
// pbrt-v4's error at 128 spp (issue 30's table).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "core/file_io.h"
#include "core/output_file.h"
#include "image/image_io.h"
#include "tools/bench/compare.h"
#include "tools/bench/knot.h"
#include "tools/bench/suite_internal.h"
#include "tools/study/target_error.h"

namespace prism {

namespace {

namespace fs = std::filesystem;

struct EqualErrorScene {
    const char *name;        // the table's row
    std::string path;        // the file ("" : left out, with `missing` said)
    const char *integrator;  // for the row
};

// The knot benchmark scene under the path integrator (its own file says whitted).
std::string KnotUnderPath(const SuiteContext &ctx) {
    const fs::path dir = fs::path(ctx.tmp) / "knot-path";
    fs::create_directories(dir);
    const KnotFiles kf = WriteKnotScene(dir.string(), 2000, 100, false);
    std::string text = ReadFileOrThrow(kf.pbrt, FileLoc{kf.pbrt});
    const std::string whitted = "Integrator \"whitted\"";
    const size_t at = text.find(whitted);
    if (at == std::string::npos) return "";
    text.replace(at, whitted.size(), "Integrator \"path\"");
    const std::string path = (dir / "knot-path.pbrt").string();
    WriteFileAtomically(path, text);
    return path;
}

}  // namespace

void MeasureEqualErrorSection(SuiteContext &ctx) {
    const std::string v4 = ctx.sharedDir + "/tools/pbrt-v4/pbrt";
    const std::string v3 = ctx.sharedDir + "/tools/pbrt-v3/pbrt";
    std::vector<CompareRenderer> against;
    if (fs::exists(v4)) against.push_back({"pbrt-v4", CompareKind::PbrtV4, v4});
    if (fs::exists(v3)) against.push_back({"pbrt-v3", CompareKind::PbrtV3, v3});
    ctx.markdown += "## Equal error against pbrt-v4 and pbrt-v3\n\n";
    if (against.empty()) {
        ctx.markdown += "Left out: neither " + v4 + " nor " + v3 + " is present.\n\n";
        return;
    }
    const std::string s = ctx.sharedDir + "/scenes/";
    const std::vector<EqualErrorScene> scenes{
        {"Cornell box", ctx.sharedDir + "/pbrt3-reference/cornell-path.pbrt", "path"},
        {"Bitterli box", s + "pbrt-cornell-box-bitterli/scene.pbrt", "path"},
        {"teapot under an area light", s + "pbrt-teapot-area-light/teapot-area-light.pbrt",
         "directlighting"},
        {"veach-mis", s + "pbrt-veach-mis/mis.pbrt", "path"},
        {"400k-triangle knot", KnotUnderPath(ctx), "path"},
    };
    // Full: 128x128 images, 16 to 128 spp, a 1024-spp reference by the first renderer (pbrt-v4),
    // 3 repeats. Quick: 32x32, 4 to 16 spp, a 64-spp reference, 1 repeat.
    const bool quick = ctx.options.quick;
    const int res = quick ? 32 : 128, top = quick ? 16 : 128;
    CompareOptions base;
    base.against = against;
    base.threads = 1;
    base.width = base.height = res;
    base.spp = quick ? std::vector<int>{4, 8, 16} : std::vector<int>{16, 32, 64, 128};
    base.targetSpp = top;
    base.referenceSpp = quick ? 64 : 1024;
    base.repeats = quick ? 1 : 3;
    base.ownReference = true;
    base.sourceDir = ctx.sourceDir;
    ctx.markdown += fmt::format(
        "`prism bench compare SCENE{} --threads 1 --res {}x{} --spp {} --target-spp {} "
        "--reference-spp {} --repeats {} --own-reference` on each scene: CPU seconds (whole "
        "process, medians of interleaved repeats) each renderer needs to reach {}'s error at {} "
        "spp, each measured against its own {}-spp image (noise alone: pbrt-v4 renders "
        "spectrally and its --upgrade rewrites materials, so the renderers converge to images "
        "a little apart; the last column is that difference, Prism's converged image against "
        "pbrt-v3's); a ratio is that renderer's time over Prism's.\n\n",
        [&] {
            std::string a;
            for (const CompareRenderer &r : against) a += " --against " + r.name + "=" + r.path;
            return a;
        }(),
        res, res, fmt::join(base.spp, ","), top, base.referenceSpp, base.repeats, against[0].name,
        top, base.referenceSpp);
    std::string header = "| scene | integrator | target error | Prism";
    std::string rule = "|---|---|---:|---:";
    for (const CompareRenderer &r : against) header += " | " + r.name, rule += "|---:";
    for (const CompareRenderer &r : against) header += " | " + r.name + " / Prism", rule += "|---:";
    header += " | Prism vs pbrt-v3, converged";
    rule += "|---:";
    ctx.markdown += header + " |\n" + rule + "|\n";
    for (const EqualErrorScene &sc : scenes) {
        if (sc.path.empty() || !fs::exists(sc.path)) {
            ctx.markdown +=
                fmt::format("| {} | {} | (scene not present) | | |\n", sc.name, sc.integrator);
            continue;
        }
        std::fprintf(stderr, "bench: equal error, %s\n", sc.name);
        CompareOptions o = base;
        o.scene = sc.path;
        o.outDir = (fs::path(ctx.options.outDir.empty() ? ctx.tmp : ctx.options.outDir) /
                    "equal-error" / fs::path(sc.path).parent_path().filename())
                       .string();
        std::vector<CompareOutcome> outcomes;
        double target = 0;
        std::string row = fmt::format("| {} | {} |", sc.name, sc.integrator);
        std::FILE *log = std::tmpfile();
        try {
            RunCompare(o, log ? log : stderr, &outcomes, &target);
        } catch (const std::exception &e) {
            ctx.markdown += row + " failed: " + e.what() + " |\n";
            if (log) std::fclose(log);
            continue;
        }
        if (log) std::fclose(log);
        row += fmt::format(" {:.4g} |", target);
        auto cell = [](const CompareOutcome &oc) {
            return oc.seconds ? fmt::format(" {:.2f} s |", *oc.seconds)
                              : std::string(oc.failed ? " failed |" : " never |");
        };
        for (const CompareOutcome &oc : outcomes) row += cell(oc);
        const CompareOutcome &prism = outcomes[0];
        for (size_t i = 1; i < outcomes.size(); ++i) {
            const CompareOutcome &oc = outcomes[i];
            if (oc.seconds && prism.seconds && *prism.seconds > 0) {
                const double ratio = *oc.seconds / *prism.seconds;
                row += fmt::format(" {:.2f}x |", ratio);
                ctx.Add("equal error", fmt::format("{} {}/Prism", sc.name, oc.name), ratio, "",
                        oc.name == "pbrt-v4" ? ">= 4" : ">= 3");
            } else {
                row += " — |";
            }
        }
        // The converged images' difference (rel. RMSE of Prism's against pbrt-v3's).
        const fs::path images = fs::path(o.outDir) / "images";
        std::string diff = " — |";
        try {
            if (fs::exists(images / "reference-pbrt-v3.exr") &&
                fs::exists(images / "reference-prism.exr"))
                diff = fmt::format(
                    " {:.4g} |",
                    RelativeRmse(ReadImage((images / "reference-prism.exr").string()),
                                 ReadImage((images / "reference-pbrt-v3.exr").string())));
        } catch (const std::exception &) {
        }
        ctx.markdown += row + diff + "\n";
    }
    ctx.markdown += "\n";
}

}  // namespace prism
