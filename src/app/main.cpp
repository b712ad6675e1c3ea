// prism: a CPU ray tracer on Embree. Subcommands: render, info, trace, pick, validate,
// batch, bench and study (with no arguments: render scenes/whitted.pbrt).
#include <CLI/CLI.hpp>
#include <algorithm>

#include "app/commands.h"
#include "app/common.h"
#include "app/render_stack.h"

namespace {

int Main(int argc, char **argv) {
    if (argc == 1) return prism::RenderDefaultScene();
    CLI::App app{"Prism: a CPU ray tracer on Embree (pbrt-v3, OBJ, glTF scenes)", "prism"};
    app.require_subcommand(1);
    app.set_version_flag("--version", PRISM_VERSION);
    int exitCode = 0;
    prism::AddRenderCommand(app, &exitCode);
    prism::AddTraceCommand(app, &exitCode);
    prism::AddPickCommand(app, &exitCode);
    prism::AddInfoCommand(app, &exitCode);
    prism::AddBatchCommand(app, &exitCode);
    prism::AddValidateCommand(app, &exitCode);
    prism::AddBenchCommand(app, &exitCode);
    prism::AddStudyCommand(app, &exitCode);
    try {
        std::vector<std::string> args = prism::NormalizeConfineArgs(argc, argv);
        std::reverse(args.begin(), args.end());  // CLI11 takes them last first
        app.parse(args);
    } catch (const CLI::CallForHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion &e) {
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        app.exit(e);
        return prism::ExitBadInput;
    }
    return exitCode;
}

}  // namespace

int main(int argc, char **argv) {
    return prism::RunOnRenderStack([&] { return Main(argc, argv); });
}
