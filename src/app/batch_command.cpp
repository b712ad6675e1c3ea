// `prism batch LIST|DIR -o OUTDIR [--jobs N] [--force] [--format png|exr]`: renders many
// scenes unattended. Each scene renders in its own child process (`prism render`), so a scene
// that crashes or runs out of memory cannot take the batch or the finished images with it.
// report.json and summary.txt are rewritten (atomically) after every scene. The parts that
// `prism-mpi batch` shares are declared in app/batch_jobs.h.
#include <fcntl.h>
#include <fmt/core.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

#include "app/batch_jobs.h"
#include "app/commands.h"
#include "app/common.h"
#include "core/file_io.h"
#include "core/memory.h"
#include "core/output_file.h"
#include "render/integrator.h"
#include "scene/load_scene.h"

namespace fs = std::filesystem;

namespace prism {

namespace {

bool IsSceneFile(const fs::path &p) { return IsSceneExtension(p.extension().string()); }

// Files that the collected scenes name (includes, meshes, textures): not scenes of their own.
std::set<std::string> ReferencedByScenes(const std::vector<std::string> &scenes) {
    std::set<std::string> referenced;
    for (const std::string &s : scenes)
        for (std::string &f : ReferencedFiles(s)) referenced.insert(std::move(f));
    return referenced;
}

std::vector<std::string> CollectScenes(const std::string &input) {
    std::vector<std::string> scenes;
    if (fs::is_directory(input)) {
        for (const auto &e : fs::recursive_directory_iterator(input))
            if (e.is_regular_file() && IsSceneFile(e.path())) scenes.push_back(e.path().string());
        std::sort(scenes.begin(), scenes.end());
        std::set<std::string> referenced = ReferencedByScenes(scenes);
        std::erase_if(scenes,
                      [&](const std::string &s) { return referenced.count(CanonicalPath(s)) > 0; });
        return scenes;
    }
    std::ifstream in(input);
    if (!in) throw UsageError("cannot open scene list or directory \"" + input + "\"");
    fs::path base = fs::path(input).parent_path();
    std::string line;
    while (std::getline(in, line)) {
        line = line.substr(0, line.find('#'));
        line.erase(0, line.find_first_not_of(" \t\r"));
        line.erase(line.find_last_not_of(" \t\r") + 1);
        if (line.empty()) continue;
        fs::path p(line);
        scenes.push_back(p.is_absolute() || base.empty() ? p.string() : (base / p).string());
    }
    return scenes;
}

// Output names: the scene's path relative to the common root with separators replaced, so
// scenes with the same file name in different folders do not collide.
std::vector<std::string> OutputNames(const std::vector<std::string> &scenes,
                                     const std::string &ext) {
    std::vector<std::string> names;
    std::set<std::string> used;
    for (const std::string &s : scenes) {
        fs::path p(s);
        std::string stem = p.parent_path().filename().string() + "_" + p.stem().string();
        if (stem.front() == '_') stem.erase(0, 1);
        std::string name = stem + "." + ext;
        for (int k = 2; used.count(name); ++k) name = stem + "-" + std::to_string(k) + "." + ext;
        used.insert(name);
        names.push_back(name);
    }
    return names;
}

// The length of the well-formed UTF-8 sequence at s[i] (1-4), or 0 when the byte there does
// not start one (a stray continuation byte, an overlong form, a surrogate, past U+10FFFF).
size_t Utf8SequenceAt(const std::string &s, size_t i) {
    auto byte = [&](size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
    auto cont = [&](size_t k) { return (byte(k) & 0xc0) == 0x80; };
    unsigned b = byte(i);
    if (b < 0x80) return 1;
    if (b >= 0xc2 && b <= 0xdf) return cont(i + 1) ? 2 : 0;
    if (b >= 0xe0 && b <= 0xef) {
        unsigned b1 = byte(i + 1);
        if ((b == 0xe0 && b1 < 0xa0) || (b == 0xed && b1 >= 0xa0)) return 0;
        return cont(i + 1) && cont(i + 2) ? 3 : 0;
    }
    if (b >= 0xf0 && b <= 0xf4) {
        unsigned b1 = byte(i + 1);
        if ((b == 0xf0 && b1 < 0x90) || (b == 0xf4 && b1 >= 0x90)) return 0;
        return cont(i + 1) && cont(i + 2) && cont(i + 3) ? 4 : 0;
    }
    return 0;
}

// A JSON string's contents: quotes, backslashes and control characters escaped, and every
// byte that is not part of well-formed UTF-8 (a file name in Latin-1, say) written as
// \u00XX, so report.json is valid UTF-8 whatever the names hold.
std::string JsonEscape(const std::string &s) {
    std::string o;
    for (size_t i = 0; i < s.size();) {
        char c = s[i];
        size_t n = Utf8SequenceAt(s, i);
        if (n == 0) {
            o += fmt::format("\\u{:04x}", int(static_cast<unsigned char>(c)));
            ++i;
            continue;
        }
        if (n > 1) {
            o.append(s, i, n);
            i += n;
            continue;
        }
        ++i;
        switch (c) {
            case '"':
                o += "\\\"";
                break;
            case '\\':
                o += "\\\\";
                break;
            case '\n':
                o += "\\n";
                break;
            case '\t':
                o += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                    o += fmt::format("\\u{:04x}", int(c));
                else
                    o += c;
        }
    }
    return o;
}

}  // namespace

int FinishReports(const BatchArgs &a, const std::vector<Job> &jobs, double wallSeconds,
                  const std::string &endedBy) {
    WriteReports(a.outDir, jobs, wallSeconds, /*sync=*/true, endedBy);
    int failed = 0;
    for (const Job &j : jobs) failed += j.status == "failed" || j.status == "timeout";
    if (!a.quiet) {
        std::ifstream s(fs::path(a.outDir) / "summary.txt");
        std::stringstream ss;
        ss << s.rdbuf();
        std::fprintf(stderr, "%s", ss.str().c_str());
    }
    return failed;
}

void WriteReports(const std::string &outDir, const std::vector<Job> &jobs, double wallSeconds,
                  bool sync, const std::string &endedBy) {
    std::map<std::string, int> counts;
    double renderSum = 0;
    for (const Job &j : jobs) {
        counts[j.status]++;
        if (j.renderSeconds > 0) renderSum += j.renderSeconds;
    }
    std::string json = "{\n  \"scenes\": [\n";
    for (size_t i = 0; i < jobs.size(); ++i) {
        const Job &j = jobs[i];
        json += fmt::format(
            "    {{\"scene\": \"{}\", \"output\": \"{}\", \"status\": \"{}\", "
            "\"seconds\": {:.3f}, \"exit_code\": {}, \"error\": \"{}\", ",
            JsonEscape(j.scene), JsonEscape(j.output), j.status, j.seconds, j.exitCode,
            JsonEscape(j.error));
        if (j.rank >= 0) json += fmt::format("\"rank\": {}, ", j.rank);
        if (j.peakRssKiB >= 0)
            json += fmt::format("\"peak_rss_kib\": {}, \"end_seconds\": {:.3f}, ", j.peakRssKiB,
                                j.endSeconds);
        if (j.renderSeconds >= 0)
            json += fmt::format(
                "\"phases\": {{\"parse\": {:.3f}, \"setup\": {:.3f}, \"bvh\": {:.3f}, "
                "\"render\": {:.3f}}}, ",
                j.parseSeconds, j.setupSeconds, j.bvhSeconds, j.renderSeconds);
        json += "\"warnings\": [";
        for (size_t k = 0; k < j.warnings.size(); ++k)
            json += (k ? ", \"" : "\"") + JsonEscape(j.warnings[k]) + "\"";
        json += std::string("]}") + (i + 1 < jobs.size() ? ",\n" : "\n");
    }
    json += "  ],\n  \"summary\": {";
    bool first = true;
    for (const char *k : {"ok", "skipped", "failed", "timeout", "interrupted", "pending"}) {
        json += fmt::format("{}\"{}\": {}", first ? "" : ", ", k, counts[k]);
        first = false;
    }
    json += "},\n";
    if (!endedBy.empty()) json += fmt::format("  \"ended_by\": \"{}\",\n", JsonEscape(endedBy));
    json += fmt::format("  \"wall_seconds\": {:.3f}, \"render_seconds\": {:.3f}\n}}\n", wallSeconds,
                        renderSum);
    WriteFileAtomically((fs::path(outDir) / "report.json").string(), json, sync);

    std::string txt =
        fmt::format("{:<11} {:>8}  {:>5}  {}\n", "status", "seconds", "warn", "scene");
    for (const Job &j : jobs) {
        // Names from the scenes' folder: control characters escaped, as on the terminal.
        txt += fmt::format("{:<11} {:>8.2f}  {:>5}  {}\n", j.status, j.seconds, j.warnings.size(),
                           EscapeControlChars(j.scene));
        if (!j.error.empty()) txt += "            error: " + EscapeControlChars(j.error) + "\n";
    }
    txt += fmt::format(
        "\n{} ok, {} skipped (up to date), {} failed, {} timed out, {} interrupted, {} not run\n",
        counts["ok"], counts["skipped"], counts["failed"], counts["timeout"], counts["interrupted"],
        counts["pending"]);
    if (!endedBy.empty()) txt += "batch stopped early: " + EscapeControlChars(endedBy) + "\n";
    txt +=
        fmt::format("batch {:.2f} s; the renders' render phases add up to {:.2f} s ({:.0f}%)\n",
                    wallSeconds, renderSum, wallSeconds > 0 ? 100 * renderSum / wallSeconds : 0.0);
    WriteFileAtomically((fs::path(outDir) / "summary.txt").string(), txt, sync);
}

std::string RunningExecutable() {
    std::error_code ec;
    fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot locate the prism executable");
    return p.string();
}

void Launch(Job &j, const BatchArgs &a, const std::string &exe, int threadsPerJob,
            bool dieWithParent) {
    // The log is a new file with a random name (O_EXCL | O_NOFOLLOW: core/output_file.h) in
    // the folder the caller chose or the output's.
    const int logFd =
        CreateUniqueFile(j.logDir.empty() ? fs::path(j.output).parent_path().string() : j.logDir,
                         ".log.tmp", &j.logPath);
    std::vector<std::string> args = {exe, "render", j.scene, "-o", j.output, "--no-progress"};
    if (a.spp > 0) {
        args.push_back("--spp");
        args.push_back(std::to_string(a.spp));
    }
    if (!a.res.empty()) {
        args.push_back("--res");
        args.push_back(a.res);
    }
    if (a.effects != "scene") {
        args.push_back("--effects");
        args.push_back(a.effects);
    }
    for (auto [flag, value] : {std::pair{"--exposure", &a.exposure},
                               {"--tonemap", &a.toneMap},
                               {"--env", &a.env},
                               {"--env-rotate", &a.envRotate},
                               {"--env-mode", &a.envMode},
                               {"--time-limit", &a.timeLimit},
                               {"--integrator", &a.integrator},
                               {"--texture-filter", &a.textureFilter},
                               {"--pbrt-version", &a.pbrtVersion}})
        if (!value->empty()) {
            args.push_back(flag);
            args.push_back(*value);
        }
    // Concurrent renders share the default budget, so together they stay within it.
    std::string budget = a.maxMemory;
    if (budget.empty() && a.jobs > 1)
        budget = std::to_string(DefaultMemoryBudget() / uint64_t(a.jobs));
    if (!budget.empty()) {
        args.push_back("--max-memory");
        args.push_back(budget);
    }
    args.push_back("--threads");
    args.push_back(std::to_string(threadsPerJob));
    if (a.confine.Given()) args.push_back("--confine=" + ConfinementFolderFor(a.confine, j.scene));
    j.start = std::chrono::steady_clock::now();
    const pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        ::close(logFd);
        throw std::runtime_error("cannot start a render process");
    }
    if (pid == 0) {
        // The render dies with the batch (SIGKILL of the batch, the OOM killer): set before
        // exec, and the parent checked afterwards in case it died before this line.
        prctl(PR_SET_PDEATHSIG, dieWithParent ? SIGTERM : SIGKILL);
        if (getppid() != parent) _exit(127);
        if (::dup2(logFd, STDERR_FILENO) < 0) _exit(127);
        std::freopen("/dev/null", "w", stdout);
        std::vector<char *> argv;
        for (auto &s : args) argv.push_back(s.data());
        argv.push_back(nullptr);
        execv(exe.c_str(), argv.data());
        _exit(127);
    }
    ::close(logFd);
    j.pid = pid;
    j.status = "running";
}

void Finish(Job &j, int status, const struct rusage &usage, bool interrupted,
            double timeoutSeconds) {
    j.seconds = SecondsSince(j.start);
    j.peakRssKiB = usage.ru_maxrss;
    std::ifstream log(j.logPath);
    std::string line;
    while (std::getline(log, line)) {
        double p, su, b, r;
        if (std::sscanf(line.c_str(), "time: parse %lfs, setup %lfs, BVH build %lfs, render %lfs",
                        &p, &su, &b, &r) == 4) {
            j.parseSeconds = p, j.setupSeconds = su, j.bvhSeconds = b, j.renderSeconds = r;
            continue;
        }
        if (line.find("warning:") != std::string::npos)
            j.warnings.push_back(line);
        else if (line.find("error:") != std::string::npos && j.error.empty())
            j.error = line;
    }
    std::error_code ec;
    fs::remove(j.logPath, ec);
    if (j.timedOut && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        j.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        j.status = "timeout";
        j.error =
            "render still running after " + fmt::format("{:g}", timeoutSeconds) +
            " s (--scene-timeout): stopped with SIGTERM" +
            (j.killedAfterTimeout ? fmt::format(", then SIGKILL after {:g} s", kSceneTimeoutGrace)
                                  : std::string()) +
            "; no image written";
    } else if (WIFEXITED(status)) {
        j.exitCode = WEXITSTATUS(status);
        j.status =
            j.exitCode == 0 ? "ok" : (j.exitCode == ExitInterrupted ? "interrupted" : "failed");
        if (j.status == "failed" && j.error.empty())
            j.error = "exit status " + std::to_string(j.exitCode);
    } else if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        j.exitCode = 128 + sig;
        j.status = ((sig == SIGINT || sig == SIGTERM) && interrupted) ? "interrupted" : "failed";
        if (j.status == "failed") {
            const char *abbrev = sigabbrev_np(sig);
            j.error = "render process killed by signal " +
                      (abbrev ? "SIG" + std::string(abbrev) : std::to_string(sig)) + " (" +
                      strsignal(sig) + ")";
            if (sig == SIGKILL) j.error += "; out of memory? The kernel's OOM killer sends SIGKILL";
        }
    }
    j.pid = -1;
}

