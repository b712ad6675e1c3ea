// `prism-mpi batch`: rank 0 hands out the scenes one at a time on request and keeps
// report.json and summary.txt (rewritten after every scene, as `prism batch` does); the other
// ranks render each scene in a child `prism render` process, as `prism batch` does, so the
// image is written (atomically) where it was rendered, and send back the scene's record.
#include <fmt/core.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "app/commands.h"
#include "tools/mpi/mpi_comm.h"
#include "tools/mpi/mpi_commands.h"

namespace fs = std::filesystem;

namespace prism::mpi {

namespace {

// The record a worker sends for a finished scene: the fields of report.json it measured.
void PutRecord(Writer &w, int32_t index, const Job &j) {
    w.Put(index);
    w.PutString(j.status);
    w.Put(j.seconds), w.Put(j.parseSeconds), w.Put(j.setupSeconds), w.Put(j.bvhSeconds),
        w.Put(j.renderSeconds);
    w.Put(int32_t(j.exitCode));
    w.Put(int64_t(j.peakRssKiB));
    w.PutString(j.error);
    w.Put(uint64_t(j.warnings.size()));
    for (const std::string &s : j.warnings) w.PutString(s);
}

void GetRecord(Reader &r, Job *j) {
    j->status = r.GetString();
    j->seconds = r.Get<double>(), j->parseSeconds = r.Get<double>(),
    j->setupSeconds = r.Get<double>(), j->bvhSeconds = r.Get<double>(),
    j->renderSeconds = r.Get<double>();
    j->exitCode = r.Get<int32_t>();
    j->peakRssKiB = long(r.Get<int64_t>());
    j->error = r.GetString();
    j->warnings.resize(size_t(r.Get<uint64_t>()));
    for (std::string &s : j->warnings) s = r.GetString();
}

// `prism` beside this executable: the render processes are plain `prism render`s.
std::string PrismExecutable() {
    fs::path p = fs::path(RunningExecutable()).parent_path() / "prism";
    if (!fs::exists(p))
        throw std::runtime_error("cannot find the prism executable beside prism-mpi (" +
                                 p.string() + ")");
    return p.string();
}

void RunWorker(const BatchArgs &a, const std::string &exe) {
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    const int nJobs = std::max(1, a.jobs);
    const int threadsPerJob = a.threads > 0 ? a.threads : std::max(1, cores / nJobs);
    std::map<pid_t, std::pair<int32_t, Job>> running;
    bool more = true;
    Message m;
    while (true) {
        while (more && int(running.size()) < nJobs) {
            Send(0, TagRequest, {});
            if (!Receive(&m, 0, TagAssign)) return;
            Reader r(m.bytes);
            int32_t index = r.Get<int32_t>();
            if (index < 0) {
                more = false;
                break;
            }
            Job j;
            j.scene = r.GetString();
            j.output = r.GetString();
            // The render's log stays on this node, so a rank that dies leaves nothing in the
            // output folder but finished images.
            // Its name is random (CreateUniqueFile): no other user of the folder can guess it
            // and plant a link or a file there first.
            j.logDir = fs::temp_directory_path().string();
            Launch(j, a, exe, threadsPerJob, /*dieWithParent=*/true);
            running.emplace(j.pid, std::pair{index, std::move(j)});
        }
        if (running.empty()) break;
        int status = 0;
        struct rusage usage {};
        pid_t pid = wait4(-1, &status, 0, &usage);
        if (pid < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error("lost track of the render processes");
        }
        auto it = running.find(pid);
        if (it == running.end()) continue;
        Finish(it->second.second, status, usage, false);
        Writer w;
        PutRecord(w, it->second.first, it->second.second);
        Send(0, TagResult, w.Bytes());
        running.erase(it);
    }
    Send(0, TagDone, {});
}

int Coordinate(const BatchArgs &a, std::vector<Job> &jobs) {
    const int size = Size();
    const auto batchStart = std::chrono::steady_clock::now();
    size_t next = 0;
    int working = size - 1;
    auto writeReports = [&] {
        // A full disk must not stop the batch: the previous report stays (atomic writes)
        // and the next scene tries again; the final write must succeed.
        try {
            WriteReports(a.outDir, jobs, SecondsSince(batchStart));
        } catch (const std::runtime_error &e) {
            std::fprintf(stderr, "warning: %s; the batch goes on\n", e.what());
        }
    };
    WriteReports(a.outDir, jobs, 0);
    Message m;
    while (working > 0) {
        if (!Receive(&m)) {
            // mpirun sends SIGTERM to every rank when one dies: keep the report, with the
            // scenes in progress marked, and say what is left.
            int ok = 0;
            std::string lost;
            for (Job &j : jobs) {
                ok += j.status == "ok";
                if (j.status != "running") continue;
                j.status = "interrupted";
                j.error = "rank " + std::to_string(j.rank) + " ended before finishing it";
                lost += fmt::format("{}{} (rank {})", lost.empty() ? "" : ", ", j.scene, j.rank);
            }
            WriteReports(a.outDir, jobs, SecondsSince(batchStart));
            std::fprintf(stderr,
                         "prism-mpi: batch ended early (a rank died or the job was cancelled; "
                         "mpirun names the rank): %d images finished and kept, report.json "
                         "written%s%s\n",
                         ok, lost.empty() ? "" : "; not finished: ", lost.c_str());
            return ExitInterrupted;
        }
        Reader r(m.bytes);
        if (m.tag == TagRequest) {
            while (next < jobs.size() && jobs[next].status != "pending") ++next;
            Writer w;
            if (next < jobs.size()) {
                Job &j = jobs[next];
                j.status = "running";
                j.rank = m.source;
                if (!a.quiet)
                    std::fprintf(stderr, "batch: rendering %s (rank %d)\n", j.scene.c_str(),
                                 m.source);
                w.Put(int32_t(next));
                w.PutString(j.scene);
                w.PutString(j.output);
                ++next;
                // Recorded at once: should rank 0 be killed before it can say so, the report
                // still shows which rank had which scene.
                writeReports();
            } else {
                w.Put(int32_t(-1));
            }
            Send(m.source, TagAssign, w.Bytes());
        } else if (m.tag == TagResult) {
            int32_t index = r.Get<int32_t>();
            if (index < 0 || size_t(index) >= jobs.size()) continue;
            Job &j = jobs[size_t(index)];
            GetRecord(r, &j);
            j.endSeconds = SecondsSince(batchStart);
            if (!a.quiet)
                std::fprintf(stderr, "batch: %s %s (rank %d, %.1fs)%s%s\n", j.status.c_str(),
                             j.scene.c_str(), m.source, j.seconds, j.error.empty() ? "" : ": ",
                             j.error.c_str());
            writeReports();
        } else if (m.tag == TagDone) {
            --working;
        } else if (m.tag == TagError) {
            // A worker that cannot go on: its scenes in progress were reported; the others
            // go to the remaining ranks.
            std::fprintf(stderr, "error: rank %d: %s\n", m.source,
                         std::string(m.bytes.begin(), m.bytes.end()).c_str());
            for (Job &j : jobs)
                if (j.status == "running" && j.rank == m.source) {
                    j.status = "failed";
                    j.error = "rank " + std::to_string(m.source) + " failed";
                }
            --working;
        }
    }
    int failed = FinishReports(a, jobs, SecondsSince(batchStart));
    return failed > 0 ? ExitBadInput : ExitOk;
}

}  // namespace

int RunMpiBatch(const BatchArgs &a) {
    const int rank = Rank(), size = Size();
    std::vector<Job> jobs;
    std::string exe, message;
    int status = RunGuarded(
        [&] {
            exe = PrismExecutable();  // every rank: the nodes may differ
            if (rank == 0) jobs = PrepareBatch(a);
            return ExitOk;
        },
        &message);
    if (int agreed = AgreeOnSetup(status, message); agreed != 0) return agreed;
    if (size == 1) {
        if (rank == 0) std::fprintf(stderr, "error: prism-mpi batch needs at least 2 ranks\n");
        return ExitBadInput;
    }
    if (rank != 0) {
        status = RunGuarded(
            [&] {
                RunWorker(a, exe);
                return ExitOk;
            },
            &message);
        if (status != ExitOk) {
            Send(0, TagError, std::vector<uint8_t>(message.begin(), message.end()));
            return ExitOk;  // rank 0 reports it; the batch goes on without this rank
        }
        return ExitOk;
    }
    return RunGuarded([&] { return Coordinate(a, jobs); });
}

}  // namespace prism::mpi
