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
};

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
