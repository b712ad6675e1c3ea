// Helpers shared by the subcommands: option parsing, error handling, paths.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "core/file_io.h"  // ShellQuote
#include "core/transform.h"
#include "core/vecmath.h"
#include "geometry/shape.h"
#include "image/tonemap.h"
#include "scene/load_scene.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace prism {

// The values of --texture-filter (render and batch take it; --integrator takes
// render/integrator.h IntegratorNames()).
inline const std::vector<std::string> TextureFilterNames = {"none", "point", "bilinear",
                                                            "trilinear", "ewa"};

// The check of an --exposure value (render and batch): "" when it is "auto" or a number of EV
// in [-64, 64], else the message.
std::string CheckExposureText(const std::string &text);

struct SceneEntity;

// Runs a command, turning exceptions into messages and exit statuses: SceneError and
// UsageError → 2, anything else → 1.
int RunGuarded(const std::function<int()> &fn);
// The same, but the error line goes to *message instead of stderr (prism-mpi: only rank 0
// prints).
int RunGuarded(const std::function<int()> &fn, std::string *message);

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Vec2i ParseResolution(const std::string &s);           // "640x480"
std::array<float, 4> ParseCrop(const std::string &s);  // "x0,x1,y0,y1"
Precision ParsePrecision(const std::string &s);
// --max-memory: "512M", "8G", ... (core/memory.h); "" gives 0, the default budget.
uint64_t ParseMaxMemory(const std::string &s);
// "ex,ey,ez,lx,ly,lz,ux,uy,uz" → worldFromCamera (pbrt LookAt, inverted).
Transform ParseLookAt(const std::string &s);
// --env SPEC [--env-rotate DEG] [--env-mode replace|add]: SPEC is an equirectangular .exr or
// .hdr file (which must exist) or a uniform radiance "R,G,B" (finite, non-negative). `rotate`
// and `mode` are those options' values ("" for a mode not given). UsageError on bad values.
EnvironmentSpec ParseEnvironment(const std::string &spec, double rotateDeg,
                                 const std::string &mode);
// Fails early (UsageError) if the image format is unsupported or the directory is missing.
void CheckOutputPath(const std::string &path);
// Fails early (UsageError) when no file can be created in `dir` ("" is the working
// directory): missing, read-only (also for root: a file is really created and removed) or full.
void CheckWritableDirectory(const std::string &dir);

// --confine [DIR] for render, info, batch and validate (docs/USAGE.md, docs/RELIABILITY.md): every
// file a scene reads must resolve inside DIR, by default the scene file's folder.
struct ConfineOption {
    std::string dir;                // as given; empty: the scene's folder
    CLI::Option *option = nullptr;  // set by AddConfineOption
    bool Given() const;
};
void AddConfineOption(CLI::App *cmd, ConfineOption *confine);
// --pbrt-version 3|4 for render, info and batch: the pbrt rules a pbrt file is read by
// (scene/pbrt_version.h); empty: detected from the file. PbrtVersionNumber gives 0 for empty.
void AddPbrtVersionOption(CLI::App *cmd, std::string *version);
int PbrtVersionNumber(const std::string &version);
// The folder reads of `scene` are confined to ("" when --confine is not given); a DIR that is
// not a folder is a UsageError.
std::string ConfinementFolderFor(const ConfineOption &confine, const std::string &scene);
// Under --confine (a ScopedReadConfinement in force): the Film's "filename" `out` must resolve
// inside the confined folder too, else a SceneError at the parameter (give -o instead).
void CheckOutputConfinement(const std::string &out, const SceneEntity &film);
// The arguments after argv[0] for CLI11, with each "--confine" that is not followed by a
// folder moved to the end, so that `--confine scene.pbrt` does not take the scene as its DIR.
std::vector<std::string> NormalizeConfineArgs(int argc, char **argv);

// scenes/whitted.pbrt relative to the working directory, else to the source tree.
std::string FindDefaultScene();
// `given` if not empty, else `rel` (e.g. "tools/plot_study.py") relative to the working
// directory if it exists there, else to the source tree.
std::string FindToolScript(const std::string &given, const std::string &rel);
// --levels "8,16,32": tessellation segment counts, each from 3 to 4096.
std::vector<int> ParseLevels(const std::string &s);
inline double SecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace prism
