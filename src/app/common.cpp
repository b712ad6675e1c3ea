#include "app/common.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "app/commands.h"
#include "assembly/build_scene.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/memory.h"
#include "core/output_file.h"
#include "image/image_io.h"
#include "image/tonemap.h"
#include "scene/scene_description.h"

namespace prism {

int RunGuarded(const std::function<int()> &fn) { return RunGuarded(fn, nullptr); }

int RunGuarded(const std::function<int()> &fn, std::string *message) {
    // One line, whatever the message carries (a name with a newline or an escape sequence).
    auto emit = [message](const std::string &text) {
        std::string line = EscapeControlChars(text);
        if (message)
            *message = line;
        else
            std::fprintf(stderr, "%s\n", line.c_str());
    };
    try {
        return fn();
    } catch (const SceneError &e) {
        // A SceneError without a location (e.g. from a command-line override) carries the bare
        // message; give it the same "error: " prefix as every other error line.
        std::string what = e.what();
        if (what.rfind("error: ", 0) != 0 && what.find(": error: ") == std::string::npos)
            what = "error: " + what;
        // The libraries report a limit without naming the flag that sets it.
        const std::string flag = " (--max-memory)";
        if (dynamic_cast<const MemoryBudgetError *>(&e) &&
            (what.size() < flag.size() ||
             what.compare(what.size() - flag.size(), flag.size(), flag) != 0))
            what += flag;
        emit(what);
        return ExitBadInput;
    } catch (const UsageError &e) {
        emit(std::string("error: ") + e.what());
        return ExitBadInput;
    } catch (const std::bad_alloc &) {
        emit("error: out of memory");
        return ExitInternal;
    } catch (const std::exception &e) {
        emit(std::string("error: ") + e.what());
        return ExitInternal;
    }
}

static std::vector<float> SplitFloats(const std::string &s, char sep) {
    std::vector<float> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, sep)) {
        try {
            size_t used = 0;
            float v = std::stof(item, &used);
            if (used != item.size()) throw std::invalid_argument(item);
            out.push_back(v);
        } catch (const std::exception &) {
            throw UsageError("invalid number \"" + item + "\" in \"" + s + "\"");
        }
    }
    return out;
}

Vec2i ParseResolution(const std::string &s) {
    std::vector<float> v = SplitFloats(s, 'x');
    if (v.size() != 2 || v[0] != float(int(v[0])) || v[1] != float(int(v[1])) || v[0] < 1 ||
        v[1] < 1)
        throw UsageError("--res expects WxH with positive integers, e.g. 640x480 (got \"" + s +
                         "\")");
    if (v[0] > MaxImageResolution || v[1] > MaxImageResolution)
        throw SceneError("--res " + s + " is out of range (1 to " +
                         std::to_string(MaxImageResolution) + " per axis)");
    return {int(v[0]), int(v[1])};
}

std::array<float, 4> ParseCrop(const std::string &s) {
    std::vector<float> v = SplitFloats(s, ',');
    if (v.size() != 4) throw UsageError("--crop expects x0,x1,y0,y1 (got \"" + s + "\")");
    for (float f : v)
        if (!(f >= 0 && f <= 1))
            throw UsageError("--crop values must lie in [0,1] (got \"" + s + "\")");
    if (!(v[0] < v[1] && v[2] < v[3]))
        throw UsageError("--crop window is empty (got \"" + s + "\")");
    return {v[0], v[1], v[2], v[3]};
}

Transform ParseLookAt(const std::string &s) {
    std::vector<float> v = SplitFloats(s, ',');
    if (v.size() != 9)
        throw UsageError("--lookat expects ex,ey,ez,lx,ly,lz,ux,uy,uz (got \"" + s + "\")");
    try {
        return LookAt({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}).Inverse();
    } catch (const std::invalid_argument &e) {
        throw SceneError(std::string("--lookat: ") + e.what());
    }
}

uint64_t ParseMaxMemory(const std::string &s) {
    if (s.empty()) return 0;
    uint64_t bytes = 0;
    if (!ParseMemorySize(s, &bytes))
        throw UsageError("--max-memory expects a size such as 512M or 8G (got \"" + s + "\")");
    return bytes;
}

Precision ParsePrecision(const std::string &s) {
    if (s == "float") return Precision::Float;
    if (s == "double") return Precision::Double;
    throw UsageError("--precision must be float or double");
}

EnvironmentSpec ParseEnvironment(const std::string &spec, double rotateDeg,
                                 const std::string &mode) {
    EnvironmentSpec env;
    if (!mode.empty() && mode != "replace" && mode != "add")
        throw UsageError("--env-mode must be replace or add (got \"" + mode + "\")");
    env.replace = mode != "add";
    if (!std::isfinite(rotateDeg)) throw UsageError("--env-rotate expects an angle in degrees");
    env.rotateDeg = rotateDeg;
    std::string ext = LowerExtension(spec);
    if (ext == ".exr" || ext == ".hdr") {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(spec, ec))
            throw UsageError("--env: environment map \"" + spec +
                             "\" does not exist or is not a "
                             "regular file");
        env.mapFile = spec;
        return env;
    }
    const std::string expected =
        "--env expects an equirectangular .exr or .hdr file or a "
        "radiance R,G,B of three non-negative numbers (got \"" +
        spec + "\")";
    std::vector<float> v;
    try {
        v = SplitFloats(spec, ',');
    } catch (const UsageError &) {
        throw UsageError(expected);
    }
    if (v.size() != 3 || spec.back() == ',') throw UsageError(expected);
    for (float f : v)
        if (!(f >= 0) || !std::isfinite(f)) throw UsageError(expected);
    env.L = RGB(v[0], v[1], v[2]);
    return env;
}

