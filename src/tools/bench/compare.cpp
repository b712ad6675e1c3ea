#include "tools/bench/compare.h"

#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "assembly/build_scene.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/output_file.h"
#include "image/image_io.h"
#include "scene/load_scene.h"
#include "tools/bench/ceiling.h"
#include "tools/bench/process.h"
#include "tools/study/target_error.h"

namespace prism {

namespace fs = std::filesystem;

std::vector<int> DefaultLadder(int sceneSpp) {
    std::vector<int> out;
    for (double f : {1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0, 2.0}) {
        const int n = std::max(1, int(std::lround(sceneSpp * f)));
        if (out.empty() || out.back() != n) out.push_back(n);
    }
    return out;
}

LogLogFit FitLogLog(const std::vector<double> &x, const std::vector<double> &y) {
    // FitPowerLaw (tools/study) leaves out non-positive points; non-finite ones go here.
    std::vector<double> fx, fy;
    for (size_t i = 0; i < x.size() && i < y.size(); ++i)
        if (std::isfinite(x[i]) && std::isfinite(y[i])) fx.push_back(x[i]), fy.push_back(y[i]);
    LogLogFit f;
    PowerLaw p;
    try {
        p = FitPowerLaw(fx, fy);  // y = p.a x^-p.b
    } catch (const std::invalid_argument &) {
        return f;  // fewer than two distinct x
    }
    f.a = std::log(p.a);
    f.b = -p.b;
    f.ok = std::isfinite(f.a) && std::isfinite(f.b);
    return f;
}

std::optional<double> SppToError(const LogLogFit &fit, double error) {
    if (!fit.ok || !(fit.b < -0.05) || !(error > 0)) return std::nullopt;
    const double n = std::exp((std::log(error) - fit.a) / fit.b);
    if (!std::isfinite(n)) return std::nullopt;
    return n;
}

CompareFit FitRenderer(const std::vector<int> &spp, const std::vector<double> &errors,
                       const std::vector<double> &seconds) {
    CompareFit f;
    std::vector<double> n(spp.begin(), spp.end());
    f.error = FitLogLog(n, errors);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k = 0;
    for (size_t i = 0; i < n.size() && i < seconds.size(); ++i) {
        if (!std::isfinite(seconds[i])) continue;
        sx += n[i], sy += seconds[i], sxx += n[i] * n[i], sxy += n[i] * seconds[i];
        ++k;
    }
    const double d = k * sxx - sx * sx;
    if (k >= 2 && d > 0) {
        f.c = std::max(0.0, (k * sxy - sx * sy) / d);
        f.t0 = std::max(0.0, (sy - f.c * sx) / k);
    } else if (k > 0) {
        f.c = sy / std::max(sx, 1.0);  // one count: all of its time per sample
    }
    return f;
}

namespace {

std::string Fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// Seconds with three significant digits (at least two decimals below 10 s).
std::string Seconds(double s) { return Fixed(s, s < 1 ? 3 : s < 10 ? 2 : s < 100 ? 1 : 0); }

std::string ErrorText(double e) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g", e);
    return buf;
}

}  // namespace

std::string EqualErrorLine(double error, const std::vector<CompareOutcome> &outcomes) {
    std::string line = "equal-error " + ErrorText(error) + ":";
    const CompareOutcome *prism = outcomes.empty() ? nullptr : &outcomes[0];
    for (size_t i = 0; i < outcomes.size(); ++i) {
        const CompareOutcome &o = outcomes[i];
        line += std::string(i ? "," : "") + " " + o.name;
        if (!o.seconds) {
            line += o.failed ? " failed" : " never";
            continue;
        }
        line += " " + Seconds(*o.seconds) + " s";
        if (i > 0 && prism && prism->seconds && *prism->seconds > 0)
            line += " (ratio " + Fixed(*o.seconds / *prism->seconds, 2) + ")";
    }
    return line;
}

