// `prism render`: one scene to one image, on this machine (src/mpi has `prism-mpi render`).
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "app/common.h"
#include "app/render_options.h"
#include "render/renderer.h"

namespace prism {

namespace {

// SIGINT during a render sets this flag: the renderer stops between tiles and nothing is
// written. During the final write the signal is deferred, so the output is either complete or
// absent.
volatile sig_atomic_t g_cancel = 0;
void OnInterrupt(int) { g_cancel = 1; }

int RunRender(const RenderArgs &a) {
    RenderJob job(a);
    ProgressFn progress = job.Progress();
    RenderStats stats;
    struct sigaction sa {
    }, old{};
    sa.sa_handler = OnInterrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old);
    sigaction(SIGTERM, &sa, nullptr);
    Image img = Render(job.Scene(), &stats, progress, &g_cancel);
    if (stats.cancelled || g_cancel) {
        std::fprintf(stderr, "interrupted: no image written\n");
        return ExitInterrupted;
    }
    job.Write(img);
    sigaction(SIGINT, &old, nullptr);
    job.Report(img, stats);
    return ExitOk;
}

}  // namespace

void AddRenderCommand(CLI::App &app, int *exitCode) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App *cmd =
        app.add_subcommand("render", "Render a scene (.pbrt, .obj, .gltf, .glb, .ply) to an image");
    std::function<void()> recordGiven = AddRenderOptions(cmd, args.get());
    cmd->callback([args, exitCode, recordGiven] {
        recordGiven();
        *exitCode = RunGuarded([&] { return RunRender(*args); });
    });
}

int RenderDefaultScene() {
    RenderArgs a;
    a.scene = FindDefaultScene();
    a.output = "whitted.png";
    return RunGuarded([&] { return RunRender(a); });
}

}  // namespace prism