void CheckOutputPath(const std::string &path) {
    namespace fs = std::filesystem;
    std::string ext = LowerExtension(path);
    if (!IsWritableImageExtension(ext))
        throw UsageError("unsupported output format \"" + ext + "\" for \"" + path +
                         "\" (use .exr or .png)");
    fs::path dir = fs::path(path).parent_path();
    if (!dir.empty() && !fs::is_directory(dir))
        throw UsageError("output directory \"" + dir.string() + "\" does not exist");
    CheckWritableDirectory(dir.string());
}

void CheckWritableDirectory(const std::string &dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec))
        throw UsageError("output directory " + Quote(dir) + " does not exist");
    // What killed writers left here long ago (core/output_file.h says when that is sure).
    RemoveStaleTemporaries(dir);
    // access(W_OK) says yes to root on a read-only folder; creating a file tells the truth.
    fs::path probe =
        fs::path(dir.empty() ? "." : dir) / (".prism-write-test-" + std::to_string(::getpid()));
    int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        int err = errno;
        if (err == EEXIST) return;  // another probe of this process; the folder is writable
        throw UsageError("cannot write to output directory " + Quote(dir.empty() ? "." : dir) +
                         ": " + std::strerror(err));
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

void AddPbrtVersionOption(CLI::App *cmd, std::string *version) {
    cmd->add_option("--pbrt-version", *version,
                    "Read a pbrt file by pbrt-v3's or pbrt-v4's rules (default: the version its "
                    "version-specific constructs name; pbrt-v3 when there are none)")
        ->check(CLI::IsMember({"3", "4"}))
        ->type_name("3|4");
}

int PbrtVersionNumber(const std::string &version) {
    return version.empty() ? 0 : std::stoi(version);
}

bool ConfineOption::Given() const { return option && option->count() > 0; }

void AddConfineOption(CLI::App *cmd, ConfineOption *confine) {
    confine->option =
        cmd->add_option("--confine", confine->dir,
                        "Refuse to read any file outside DIR (default: the scene's folder), "
                        "after symlinks, and any device or FIFO; for untrusted scenes")
            ->expected(0, 1)
            ->type_name("[DIR]");
}

std::string ConfinementFolderFor(const ConfineOption &confine, const std::string &scene) {
    if (!confine.Given()) return {};
    std::string dir = confine.dir;
    if (dir.empty()) dir = DirectoryOf(scene);
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw UsageError("--confine: " + Quote(dir) + " is not a folder");
    return dir;
}

void CheckOutputConfinement(const std::string &out, const SceneEntity &film) {
    namespace fs = std::filesystem;
    const std::string folder = ReadConfinementFolder();
    if (folder.empty()) return;
    const Param *p = film.params.Find("filename");
    auto refuse = [&](const std::string &why) {
        throw SceneError(p ? p->loc : film.loc, "Film \"filename\" " + Quote(out) + " " + why +
                                                    "; give the output with -o");
    };
    // The folder the file goes into, with every symbolic link resolved, must lie inside the
    // confined folder; the name itself must not be a link (nor anything but a regular file),
    // even one pointing back inside: what the scene names is what gets replaced.
    fs::path target(out);
    fs::path dir =
        CanonicalPath(target.parent_path().empty() ? "." : target.parent_path().string());
    fs::path rel = (dir / target.filename()).lexically_relative(folder);
    if (rel.empty() || *rel.begin() == ".." || target.filename().empty() ||
        target.filename() == "." || target.filename() == "..")
        refuse("is outside the confined folder");
    struct stat st;
    if (::lstat(out.c_str(), &st) == 0) {
        if (S_ISLNK(st.st_mode)) refuse("is a symbolic link (confined outputs)");
        if (!S_ISREG(st.st_mode)) refuse("exists and is not a regular file");
    }
}

std::vector<std::string> NormalizeConfineArgs(int argc, char **argv) {
    std::vector<std::string> args(argv + 1, argv + argc), moved;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] != "--confine" || i + 1 >= args.size()) continue;
        const std::string &next = args[i + 1];
        std::error_code ec;
        if (next.empty() || next[0] == '-' || std::filesystem::is_directory(next, ec)) continue;
        moved.push_back(args[i]);
        args.erase(args.begin() + long(i));
        --i;
    }
    args.insert(args.end(), moved.begin(), moved.end());
    return args;
}

std::string FindDefaultScene() {
    const char *rel = "scenes/whitted.pbrt";
    if (std::filesystem::exists(rel)) return rel;
    std::string src = std::string(PRISM_SOURCE_DIR) + "/" + rel;
    if (std::filesystem::exists(src)) return src;
    return rel;  // LoadScene reports it missing
}

std::string FindToolScript(const std::string &given, const std::string &rel) {
    if (!given.empty()) return given;
    if (std::filesystem::exists(rel)) return rel;
    return std::string(PRISM_SOURCE_DIR) + "/" + rel;
}

std::vector<int> ParseLevels(const std::string &s) {
    std::vector<int> v;
    std::stringstream in(s);
    std::string tok;
    while (std::getline(in, tok, ',')) {
        try {
            size_t used = 0;
            int n = std::stoi(tok, &used);
            if (used != tok.size() || n < 3 || n > 4096) throw std::invalid_argument(tok);
            v.push_back(n);
        } catch (const std::exception &) {
            throw UsageError("--levels: \"" + tok + "\" is not a segment count from 3 to 4096");
        }
    }
    if (v.empty()) throw UsageError("--levels is empty");
    return v;
}

std::string CheckExposureText(const std::string &text) {
    float ev;
    bool isAuto;
    return ParseExposure(text, &ev, &isAuto) ? "" : "must be auto or a number of EV in [-64, 64]";
}

}  // namespace prism