namespace {

// The last non-empty line of a child's stderr (or stdout), for a failure's reason.
std::string LastLine(const std::string &s) {
    std::istringstream in(s);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

// Through AtomicOutputFile, as every output Prism writes (core/output_file.h).
void WriteText(const fs::path &path, const std::string &text) {
    WriteFileAtomically(path.string(), text);
}

// A command line as a shell reads it (arguments with other characters than these quoted).
std::string Joined(const std::vector<std::string> &argv) {
    std::string s;
    for (const std::string &a : argv) {
        const bool plain = !a.empty() && a.find_first_not_of(
                                             "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                             "0123456789-_./=:,+") == std::string::npos;
        s += (s.empty() ? "" : " ") + (plain ? a : ShellQuote(a));
    }
    return s;
}

// A renderer taking part, and what it measured.
struct Contender {
    CompareRenderer renderer;
    std::string workDir;    // "" : the current folder
    std::string stdinText;  // the scene on stdin ("" : a file argument)
    std::string why;        // how it reads the scene, printed once
    bool failed = false;
    std::string failure;
    struct Rung {
        int spp = 0;
        std::vector<double> cpu, wall;
        double error = std::nan("");
    };
    std::vector<Rung> rungs;
    Image reference;  // its own converged image (CompareOptions::ownReference)
};

class CompareRun {
  public:
    CompareRun(const CompareOptions &o, std::FILE *out) : o_(o), out_(out) {}
    std::vector<CompareOutcome> resultOutcomes;
    double resultTarget = 0;
    CompareRun(const CompareRun &) = delete;
    CompareRun &operator=(const CompareRun &) = delete;
    ~CompareRun() {
        std::error_code ec;
        if (tempDir_) fs::remove_all(dir_, ec);
    }
    int Run();

  private:
    void Prepare();
    // The command for `spp` ("N" in the printed template).
    std::vector<std::string> Argv(const Contender &c, const std::string &spp,
                                  const std::string &image, std::string *stdinPath) const;
    // Renders `c` at `spp` into `image`; false (and c.failed) when it fails.
    bool Render(Contender &c, int spp, const std::string &image, ChildRun *run);
    std::string ImagePath(const Contender &c, const std::string &spp) const {
        return (dir_ / "images" / (c.renderer.name + "-" + spp + ".exr")).string();
    }

    const CompareOptions &o_;
    std::FILE *out_;
    fs::path scene_, dir_;
    bool tempDir_ = false;
    SceneDescription desc_;
    int sceneSpp_ = 16;
    std::vector<int> ladder_;
    std::vector<Contender> cs_;  // [0] is Prism
};

std::vector<std::string> CompareRun::Argv(const Contender &c, const std::string &n,
                                          const std::string &image, std::string *stdinPath) const {
    const std::string t = std::to_string(o_.threads);
    *stdinPath = "";
    if (!c.stdinText.empty()) {
        *stdinPath = (dir_ / "inputs" / (c.renderer.name + "-" + n + ".pbrt")).string();
    }
    switch (c.renderer.kind) {
        case CompareKind::Prism: {
            std::vector<std::string> a{
                c.renderer.path, "render", scene_.string(), "--spp", n, "--threads", t, "-o",
                image,           "-q"};
            if (o_.width > 0)
                a.insert(a.end(),
                         {"--res", std::to_string(o_.width) + "x" + std::to_string(o_.height)});
            return a;
        }
        case CompareKind::PbrtV3:
            return {c.renderer.path,          "--nthreads", t,    "--quiet", "--logdir",
                    (dir_ / "logs").string(), "--outfile",  image};
        case CompareKind::PbrtV4: {
            std::vector<std::string> a{c.renderer.path, "--nthreads", t, "--quiet", "--spp", n,
                                       "--outfile",     image};
            if (c.stdinText.empty()) a.push_back(scene_.string());
            return a;
        }
    }
    return {};
}

bool CompareRun::Render(Contender &c, int spp, const std::string &image, ChildRun *run) {
    std::string stdinPath;
    std::vector<std::string> argv = Argv(c, std::to_string(spp), image, &stdinPath);
    if (!stdinPath.empty() && !fs::exists(stdinPath)) {
        std::string text = c.stdinText;
        if (c.renderer.kind == CompareKind::PbrtV3)
            text = SetPbrtV3SampleCount(c.stdinText, spp, scene_.string());
        WriteText(stdinPath, text);
    }
    std::error_code ec;
    fs::remove(image, ec);
    try {
        *run = RunChild(argv, c.workDir, stdinPath);
    } catch (const std::exception &e) {
        c.failed = true;
        c.failure = e.what();
        return false;
    }
    if (run->exitStatus != 0 || !fs::exists(image)) {
        c.failed = true;
        std::string why = LastLine(run->err);
        if (why.empty()) why = LastLine(run->out);
        c.failure = (run->exitStatus != 0 ? "exit status " + std::to_string(run->exitStatus)
                                          : std::string("no image written")) +
                    (why.empty() ? "" : ": " + why) + " (" + Joined(argv) + ")";
        return false;
    }
    return true;
}

void CompareRun::Prepare() {
    scene_ = fs::absolute(o_.scene).lexically_normal();
    Diagnostics diag;
    LoadOptions lo;
    desc_ = LoadScene(scene_.string(), diag, lo);
    sceneSpp_ = std::max(1, SceneSamplesPerPixel(desc_));
    ladder_ = o_.spp.empty() ? DefaultLadder(sceneSpp_) : o_.spp;
    std::sort(ladder_.begin(), ladder_.end());
    ladder_.erase(std::unique(ladder_.begin(), ladder_.end()), ladder_.end());
    if (o_.outDir.empty()) {
        std::string tmpl = (fs::temp_directory_path() / "prism-compare-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary folder");
        dir_ = tmpl;
        tempDir_ = true;
    } else {
        dir_ = fs::absolute(o_.outDir);
        fs::create_directories(dir_);
    }
    for (const char *sub : {"images", "inputs", "logs"}) fs::create_directories(dir_ / sub);

    Contender prism;
    prism.renderer = {"prism", CompareKind::Prism, SelfExecutable()};
    const std::string res =
        o_.width > 0 ? std::to_string(o_.width) + "x" + std::to_string(o_.height) : std::string();
    prism.why = "the file itself, --spp N" + (res.empty() ? "" : " --res " + res);
    cs_.push_back(prism);
    const std::string sceneText =
        desc_.format == "pbrt" ? ReadFileOrThrow(scene_.string(), FileLoc{scene_.string()}) : "";
    for (const CompareRenderer &r : o_.against) {
        Contender c;
        c.renderer = r;
        c.workDir = scene_.parent_path().string();  // relative paths resolve as from the file
        if (desc_.format != "pbrt") {
            c.failed = true;
            c.failure = "cannot render " + desc_.format + " scenes (pbrt files only)";
        } else if (r.kind == CompareKind::PbrtV3) {
            c.stdinText = res.empty() ? sceneText
                                      : SetPbrtResolution(sceneText, o_.width, o_.height, "image",
                                                          scene_.string());
            SetPbrtV3SampleCount(c.stdinText, 1, scene_.string());  // fails early if it cannot
            c.why = "the file on stdin, its Sampler's count set to N" +
                    (res.empty() ? "" : ", its Film's size to " + res);
        } else {
            // A pbrt-v3 file goes through pbrt-v4's own --upgrade; a file it cannot upgrade
            // (a pbrt-v4 file) is given as it is.
            ChildRun up;
            try {
                up = RunChild({r.path, "--upgrade", scene_.string()}, c.workDir);
            } catch (const std::exception &e) {
                c.failed = true;
                c.failure = e.what();
            }
            const std::string size = res.empty() ? "" : ", its Film's size set to " + res;
            if (!c.failed && up.exitStatus == 0 && !up.out.empty()) {
                WriteText(dir_ / "inputs" / (r.name + "-upgraded.pbrt"), up.out);
                c.stdinText = res.empty() ? up.out
                                          : SetPbrtResolution(up.out, o_.width, o_.height, "rgb",
                                                              scene_.string());
                c.why = "the file converted by its --upgrade, on stdin, --spp N" + size;
            } else if (!c.failed) {
                if (!res.empty())
                    c.stdinText =
                        SetPbrtResolution(sceneText, o_.width, o_.height, "rgb", scene_.string());
                c.why = "the file " + std::string(res.empty() ? "itself" : "on stdin") +
                        " (--upgrade refused it: " + LastLine(up.err) + "), --spp N" + size;
            }
        }
        cs_.push_back(std::move(c));
    }
}

int CompareRun::Run() {
    Prepare();
    std::fprintf(out_, "compare: %s, %d spp in the file; ladder", scene_.string().c_str(),
                 sceneSpp_);
    for (int n : ladder_) std::fprintf(out_, " %d", n);
    std::fprintf(out_,
                 " spp; %d thread%s; %d repeat%s, interleaved; CPU seconds (user + system) "
                 "of each whole process, medians\n",
                 o_.threads, o_.threads == 1 ? "" : "s", o_.repeats, o_.repeats == 1 ? "" : "s");
    if (!o_.commandLine.empty()) std::fprintf(out_, "command: %s\n", o_.commandLine.c_str());
    for (const Contender &c : cs_) {
        if (c.failed) {
            std::fprintf(out_, "%s: %s\n", c.renderer.name.c_str(), c.failure.c_str());
            continue;
        }
        std::string stdinPath;
        std::vector<std::string> argv = Argv(c, "N", ImagePath(c, "N"), &stdinPath);
        std::string cmd = Joined(argv);
        if (!stdinPath.empty()) cmd += " < " + stdinPath;
        if (!c.workDir.empty()) cmd = "(cd " + c.workDir + " && " + cmd + ")";
        std::fprintf(out_, "%s: %s, for each count N\n  %s\n", c.renderer.name.c_str(),
                     c.why.c_str(), cmd.c_str());
    }

    // The converged reference.
    Image reference;
    if (!o_.reference.empty()) {
        reference = ReadImage(o_.reference);
        std::fprintf(out_, "reference: %s\n", o_.reference.c_str());
    } else {
        const int refSpp = o_.referenceSpp > 0 ? o_.referenceSpp : 8 * ladder_.back();
        // The first reference renderer that renders it, else Prism.
        std::vector<Contender *> order;
        for (size_t i = 1; i < cs_.size(); ++i) order.push_back(&cs_[i]);
        order.push_back(&cs_[0]);
        bool done = false;
        for (Contender *c : order) {
            if (c->failed) continue;
            const std::string image =
                (dir_ / "images" / ("reference-" + c->renderer.name + ".exr")).string();
            ChildRun run;
            std::fprintf(stderr, "rendering the reference: %s at %d spp\n",
                         c->renderer.name.c_str(), refSpp);
            if (Render(*c, refSpp, image, &run)) {
                reference = ReadImage(image);
                std::fprintf(out_, "reference: %s at %d spp (%s s CPU), %s\n",
                             c->renderer.name.c_str(), refSpp, Seconds(run.cpuSeconds).c_str(),
                             image.c_str());
                done = true;
                break;
            }
            std::fprintf(out_, "%s: %s\n", c->renderer.name.c_str(), c->failure.c_str());
        }
        if (!done) throw std::runtime_error("no renderer rendered the reference");
        // Each renderer's noise against its own converged image, and how far that image is
        // from the shared reference (the bias between the renderers, which more samples do not
        // remove).
        if (o_.ownReference)
            for (Contender &c : cs_) {
                if (c.failed) continue;
                const std::string image =
                    (dir_ / "images" / ("reference-" + c.renderer.name + ".exr")).string();
                if (!fs::exists(image)) {
                    ChildRun run;
                    std::fprintf(stderr, "rendering %s's own reference at %d spp\n",
                                 c.renderer.name.c_str(), refSpp);
                    if (!Render(c, refSpp, image, &run)) {
                        std::fprintf(out_, "%s: %s\n", c.renderer.name.c_str(), c.failure.c_str());
                        continue;
                    }
                }
                c.reference = ReadImage(image);
                if (c.reference.width != reference.width ||
                    c.reference.height != reference.height) {
                    c.failed = true;
                    c.failure = "its image is not the reference's size";
                    continue;
                }
                std::fprintf(out_,
                             "%s's own reference at %d spp: rel. RMSE %s against the "
                             "shared one\n",
                             c.renderer.name.c_str(), refSpp,
                             ErrorText(RelativeRmse(c.reference, reference)).c_str());
            }
    }

    for (Contender &c : cs_)
        for (int n : ladder_) c.rungs.push_back({n, {}, {}, std::nan("")});
    for (int rep = 0; rep < o_.repeats; ++rep)
        for (size_t k = 0; k < ladder_.size(); ++k)
            for (Contender &c : cs_) {
                if (c.failed) continue;
                const int n = ladder_[k];
                std::fprintf(stderr, "repeat %d/%d: %s at %d spp\n", rep + 1, o_.repeats,
                             c.renderer.name.c_str(), n);
                ChildRun run;
                const std::string image = ImagePath(c, std::to_string(n));
                if (!Render(c, n, image, &run)) {
                    std::fprintf(out_, "%s: %s\n", c.renderer.name.c_str(), c.failure.c_str());
                    continue;
                }
                c.rungs[k].cpu.push_back(run.cpuSeconds);
                c.rungs[k].wall.push_back(run.wallSeconds);
                if (rep > 0) continue;
                Image img = ReadImage(image);
                if (img.width != reference.width || img.height != reference.height) {
                    c.failed = true;
                    c.failure = "its image is " + std::to_string(img.width) + "x" +
                                std::to_string(img.height) + ", the reference " +
                                std::to_string(reference.width) + "x" +
                                std::to_string(reference.height);
                    std::fprintf(out_, "%s: %s\n", c.renderer.name.c_str(), c.failure.c_str());
                    continue;
                }
                c.rungs[k].error =
                    RelativeRmse(img, c.reference.width > 0 ? c.reference : reference);
            }

    // The table, the CSV and the fits.
    std::string csv = "renderer,spp,repeat,cpu_seconds,wall_seconds,rel_rmse\n";
    std::fprintf(out_,
                 "\n| renderer | spp | CPU s | wall s | rel. RMSE |\n|---|---:|---:|---:|---:|\n");
    std::vector<CompareFit> fits;
    for (const Contender &c : cs_) {
        std::vector<double> t, e;
        std::vector<int> n;
        for (const Contender::Rung &r : c.rungs) {
            for (size_t i = 0; i < r.cpu.size(); ++i)
                csv += c.renderer.name + "," + std::to_string(r.spp) + "," + std::to_string(i) +
                       "," + Fixed(r.cpu[i], 4) + "," + Fixed(r.wall[i], 4) + "," +
                       (std::isfinite(r.error) ? ErrorText(r.error) : std::string("")) + "\n";
            if (r.cpu.empty()) continue;
            std::fprintf(out_, "| %s | %d | %s | %s | %s |\n", c.renderer.name.c_str(), r.spp,
                         Seconds(Median(r.cpu)).c_str(), Seconds(Median(r.wall)).c_str(),
                         std::isfinite(r.error) ? ErrorText(r.error).c_str() : "-");
            t.push_back(Median(r.cpu));
            e.push_back(r.error);
            n.push_back(r.spp);
        }
        fits.push_back(c.failed ? CompareFit{} : FitRenderer(n, e, t));
    }

    // The target error: the first reference renderer's at targetSpp (the scene's own count).
    double target = o_.targetError;
    std::string targetWhy = "--target-error";
    if (!(target > 0)) {
        const int at = o_.targetSpp > 0 ? o_.targetSpp : sceneSpp_;
        const size_t k =
            size_t(std::lower_bound(ladder_.begin(), ladder_.end(), at) - ladder_.begin());
        const size_t rung = std::min(k, ladder_.size() - 1);
        for (size_t i = 1; i <= cs_.size(); ++i) {
            const Contender &c = cs_[i % cs_.size()];  // the references first, then Prism
            if (!c.failed && std::isfinite(c.rungs[rung].error)) {
                target = c.rungs[rung].error;
                targetWhy =
                    c.renderer.name + "'s error at " + std::to_string(ladder_[rung]) + " spp";
                break;
            }
        }
    }
    if (!(target > 0)) throw std::runtime_error("no error measured: nothing to compare");

    std::fprintf(out_, "\ntarget error %s (%s)\n", ErrorText(target).c_str(), targetWhy.c_str());
    std::vector<CompareOutcome> outcomes;
    bool complete = true;
    std::string fitCsv = "renderer,a,b,t0,c,spp_at_target,seconds_at_target\n";
    for (size_t i = 0; i < cs_.size(); ++i) {
        const Contender &c = cs_[i];
        const CompareFit &f = fits[i];
        CompareOutcome oc;
        oc.name = c.renderer.name;
        oc.failed = c.failed;
        std::optional<double> n;
        if (!c.failed) n = SppToError(f.error, target);
        if (n) oc.seconds = f.Seconds(*n);
        if (!oc.seconds) complete = false;
        if (f.error.ok) {
            double lo = INFINITY, hi = 0;
            for (const Contender::Rung &r : c.rungs)
                if (std::isfinite(r.error)) lo = std::min(lo, r.error), hi = std::max(hi, r.error);
            std::fprintf(out_, "%s: error = %s n^%s, CPU = %s s + %s s n; ",
                         c.renderer.name.c_str(), ErrorText(std::exp(f.error.a)).c_str(),
                         Fixed(f.error.b, 3).c_str(), Seconds(f.t0).c_str(),
                         ErrorText(f.c).c_str());
            if (n)
                std::fprintf(out_, "the target at %s spp, %s s%s\n", Fixed(*n, 1).c_str(),
                             Seconds(*oc.seconds).c_str(),
                             target < lo || target > hi
                                 ? " (outside its measured errors: extrapolated)"
                                 : "");
            else
                std::fprintf(out_, "its error stops falling: never at the target\n");
        }
        fitCsv += c.renderer.name + "," + Fixed(f.error.a, 6) + "," + Fixed(f.error.b, 6) + "," +
                  Fixed(f.t0, 6) + "," + ErrorText(f.c) + "," +
                  (n ? Fixed(*n, 3) : std::string("")) + "," +
                  (oc.seconds ? Fixed(*oc.seconds, 4) : std::string("")) + "\n";
        outcomes.push_back(oc);
    }
    WriteText(dir_ / "compare.csv", csv);
    WriteText(dir_ / "fit.csv", fitCsv);
    if (!tempDir_) {
        const std::string script = o_.sourceDir + "/tools/plot_compare.py";
        const std::string python =
            fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : std::string("python3");
        if (fs::exists(script)) {
            ChildRun plot = RunChild({python, script, (dir_ / "compare.csv").string(),
                                      (dir_ / "fit.csv").string(), ErrorText(target),
                                      (dir_ / "compare.png").string()});
            if (plot.exitStatus != 0)
                std::fprintf(stderr, "warning: plotting failed (%s); compare.csv is complete\n",
                             LastLine(plot.err).c_str());
        }
        std::fprintf(out_, "results: %s (compare.csv, fit.csv, compare.png, images/)\n",
                     dir_.string().c_str());
    }
    std::fprintf(out_, "%s\n", EqualErrorLine(target, outcomes).c_str());
    resultOutcomes = outcomes;
    resultTarget = target;
    return complete ? 0 : 3;
}

}  // namespace

int RunCompare(const CompareOptions &options, std::FILE *out, std::vector<CompareOutcome> *outcomes,
               double *target) {
    if (options.threads < 1) throw std::invalid_argument("threads must be at least 1");
    if (options.repeats < 1) throw std::invalid_argument("repeats must be at least 1");
    CompareRun run(options, out);
    const int status = run.Run();
    if (outcomes) *outcomes = run.resultOutcomes;
    if (target) *target = run.resultTarget;
    return status;
}

}  // namespace prism
