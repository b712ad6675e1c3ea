// `prism-mpi render`: every rank loads the scene and builds its BVH; rank 0 hands out runs of
// tiles on request (a slow rank asks less often, so it gets fewer), the other ranks render them
// with TBB and send back the tiles' filtered sums, and rank 0 merges them in tile order: the
// image is bit-identical to `prism render`'s. Rank 0 only coordinates (docs/DISTRIBUTED.md).
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/common.h"
#include "app/render_options.h"
#include "render/renderer.h"
#include "tools/mpi/mpi_comm.h"
#include "tools/mpi/mpi_commands.h"

namespace prism::mpi {

namespace {

// One rank's share, as rank 0 counts it.
struct RankTotals {
    int tiles = 0, requests = 0, threads = 0;
    uint64_t bytes = 0;  // tile messages received from it
    RayCounters rays;
    double busySeconds = 0;  // rendering, by its own clock
};

void PutTile(Writer &w, const FilmTile &tile) {
    std::span<const FilmPixel> sums = tile.Sums();
    const NonFiniteRecord &nf = tile.NonFinite();
    w.Put(uint64_t(sums.size()));
    w.Put(nf.count);
    w.Put(int32_t(nf.firstPixel.has_value()));
    w.Put(nf.firstPixel.value_or(Vec2i(0, 0)));
    w.PutBytes(sums.data(), sums.size_bytes());
    // Light tracing's splats (render/integrator.h SampleSplat), in order.
    const std::vector<FilmSplat> &splats = tile.Splats();
    w.Put(uint64_t(splats.size()));
    if (!splats.empty()) w.PutBytes(splats.data(), splats.size() * sizeof(FilmSplat));
}

void GetTile(Reader &r, FilmTile *tile) {
    std::span<FilmPixel> sums = tile->Sums();
    if (r.Get<uint64_t>() != sums.size())
        throw std::runtime_error(
            "a tile from another rank does not fit: do all ranks load the "
            "same scene file?");
    NonFiniteRecord nf;
    nf.count = r.Get<uint64_t>();
    bool has = r.Get<int32_t>() != 0;
    Vec2i p = r.Get<Vec2i>();
    if (has) nf.firstPixel = p;
    tile->SetNonFinite(nf);
    r.GetBytes(sums.data(), sums.size_bytes());
    const uint64_t n = r.Get<uint64_t>();
    std::vector<FilmSplat> &splats = tile->Splats();
    if (n > r.Remaining() / sizeof(FilmSplat))
        throw std::runtime_error("a tile from another rank holds more splats than it sent");
    splats.resize(size_t(n));
    if (n > 0) r.GetBytes(splats.data(), splats.size() * sizeof(FilmSplat));
}

// A worker keeps two requests out: while it renders one run, the next is already on its way,
// so it never waits for rank 0 (which may be descheduled on a busy node).
constexpr int RequestsInFlight = 2;

void RunWorker(const RenderJob &job) {
    FrameTiles frame(job.Scene());
    std::vector<FilmTile> tiles;
    RayCounters rays;
    double busy = 0;
    // --threads limits TBB through a global_control, which the arena's concurrency ignores.
    const int threads = int(std::min<size_t>(
        size_t(tbb::this_task_arena::max_concurrency()),
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
    Writer first;  // a tile message without tiles: a request
    first.Put(int32_t(0)), first.Put(int32_t(0)), first.Put(int32_t(threads));
    for (int k = 0; k < RequestsInFlight; ++k) Send(0, TagTiles, first.Bytes());
    int outstanding = RequestsInFlight;  // each tile message gets one reply
    Message m;
    while (outstanding > 0 && Receive(&m, 0, TagAssign)) {
        --outstanding;
        Reader r(m.bytes);
        int32_t begin = r.Get<int32_t>(), end = r.Get<int32_t>();
        if (begin >= end) continue;  // no tiles left
        auto t0 = std::chrono::steady_clock::now();
        // SIGINT/SIGTERM stop the run within a camera packet, as they stop `prism render`;
        // its unfinished tiles are not sent (rank 0 is stopping too).
        if (!frame.RenderTiles(begin, end, &tiles, &rays, &g_stop)) break;
        busy += SecondsSince(t0);
        Writer w;
        w.Put(begin), w.Put(end), w.Put(int32_t(threads));
        for (const FilmTile &t : tiles) PutTile(w, t);
        Send(0, TagTiles, w.Bytes());
        ++outstanding;
    }
    Writer w;
    w.Put(rays);
    w.Put(busy);
    Send(0, TagStats, w.Bytes());
}

// Rank 0's loop. Returns false when stopped (SIGINT/SIGTERM) before the image was complete.
bool Coordinate(RenderJob &job, FrameTiles &frame, std::vector<RankTotals> &totals,
                const ProgressFn &progress) {
    const int nTiles = frame.NumTiles(), nWorkers = Size() - 1;
    int nextTile = 0, working = nWorkers;
    // Tiles that arrived before every tile ahead of them was merged.
    std::vector<std::unique_ptr<FilmTile>> waiting(static_cast<size_t>(nTiles));
    auto lastProgress = std::chrono::steady_clock::now();
    Message m;
    while (working > 0) {
        if (!Receive(&m)) return false;
        RankTotals &rt = totals[size_t(m.source)];
        Reader r(m.bytes);
        if (m.tag == TagError) {
            std::fprintf(stderr, "error: rank %d: %s\n", m.source,
                         std::string(m.bytes.begin(), m.bytes.end()).c_str());
            MPI_Abort(MPI_COMM_WORLD, ExitInternal);
        } else if (m.tag == TagStats) {
            rt.rays = r.Get<RayCounters>();
            rt.busySeconds = r.Get<double>();
            --working;
            continue;
        } else if (m.tag != TagTiles) {
            continue;
        }
        int32_t begin = r.Get<int32_t>(), end = r.Get<int32_t>();
        rt.threads = r.Get<int32_t>();
        rt.bytes += m.bytes.size();
        rt.requests++;
        rt.tiles += end - begin;
        auto m0 = std::chrono::steady_clock::now();
        for (int t = begin; t < end; ++t) {
            auto tile = std::make_unique<FilmTile>();
            frame.ResetTile(t, tile.get());
            GetTile(r, tile.get());
            waiting[size_t(t)] = std::move(tile);
        }
        while (frame.NextTile() < nTiles && waiting[size_t(frame.NextTile())]) {
            int t = frame.NextTile();
            frame.MergeNext(*waiting[size_t(t)]);
            waiting[size_t(t)].reset();
        }
        totals[0].busySeconds += SecondsSince(m0);
        // Guided hand-out: runs shrink as the frame empties, so the last ones end together;
        // at least one tile per thread of the asking rank, at most four.
        const int remaining = nTiles - nextTile;
        int run = std::max(1, rt.threads);
        run = std::clamp((remaining + 2 * nWorkers - 1) / (2 * nWorkers), run, 4 * run);
        run = std::min(run, remaining);
        Writer w;
        w.Put(int32_t(nextTile)), w.Put(int32_t(nextTile + run));
        nextTile += run;
        Send(m.source, TagAssign, w.Bytes());
        if (progress &&
            std::chrono::steady_clock::now() - lastProgress > std::chrono::milliseconds(250)) {
            lastProgress = std::chrono::steady_clock::now();
            progress(double(frame.NextTile()) / nTiles);
        }
    }
    if (progress) progress(1.0);
    return frame.NextTile() == nTiles;
}

void PrintRankTable(const std::vector<RankTotals> &totals, double seconds) {
    const int size = int(totals.size());
    int tiles = 0;
    uint64_t bytes = 0;
    double busyMax = 0, busySum = 0;
    for (int k = 1; k < size; ++k) {
        tiles += totals[size_t(k)].tiles;
        bytes += totals[size_t(k)].bytes;
        busyMax = std::max(busyMax, totals[size_t(k)].busySeconds);
        busySum += totals[size_t(k)].busySeconds;
    }
    std::fprintf(stderr,
                 "mpi: %d ranks (rank 0 coordinates, %d render), %d tiles, %.2f MB of tiles "
                 "sent to rank 0 in %.3fs; rank 0 unpacked and merged them in %.3fs\n",
                 size, size - 1, tiles, bytes * 1e-6, seconds, totals[0].busySeconds);
    for (int k = 1; k < size; ++k) {
        const RankTotals &t = totals[size_t(k)];
        std::fprintf(stderr,
                     "mpi: rank %d: %d threads, %d tiles (%.0f%%) in %d runs, %llu rays, "
                     "%.2f MB sent, busy %.3fs\n",
                     k, t.threads, t.tiles, tiles ? 100.0 * t.tiles / tiles : 0.0,
                     t.requests - RequestsInFlight, (unsigned long long)t.rays.Total(),
                     t.bytes * 1e-6, t.busySeconds);
    }
    if (size > 2 && busySum > 0)
        std::fprintf(stderr, "mpi: load balance: mean busy / max busy = %.2f\n",
                     busySum / (size - 1) / busyMax);
}

}  // namespace

int RunMpiRender(const RenderArgs &a) {
    const int rank = Rank(), size = Size();
    std::unique_ptr<RenderJob> job;
    std::string message;
    int status = RunGuarded(
        [&] {
            // The pilot study of --target-error weighs render times, so ranks could choose
            // different settings: not over MPI (yet).
            if (a.targetError > 0)
                throw UsageError(
                    "prism-mpi render does not take --target-error: run prism "
                    "render --target-error on a small machine and pass the spp, "
                    "cutoff and light samples it prints");
            // Each rank would run out of time after a different number of passes, and the
            // noise halves are not sent with the tiles.
            if (a.timeLimit > 0 || a.stats)
                throw UsageError(std::string("prism-mpi render does not take ") +
                                 (a.timeLimit > 0 ? "--time-limit" : "--stats") +
                                 ": give --spp (prism render takes both)");
            job = std::make_unique<RenderJob>(a, rank == 0);
            return ExitOk;
        },
        &message);
    if (int agreed = AgreeOnSetup(status, message); agreed != 0) return agreed;

    if (rank != 0) {
        status = RunGuarded(
            [&] {
                RunWorker(*job);
                return ExitOk;
            },
            &message);
        if (status != ExitOk) {
            Send(0, TagError, std::vector<uint8_t>(message.begin(), message.end()));
            Message m;
            Receive(&m, 0, TagAssign);  // until rank 0 ends the job
        }
        return status;
    }

    return RunGuarded([&] {
        ProgressFn progress = job->Progress();
        RenderStats stats;
        Image img;
        auto start = std::chrono::steady_clock::now();
        std::vector<RankTotals> totals(static_cast<size_t>(size));
        if (size == 1) {
            // No other rank: render here, as `prism render` does.
            img = job->RenderImage(&stats, progress, &g_stop);
            if (stats.cancelled) return ExitInterrupted;
        } else {
            FrameTiles frame(job->Scene());
            if (!Coordinate(*job, frame, totals, progress)) {
                std::fprintf(stderr,
                             "prism-mpi: interrupted (a rank died or the job was "
                             "cancelled): no image written\n");
                return ExitInterrupted;
            }
            img = frame.Finish(&stats);
            for (const RankTotals &t : totals) stats.rays += t.rays;
            job->RenderAovs(&g_stop);  // the tiles' samples are the other ranks'
            if (g_stop) return ExitInterrupted;
            stats.renderSeconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        job->Write(img);
        job->Report(img, stats);
        if (!a.quiet && size > 1) PrintRankTable(totals, stats.renderSeconds);
        return ExitOk;
    });
}

}  // namespace prism::mpi
