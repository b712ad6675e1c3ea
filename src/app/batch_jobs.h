// `prism batch`'s options, scene list, render processes and reports, shared by `prism batch`
// and `prism-mpi batch` (src/tools/mpi): each scene renders in its own child process (`prism
// render`), so a scene that crashes or runs out of memory cannot take the batch or the finished
// images with it; report.json and summary.txt are rewritten (atomically) after every scene.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

#include "app/common.h"

struct rusage;

namespace CLI {
class App;
}

namespace prism {

struct BatchArgs {
    std::string input, outDir, format = "png";
    int jobs = 1, spp = 0, threads = 0;
    std::string res, maxMemory;
    std::string effects = "scene";  // passed on to each render (--effects)
    bool force = false, quiet = false;
    ConfineOption confine;  // --confine [DIR]: each scene confined to DIR or its own folder
    // Passed on to every `prism render` (empty: not given).
    std::string exposure, toneMap, env, envRotate, envMode, timeLimit, integrator, textureFilter,
        pbrtVersion;
    // `prism batch --scene-timeout S`: a render still running after S seconds is stopped
    // (SIGTERM, then SIGKILL after kSceneTimeoutGrace) and reported "timeout"; 0: no limit.
    double sceneTimeout = 3600;
};

// Seconds between the SIGTERM that ends a render past --scene-timeout and the SIGKILL.
inline constexpr double kSceneTimeoutGrace = 5;

struct Job {
    std::string scene, output;
    std::string status = "pending";  // ok, failed, skipped, interrupted, timeout
    double seconds = 0;              // whole child process
    // The child's own phases, from its statistics line; negative when it printed none.
    double parseSeconds = -1, setupSeconds = -1, bvhSeconds = -1, renderSeconds = -1;
    int exitCode = 0;
    long peakRssKiB = -1;
    double endSeconds = -1;  // when it finished, from the batch's start (the soak's clock)  // the
                             // render process's peak resident memory (wait4), -1: unknown
    std::vector<std::string> warnings;
    std::string error;
    int rank = -1;  // prism-mpi: the rank that rendered it (-1: not written to the report)
    pid_t pid = -1;
    // --scene-timeout: when the SIGTERM was sent (timedOut) and whether SIGKILL followed.
    bool timedOut = false, killedAfterTimeout = false;
    std::chrono::steady_clock::time_point timeoutSent;
    std::string logPath;  // set by Launch
    // The folder of the render log: "" for the output's folder (prism-mpi: the node's
    // temporary folder, so a rank that dies leaves nothing among the images).
    std::string logDir;
    std::chrono::steady_clock::time_point start;
};

// Registers the batch options on `cmd` (its positionals included).
void AddBatchOptions(CLI::App *cmd, BatchArgs *args);
// Checks the options (UsageError), collects the scenes, creates the output directory and marks
// the scenes whose output is up to date as skipped.
std::vector<Job> PrepareBatch(const BatchArgs &a);
// Rewrites report.json and summary.txt in a.outDir atomically; `sync` (the final reports,
// FinishReports) also fsyncs them (core/output_file.h).
// `endedBy`, when not empty, says why the batch stopped early (e.g. "SIGTERM"): report.json's
// "ended_by" and a line of summary.txt.
void WriteReports(const std::string &outDir, const std::vector<Job> &jobs, double wallSeconds,
                  bool sync = false, const std::string &endedBy = "");
// The end of a batch: the final reports, the summary on stderr (unless quiet); returns the
// number of failed (or timed-out) scenes.
int FinishReports(const BatchArgs &a, const std::vector<Job> &jobs, double wallSeconds,
                  const std::string &endedBy = "");
// The running executable (/proc/self/exe).
std::string RunningExecutable();
// Starts `exe render` for j in a child process (stderr to j.logPath, a new
// `.prism-<pid>-XXXXXX.log.tmp` with a random suffix in j.logDir or else the output's folder,
// created O_EXCL | O_NOFOLLOW: neither guessable nor followed through a symbolic link).
// The child is killed when this process dies (PR_SET_PDEATHSIG: SIGTERM with dieWithParent,
// prism-mpi's ranks, else SIGKILL), so no render outlives a batch that was killed.
void Launch(Job &j, const BatchArgs &a, const std::string &exe, int threadsPerJob,
            bool dieWithParent = false);
// Records the child's end: status, phases and warnings from its log. `interrupted`: the batch
// was interrupted (a render ended by SIGINT is then "interrupted", not "failed").
// A render stopped for --scene-timeout (j.timedOut) is "timeout", with timeoutSeconds in its
// error, unless it exited 0 (it finished writing as the limit came).
void Finish(Job &j, int status, const struct rusage &usage, bool interrupted,
            double timeoutSeconds = 0);

}  // namespace prism
