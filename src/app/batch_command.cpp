// `prism batch LIST|DIR -o OUTDIR [--jobs N] [--force] [--format png|exr]`: renders many
// scenes unattended, each in its own `prism render` process (app/batch_jobs.h).
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "app/batch_jobs.h"
#include "app/commands.h"
#include "app/common.h"

namespace fs = std::filesystem;

namespace prism {

namespace {

volatile sig_atomic_t g_interrupted = 0;
void OnSigint(int) { g_interrupted = 1; }

int RunBatch(const BatchArgs &a) {
    std::vector<Job> jobs = PrepareBatch(a);
    std::string exe = RunningExecutable();
    int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    int nJobs = std::max(1, a.jobs);
    int threadsPerJob = a.threads > 0 ? a.threads : std::max(1, cores / nJobs);

    struct sigaction sa {};
    sa.sa_handler = OnSigint;
    sigemptyset(&sa.sa_mask);
    struct sigaction old {};
    sigaction(SIGINT, &sa, &old);

    size_t next = 0;
    int running = 0;
    const auto batchStart = std::chrono::steady_clock::now();
    WriteReports(a.outDir, jobs, 0);
    while (true) {
        while (!g_interrupted && running < nJobs && next < jobs.size()) {
            Job &j = jobs[next++];
            if (j.status != "pending") continue;
            if (!a.quiet) std::fprintf(stderr, "batch: rendering %s\n", j.scene.c_str());
            Launch(j, a, exe, threadsPerJob);
            ++running;
        }
        if (running == 0) break;
        int status = 0;
        struct rusage usage {};
        pid_t pid = wait4(-1, &status, 0, &usage);
        if (pid < 0) {
            if (errno == EINTR) {
                // Forward the interrupt to running renders; they stop without writing.
                for (Job &j : jobs)
                    if (j.pid > 0) kill(j.pid, SIGINT);
                continue;
            }
            break;
        }
        for (Job &j : jobs) {
            if (j.pid != pid) continue;
            Finish(j, status, usage, g_interrupted);
            j.endSeconds = SecondsSince(batchStart);
            --running;
            if (!a.quiet)
                std::fprintf(stderr, "batch: %s %s (%.1fs)%s%s\n", j.status.c_str(),
                             j.scene.c_str(), j.seconds, j.error.empty() ? "" : ": ",
                             j.error.c_str());
            // A full disk must not stop the batch: the previous report stays (atomic
            // writes) and the next scene tries again; the final write below must succeed.
            try {
                WriteReports(a.outDir, jobs, SecondsSince(batchStart));
            } catch (const std::runtime_error &e) {
                std::fprintf(stderr, "warning: %s; the batch goes on\n", e.what());
            }
        }
    }
    sigaction(SIGINT, &old, nullptr);
    WriteReports(a.outDir, jobs, SecondsSince(batchStart));
    int failed = 0;
    for (const Job &j : jobs) failed += j.status == "failed";
    if (!a.quiet) {
        std::ifstream s(fs::path(a.outDir) / "summary.txt");
        std::stringstream ss;
        ss << s.rdbuf();
        std::fprintf(stderr, "%s", ss.str().c_str());
    }
    if (g_interrupted) return ExitInterrupted;
    return failed > 0 ? ExitBadInput : ExitOk;
}

}  // namespace

void AddBatchCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<BatchArgs>();
    CLI::App *cmd = app.add_subcommand(
        "batch", "Render many scenes; keeps going past failures and writes a report");
    AddBatchOptions(cmd, args.get());
    cmd->callback([args, exitCode] { *exitCode = RunGuarded([&] { return RunBatch(*args); }); });
}

}  // namespace prism
