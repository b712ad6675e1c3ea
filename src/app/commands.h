// Subcommands of the prism executable. Each returns the process exit status:
// 0 success, 1 internal failure, 2 bad input (scene, options or files).
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace prism {

inline constexpr int ExitOk = 0;
inline constexpr int ExitInternal = 1;
inline constexpr int ExitBadInput = 2;
// 3 and 4: `prism validate` (ExitOutOfBand, ExitBadSlope in tools/validate/validate.h).
inline constexpr int ExitInterrupted = 130;  // SIGINT or SIGTERM: nothing half-written

// Registers the subcommand's options on `app`; the returned callback runs it.
void AddRenderCommand(CLI::App &app, int *exitCode);
void AddTraceCommand(CLI::App &app, int *exitCode);
void AddPickCommand(CLI::App &app, int *exitCode);
void AddInfoCommand(CLI::App &app, int *exitCode);
void AddBatchCommand(CLI::App &app, int *exitCode);
void AddValidateCommand(CLI::App &app, int *exitCode);  // exit 3/4: see tools/validate/validate.h
void AddBenchCommand(CLI::App &app, int *exitCode);
void AddStudyCommand(CLI::App &app, int *exitCode);
// `prism` with no arguments: render the default scene to whitted.png.
int RenderDefaultScene();

}  // namespace prism
