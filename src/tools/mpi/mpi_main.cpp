// prism-mpi: `prism render` and `prism batch` over MPI (docs/DISTRIBUTED.md). Started by
// mpirun or srun; every rank parses the same command line, only rank 0 prints.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <memory>

#include "app/commands.h"
#include "app/common.h"
#include "app/render_stack.h"
#include "tools/mpi/mpi_comm.h"
#include "tools/mpi/mpi_commands.h"

namespace {

int Main(int argc, char **argv) {
    // Only this thread (MPI's main thread: it calls MPI_Init_thread) calls MPI; TBB's
    // threads render.
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    const int rank = prism::mpi::Rank();
    // Rank 0 turns SIGTERM (mpirun's, when a rank dies) into an orderly end: the batch report
    // is kept. Workers die at once; their render processes follow (PR_SET_PDEATHSIG).
    if (rank == 0) prism::mpi::InstallStopHandler();

    CLI::App app{"prism-mpi: prism render and prism batch over MPI (mpirun -np N prism-mpi ...)",
                 "prism-mpi"};
    app.require_subcommand(1);
    app.set_version_flag("--version", PRISM_VERSION);
    int exitCode = 0;
    auto renderArgs = std::make_shared<prism::RenderArgs>();
    CLI::App *render = app.add_subcommand(
        "render", "Render a scene over MPI: the same options and image as prism render");
    std::function<void()> recordGiven = prism::AddRenderOptions(render, renderArgs.get());
    render->callback([&] {
        recordGiven();
        exitCode = prism::mpi::RunMpiRender(*renderArgs);
    });
    auto batchArgs = std::make_shared<prism::BatchArgs>();
    CLI::App *batch = app.add_subcommand(
        "batch", "Render many scenes over MPI, one rank per scene at a time (as prism batch)");
    prism::AddBatchOptions(batch, batchArgs.get());
    batch->callback([&] { exitCode = prism::mpi::RunMpiBatch(*batchArgs); });

    try {
        std::vector<std::string> args = prism::NormalizeConfineArgs(argc, argv);
        std::reverse(args.begin(), args.end());  // CLI11 takes them last first
        app.parse(args);
    } catch (const CLI::ParseError &e) {
        // Help, version and usage errors: printed once, by rank 0.
        int code = e.get_exit_code() == 0 ? 0 : prism::ExitBadInput;
        if (rank == 0) app.exit(e);
        MPI_Finalize();
        return code;
    }
    MPI_Finalize();
    return exitCode;
}

}  // namespace

// On a render stack (app/render_stack.h), which is then MPI's main thread.
int main(int argc, char **argv) {
    return prism::RunOnRenderStack([&] { return Main(argc, argv); });
}