std::vector<Job> PrepareBatch(const BatchArgs &a) {
    if (a.format != "png" && a.format != "exr") throw UsageError("--format must be png or exr");
    std::vector<std::string> scenes = CollectScenes(a.input);
    if (scenes.empty()) throw UsageError("no scenes found in \"" + a.input + "\"");
    ParseMaxMemory(a.maxMemory);  // a bad value is a usage error now, not one per scene
    if (!a.env.empty())           // likewise a missing map or a bad R,G,B
        ParseEnvironment(a.env, a.envRotate.empty() ? 0.0 : std::stod(a.envRotate), a.envMode);
    else if (!a.envRotate.empty() || !a.envMode.empty())
        throw UsageError("--env-rotate and --env-mode need --env");
    std::error_code ec;
    fs::create_directories(a.outDir, ec);
    if (!fs::is_directory(a.outDir))
        throw UsageError("cannot create output directory \"" + a.outDir + "\"");
    CheckWritableDirectory(a.outDir);  // read-only or full: say so before any render
    if (a.confine.Given() && !a.confine.dir.empty()) ConfinementFolderFor(a.confine, "");
    std::vector<std::string> names = OutputNames(scenes, a.format);
    std::vector<Job> jobs(scenes.size());
    for (size_t i = 0; i < scenes.size(); ++i) {
        jobs[i].scene = scenes[i];
        jobs[i].output = (fs::path(a.outDir) / names[i]).string();
        // Up to date: the output is newer than the scene file (included files are not
        // tracked; use --force after editing them).
        if (!a.force && fs::exists(jobs[i].output) && fs::exists(scenes[i]) &&
            fs::last_write_time(jobs[i].output) >= fs::last_write_time(scenes[i]))
            jobs[i].status = "skipped";
    }
    return jobs;
}

