// Writing output files (images, reports, logs) so that nothing is lost and nothing is written
// where it does not belong. Every output Prism writes goes through AtomicOutputFile:
//  - the temporary file is a new file with a short random name, `.prism-<pid>-XXXXXX.tmp`, in
//    the target's folder, created with O_CREAT | O_EXCL | O_NOFOLLOW: a symbolic link planted
//    under any name (an upload that ships links) is never written through, and the name stays
//    short whatever the target's length;
//  - every write, the fsync (see `sync`) and the close are checked; the first failure is an
//  exception
//    naming the OS reason ("write error: No space left on device");
//  - only a complete file is renamed over the target (rename replaces a symbolic link at the
//    target rather than following it); on any failure, or when the object is destroyed
//    without Commit, the temporary file is removed and the previous target stays untouched.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace prism {

// The prefix of every temporary output file (see TemporaryOutputPid).
inline constexpr std::string_view kTemporaryOutputPrefix = ".prism-";

class AtomicOutputFile {
  public:
    // Creates the temporary file for `target` in the target's folder. Throws
    // std::runtime_error("could not create a temporary file in DIR: REASON"). `sync`: Commit
    // fsyncs before the rename, so that a crash right after cannot leave an empty file in
    // place of the previous one (a finished image); files rewritten again soon (the batch's
    // report after every scene) skip it, as an fsync costs 4-8 ms on this machine's ext4.
    explicit AtomicOutputFile(const std::string &target, bool sync = true);
    // Removes the temporary file unless Commit succeeded.
    ~AtomicOutputFile();
    AtomicOutputFile(const AtomicOutputFile &) = delete;
    AtomicOutputFile &operator=(const AtomicOutputFile &) = delete;

    // Appends `n` bytes at the current position (partial writes and EINTR are retried).
    // Throws std::runtime_error("write error: REASON").
    void Write(const void *data, size_t n);
    void Write(std::string_view s) { Write(s.data(), s.size()); }
    // The current position, and moving it (OpenEXR writes its offset table last).
    uint64_t Tell() const;
    void Seek(uint64_t pos);
    // fsync (when `sync`), close, rename over the target. Throws std::runtime_error("write
    // error: REASON") (or the rename's reason); the temporary file is removed then.
    void Commit();

    const std::string &TemporaryPath() const { return tmp_; }

  private:
    void Discard();
    std::string target_, tmp_;
    int fd_ = -1;
    bool sync_ = true;
};

// Creates a new, empty file `.prism-<pid>-XXXXXX<suffix>` in `dir` ("" = the current folder)
// with O_CREAT | O_EXCL | O_NOFOLLOW, retrying another random name if one exists. Returns the
// open descriptor (O_WRONLY, close-on-exec) and sets *path. Throws std::runtime_error
// ("could not create a temporary file in DIR: REASON").
int CreateUniqueFile(const std::string &dir, std::string_view suffix, std::string *path);

// Writes `contents` to `path` through AtomicOutputFile (`sync` as there). Throws
// std::runtime_error `cannot write "PATH": REASON`.
void WriteFileAtomically(const std::string &path, std::string_view contents, bool sync = true);

// The pid in a temporary output file's name (`.prism-<pid>-XXXXXX.tmp` or `...log.tmp`), or
// -1 when `name` is not one.
long TemporaryOutputPid(std::string_view name);

// A process killed while it wrote (SIGKILL, the OOM killer, a power cut) leaves its
// temporary file behind. This removes, in `dir`, the temporary output files that are surely
// stale: named exactly as CreateUniqueFile names them, regular files (not links) owned by this
// user, last modified more than kStaleTemporarySeconds ago, and whose pid names no live
// process here (kill(pid, 0) fails with ESRCH). The age covers what the pid cannot: a folder
// shared with another machine or pid namespace, where the same pid means another process (a
// file being written is modified continually; a render log at least at its start, so the age
// spares a log only as long as a render takes). Returns the number removed; errors are
// ignored (the folder is checked for writing separately).
inline constexpr long kStaleTemporarySeconds = 3600;
int RemoveStaleTemporaries(const std::string &dir);

}  // namespace prism
