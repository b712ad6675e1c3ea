// Reading whole files, and the small path helpers every reader needs. All scene, mesh and
// spectrum files are read through ReadFileContents, so its safety checks hold everywhere:
// only regular files are read (a device such as /dev/zero or a FIFO would never end), the OS
// reason is reported, and a size limit is checked before anything is allocated.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace prism {

// Why ReadFileContents failed.
struct FileReadError {
    // The OS reason ("No such file or directory", "Is a directory", "Permission denied") or
    // "not a regular file" for devices, FIFOs and sockets.
    std::string reason;
    bool tooLarge = false;  // the file is larger than the limit; `size` holds its size
    uint64_t size = 0;
    bool refused = false;  // the read confinement refused it (ReadConfinementRefusal)
};

// Read confinement (`--confine`): while a folder is set, every file read through this module
// (ReadFileContents, ReadFileOrThrow) and every image the image reader opens must resolve,
// after symbolic links, to a regular file inside that folder; anything else is refused before
// it is opened, and checked again on the opened descriptor (/proc/self/fd), so a symlink
// swapped in between is refused too. One setting for the process, made by the app before a
// scene is read (ScopedReadConfinement); readers that know a better location than the file
// they read (a directive, a parameter) call CheckReadConfinement first.
class ScopedReadConfinement {
  public:
    // Confines reads to `folder` (made canonical here) until destroyed; the previous setting
    // is restored then. An empty `folder` leaves reads unconfined. `operatorFiles` are files
    // the operator named on the command line (e.g. `--env`), not the scene: they may be read
    // wherever they are (each exact file, after symlinks; nothing else beside it).
    explicit ScopedReadConfinement(const std::string &folder,
                                   const std::vector<std::string> &operatorFiles = {});
    ~ScopedReadConfinement();
    ScopedReadConfinement(const ScopedReadConfinement &) = delete;
    ScopedReadConfinement &operator=(const ScopedReadConfinement &) = delete;

  private:
    std::string previous_;
    std::vector<std::string> previousAllowed_;
};

// The confinement folder (canonical), or "" when reads are not confined.
std::string ReadConfinementFolder();
// "" when `path` may be read under the current confinement; otherwise why not:
// `it lies outside the confined folder` or `it is not a regular file`. Neither names where
// the path resolves or the folder (an upload must not learn the server's paths); callers
// name the file as the scene wrote it. A path that does not exist is allowed (opening it then
// fails as usual).
std::string ReadConfinementRefusal(const std::string &path);
// Throws SceneError at `loc`, `WHAT "NAME": REFUSAL`, when ReadConfinementRefusal(path) is
// not empty. `what` is e.g. "texture file", `name` the file as the scene writes it.
void CheckReadConfinement(const std::string &path, const FileLoc &loc, std::string_view what,
                          const std::string &name);

// Reads the whole file at `path` into *out. The file is opened without blocking and checked
// with fstat before any byte is read: anything but a regular file is refused, and so is a file
// larger than `maxBytes` (nothing is allocated for it). Returns false with *error filled in.
bool ReadFileContents(const std::string &path, std::string *out, FileReadError *error,
                      uint64_t maxBytes = std::numeric_limits<uint64_t>::max());
bool ReadFileContents(const std::string &path, std::vector<unsigned char> *out,
                      FileReadError *error,
                      uint64_t maxBytes = std::numeric_limits<uint64_t>::max());

class MemoryBudget;

// ReadFileContents for readers that report errors as SceneError at `loc`:
// `cannot open file "PATH": REASON`, or for a file over `maxBytes` a MemoryBudgetError
// (core/memory.h) `file is SIZE, more than the memory budget of MAX`.
std::string ReadFileOrThrow(const std::string &path, const FileLoc &loc,
                            uint64_t maxBytes = std::numeric_limits<uint64_t>::max());
// As above, charging the file's size to `budget` as `what` ("scene file", "included file
// \"b.pbrt\""): a file larger than what remains of the budget is refused before it is read,
// with MemoryBudget::Charge's MemoryBudgetError at `loc`. The charge is kept.
std::string ReadFileOrThrow(const std::string &path, const FileLoc &loc, MemoryBudget &budget,
                            std::string_view what);

// `s` in single quotes for /bin/sh (a quote inside becomes '\''): prism bench, study and
// validate build shell commands with it.
std::string ShellQuote(const std::string &s);

// `s` with ASCII letters in lower case (file extensions, format names).
std::string ToLowerAscii(std::string_view s);

// The extension of `path` with its dot, in lower case: "scene.PBRT" -> ".pbrt", "a/b" -> "".
std::string LowerExtension(const std::string &path);

// The directory part of `path` ("" for a bare file name): "scenes/a.pbrt" -> "scenes".
std::string DirectoryOf(const std::string &path);

// `path` with symbolic links, "." and ".." resolved as far as it exists (the rest normalized
// lexically), made absolute: one spelling per file, for include-cycle checks and confinement.
std::string CanonicalPath(const std::string &path);

}  // namespace prism