namespace {

volatile sig_atomic_t g_interrupted = 0;  // SIGINT or SIGTERM: no new renders
volatile sig_atomic_t g_signal = 0;       // the last of them
void OnStopSignal(int sig) {
    g_interrupted = 1;
    g_signal = sig;
}

int RunBatch(const BatchArgs &a) {
    std::vector<Job> jobs = PrepareBatch(a);
    std::string exe = RunningExecutable();
    int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    int nJobs = std::max(1, a.jobs);
    int threadsPerJob = a.threads > 0 ? a.threads : std::max(1, cores / nJobs);

    struct sigaction sa {};
    sa.sa_handler = OnStopSignal;
    sigemptyset(&sa.sa_mask);
    struct sigaction oldInt {
    }, oldTerm{};
    sigaction(SIGINT, &sa, &oldInt);
    sigaction(SIGTERM, &sa, &oldTerm);

    size_t next = 0;
    int running = 0;
    int forwarded = 0;  // the signal last passed on to the renders
    const auto batchStart = std::chrono::steady_clock::now();
    WriteReports(a.outDir, jobs, 0);
    while (true) {
        while (!g_interrupted && running < nJobs && next < jobs.size()) {
            Job &j = jobs[next++];
            if (j.status != "pending") continue;
            if (!a.quiet)
                std::fprintf(stderr, "batch: rendering %s\n", EscapeControlChars(j.scene).c_str());
            Launch(j, a, exe, threadsPerJob);
            ++running;
        }
        if (running == 0) break;
        int status = 0;
        struct rusage usage {};
        // Polled, so that the scene timeouts are kept while renders run: the wake-ups cost
        // nothing beside a render.
        pid_t pid = wait4(-1, &status, WNOHANG, &usage);
        if (pid == 0 || (pid < 0 && errno == EINTR)) {
            // Pass SIGINT or SIGTERM on to the running renders; they stop without writing.
            if (g_interrupted && g_signal != forwarded) {
                forwarded = g_signal;
                for (Job &j : jobs)
                    if (j.pid > 0) kill(j.pid, forwarded);
            }
            const auto now = std::chrono::steady_clock::now();
            for (Job &j : jobs) {
                if (j.pid <= 0 || a.sceneTimeout <= 0) continue;
                if (!j.timedOut && SecondsSince(j.start) > a.sceneTimeout) {
                    j.timedOut = true;
                    j.timeoutSent = now;
                    kill(j.pid, SIGTERM);
                } else if (j.timedOut && !j.killedAfterTimeout &&
                           std::chrono::duration<double>(now - j.timeoutSent).count() >
                               kSceneTimeoutGrace) {
                    j.killedAfterTimeout = true;
                    kill(j.pid, SIGKILL);
                }
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        if (pid < 0) break;
        for (Job &j : jobs) {
            if (j.pid != pid) continue;
            Finish(j, status, usage, g_interrupted, a.sceneTimeout);
            j.endSeconds = SecondsSince(batchStart);
            --running;
            if (!a.quiet)
                std::fprintf(stderr, "batch: %s %s (%.1fs)%s%s\n", j.status.c_str(),
                             EscapeControlChars(j.scene).c_str(), j.seconds,
                             j.error.empty() ? "" : ": ", EscapeControlChars(j.error).c_str());
            // A full disk must not stop the batch: the previous report stays (atomic
            // writes) and the next scene tries again; the final write below must succeed.
            try {
                WriteReports(a.outDir, jobs, SecondsSince(batchStart));
            } catch (const std::runtime_error &e) {
                std::fprintf(stderr, "warning: %s; the batch goes on\n", e.what());
            }
        }
    }
    sigaction(SIGINT, &oldInt, nullptr);
    sigaction(SIGTERM, &oldTerm, nullptr);
    std::string endedBy;
    if (g_interrupted)
        endedBy = g_signal == SIGTERM ? "SIGTERM: the running renders were stopped, the scenes "
                                        "not started are pending"
                                      : "SIGINT: the running renders were stopped, the scenes "
                                        "not started are pending";
    int failed = FinishReports(a, jobs, SecondsSince(batchStart), endedBy);
    if (g_interrupted) return ExitInterrupted;
    return failed > 0 ? ExitBadInput : ExitOk;
}

}  // namespace

void AddBatchOptions(CLI::App *cmd, BatchArgs *args) {
    cmd->add_option("input", args->input,
                    "A directory (searched recursively) or a file listing scenes, one per line")
        ->required();
    cmd->add_option("-o,--output", args->outDir,
                    "Output directory for images, report.json and summary.txt")
        ->required();
    cmd->add_option("--jobs", args->jobs, "Scenes rendered at once (cores are shared between them)")
        ->check(CLI::Range(1, 256));
    cmd->add_flag("--force", args->force, "Re-render scenes whose output is up to date");
    cmd->add_option("--format", args->format, "Image format: png or exr")
        ->check(CLI::IsMember({"png", "exr"}));
    cmd->add_option("--spp", args->spp, "Samples per pixel for every scene")
        ->check(CLI::Range(1, 1 << 16));
    cmd->add_option("--res", args->res, "Resolution WxH for every scene");
    cmd->add_option("--threads", args->threads, "Threads per scene (default: cores / jobs)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--max-memory", args->maxMemory,
                    "Memory budget of each render, e.g. 4G (default: 75% of RAM)");
    AddConfineOption(cmd, &args->confine);
    AddPbrtVersionOption(cmd, &args->pbrtVersion);
    cmd->add_option("--effects", args->effects,
                    "Kernel for every scene: \"scene\" (specialized) or \"all\" (general)")
        ->check(CLI::IsMember({"scene", "all"}));
    cmd->add_option("--exposure", args->exposure,
                    "Exposure in EV for every scene (2^EV), or auto (as prism render)")
        ->check(CheckExposureText);
    cmd->add_option("--tonemap", args->toneMap,
                    "Tone map of PNG outputs: none, neutral, aces or filmic (default: per scene "
                    "format, as prism render)")
        ->check(CLI::IsMember({"none", "neutral", "aces", "filmic"}));
    cmd->add_option("--env", args->env,
                    "Environment light for every scene: FILE.exr|hdr or R,G,B (as prism render)");
    cmd->add_option("--env-rotate", args->envRotate, "Turn the --env map by DEG about up")
        ->check(CLI::Number);
    cmd->add_option("--env-mode", args->envMode, "replace (default) or add")
        ->check(CLI::IsMember({"replace", "add"}));
    cmd->add_option("--integrator", args->integrator,
                    "Integrator for every scene: whitted, distribution, directlighting, path, "
                    "volpath or ambientocclusion (as prism render; default: each scene's)")
        ->check(CLI::IsMember(IntegratorNames()));
    cmd->add_option("--texture-filter", args->textureFilter,
                    "Image-texture lookups for every scene: ewa, trilinear, bilinear, point or "
                    "none (as prism render)")
        ->check(CLI::IsMember(TextureFilterNames));
    cmd->add_option("--time-limit", args->timeLimit,
                    "Seconds per scene: each renders in progressive passes until its time runs "
                    "out (or --spp is reached), as prism render --time-limit")
        ->check(CLI::Range(1e-3, 1e9));
    cmd->add_flag("-q,--quiet", args->quiet, "No progress lines");
}

void AddBatchCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<BatchArgs>();
    CLI::App *cmd = app.add_subcommand(
        "batch", "Render many scenes; keeps going past failures and writes a report");
    AddBatchOptions(cmd, args.get());
    cmd->add_option("--scene-timeout", args->sceneTimeout,
                    "Seconds each scene's render may take (default 3600; 0: no limit); one "
                    "past it is stopped (SIGTERM, SIGKILL 5 s later), reported \"timeout\", "
                    "and the batch goes on")
        ->check(CLI::Range(0.0, 1e9));
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunBatch(*args); }); });
}

}  // namespace prism
