#include "core/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "core/memory.h"

namespace prism {

namespace {

std::mutex g_confinementMutex;
std::string g_confinementFolder;           // canonical; empty: reads are not confined
std::vector<std::string> g_operatorFiles;  // canonical files allowed outside it

bool OperatorFile(const std::string &canonicalPath) {
    std::lock_guard<std::mutex> lock(g_confinementMutex);
    for (const std::string &f : g_operatorFiles)
        if (f == canonicalPath) return true;
    return false;
}

// Whether `canonicalPath` lies inside the canonical folder `folder` (or is the folder).
bool InsideFolder(const std::string &canonicalPath, const std::string &folder) {
    if (folder == "/") return !canonicalPath.empty() && canonicalPath[0] == '/';
    return canonicalPath == folder || (canonicalPath.size() > folder.size() &&
                                       canonicalPath.compare(0, folder.size(), folder) == 0 &&
                                       canonicalPath[folder.size()] == '/');
}

// Refusals name neither where the file resolves nor the confined folder: an upload learns
// nothing of the server's paths from them (the caller names the file as the scene wrote it).
std::string OutsideReason() { return "it lies outside the confined folder"; }

// The confinement check on an opened descriptor: the file it really is (the kernel's name for
// it), so a path whose symlinks changed after ReadConfinementRefusal is caught. "" if allowed.
std::string RefusalOfOpenFile(int fd, const std::string &folder) {
    char link[64];
    std::snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
    std::error_code ec;
    std::filesystem::path real = std::filesystem::read_symlink(link, ec);
    if (ec) return {};  // no /proc: the path check before opening stands
    if (!InsideFolder(real.string(), folder) && !OperatorFile(real.string()))
        return OutsideReason();
    return {};
}

template <typename Buffer>
bool ReadInto(const std::string &path, Buffer *out, FileReadError *error, uint64_t maxBytes) {
    *error = FileReadError{};
    auto fail = [&](int err) {
        error->reason = std::strerror(err);
        return false;
    };
    auto refuse = [&](std::string why) {
        error->refused = true;
        error->reason = std::move(why);
        return false;
    };
    const std::string folder = ReadConfinementFolder();
    if (!folder.empty()) {
        std::string why = ReadConfinementRefusal(path);
        if (!why.empty()) return refuse(std::move(why));
    }
    // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below.
    int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return fail(errno);
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    if (!folder.empty()) {
        std::string why = RefusalOfOpenFile(fd, folder);
        if (!why.empty()) return refuse(std::move(why));
    }
    struct stat st;
    if (::fstat(fd, &st) != 0) return fail(errno);
    if (S_ISDIR(st.st_mode)) return fail(EISDIR);
    if (!S_ISREG(st.st_mode)) {
        error->reason = "not a regular file";
        return false;
    }
    uint64_t size = st.st_size > 0 ? uint64_t(st.st_size) : 0;
    if (size > maxBytes) {
        error->tooLarge = true;
        error->size = size;
        error->reason = "file is larger than the limit";
        return false;
    }
    int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    out->clear();
    out->resize(size_t(size));
    size_t have = 0;
    auto readSome = [&](char *dst, size_t n) {
        while (true) {
            ssize_t r = ::read(fd, dst, n);
            if (r >= 0 || errno != EINTR) return r;
        }
    };
    while (true) {
        if (have < out->size()) {
            ssize_t n = readSome(reinterpret_cast<char *>(out->data()) + have, out->size() - have);
            if (n < 0) return fail(errno);
            if (n == 0) break;
            have += size_t(n);
            continue;
        }
        // Read everything fstat announced; the file may have grown since (or a filesystem may
        // report size 0), so read on in small pieces until the end or the limit.
        char chunk[1 << 12];
        ssize_t n = readSome(chunk, sizeof(chunk));
        if (n < 0) return fail(errno);
        if (n == 0) break;
        if (have + uint64_t(n) > maxBytes) {
            error->tooLarge = true;
            error->size = have + uint64_t(n);
            error->reason = "file is larger than the limit";
            return false;
        }
        out->insert(out->end(), chunk, chunk + n);
        have += size_t(n);
    }
    out->resize(have);
    // A file that is being written (a copy still in progress, an editor saving) gives a mix of
    // old and new bytes or a truncated text that may still parse: refuse it when its size or
    // modification time moved while it was read. (Files such as /proc's report size 0.)
    struct stat after;
    if (size > 0 && (have != size || ::fstat(fd, &after) != 0 || after.st_size != st.st_size ||
                     after.st_mtim.tv_sec != st.st_mtim.tv_sec ||
                     after.st_mtim.tv_nsec != st.st_mtim.tv_nsec)) {
        error->reason = "the file changed while it was read (" + std::to_string(size) +
                        " bytes when opened, " + std::to_string(have) +
                        " read); is it still being written?";
        return false;
    }
    return true;
}

}  // namespace

bool ReadFileContents(const std::string &path, std::string *out, FileReadError *error,
                      uint64_t maxBytes) {
    return ReadInto(path, out, error, maxBytes);
}

bool ReadFileContents(const std::string &path, std::vector<unsigned char> *out,
                      FileReadError *error, uint64_t maxBytes) {
    return ReadInto(path, out, error, maxBytes);
}

std::string ReadFileOrThrow(const std::string &path, const FileLoc &loc, uint64_t maxBytes) {
    std::string text;
    FileReadError err;
    if (ReadFileContents(path, &text, &err, maxBytes)) return text;
    if (err.tooLarge)
        throw MemoryBudgetError(loc,
                                "file is " + FormatBytes(err.size) +
                                    ", more than the memory budget of " + FormatBytes(maxBytes),
                                err.size, 0, maxBytes);
    if (err.refused) throw SceneError(loc, "cannot read file " + Quote(path) + ": " + err.reason);
    throw SceneError(loc, "cannot open file " + Quote(path) + ": " + err.reason);
}

std::string ReadFileOrThrow(const std::string &path, const FileLoc &loc, MemoryBudget &budget,
                            std::string_view what) {
    std::string text;
    FileReadError err;
    if (ReadFileContents(path, &text, &err, budget.Remaining())) {
        budget.Charge(text.size(), what, loc);
        return text;
    }
    if (err.tooLarge) {
        budget.Check(err.size, what, loc);
        // Only reached when another thread released memory since Remaining() was read.
        uint64_t used = budget.Used();
        throw MemoryBudgetError(loc, budget.ExceededMessage(err.size, used, what), err.size, used,
                                budget.Limit());
    }
    if (err.refused) throw SceneError(loc, "cannot read file " + Quote(path) + ": " + err.reason);
    throw SceneError(loc, "cannot open file " + Quote(path) + ": " + err.reason);
}

ScopedReadConfinement::ScopedReadConfinement(const std::string &folder,
                                             const std::vector<std::string> &operatorFiles) {
    std::string canonical = folder.empty() ? std::string() : CanonicalPath(folder);
    std::vector<std::string> allowed;
    for (const std::string &f : operatorFiles) allowed.push_back(CanonicalPath(f));
    std::lock_guard<std::mutex> lock(g_confinementMutex);
    previous_ = g_confinementFolder;
    previousAllowed_ = g_operatorFiles;
    g_confinementFolder = canonical;
    g_operatorFiles = std::move(allowed);
}

ScopedReadConfinement::~ScopedReadConfinement() {
    std::lock_guard<std::mutex> lock(g_confinementMutex);
    g_confinementFolder = previous_;
    g_operatorFiles = previousAllowed_;
}

std::string ReadConfinementFolder() {
    std::lock_guard<std::mutex> lock(g_confinementMutex);
    return g_confinementFolder;
}

std::string ReadConfinementRefusal(const std::string &path) {
    const std::string folder = ReadConfinementFolder();
    if (folder.empty()) return {};
    std::string resolved = CanonicalPath(path);
    if (!InsideFolder(resolved, folder) && !OperatorFile(resolved)) return OutsideReason();
    struct stat st;
    if (::stat(resolved.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
        return "it is not a regular file";
    return {};
}

void CheckReadConfinement(const std::string &path, const FileLoc &loc, std::string_view what,
                          const std::string &name) {
    std::string why = ReadConfinementRefusal(path);
    if (!why.empty()) throw SceneError(loc, std::string(what) + " " + Quote(name) + ": " + why);
}

std::string ShellQuote(const std::string &s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string ToLowerAscii(std::string_view s) {
    std::string r(s);
    for (char &c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

std::string LowerExtension(const std::string &path) {
    return ToLowerAscii(std::filesystem::path(path).extension().string());
}

std::string DirectoryOf(const std::string &path) {
    return std::filesystem::path(path).parent_path().string();
}

std::string CanonicalPath(const std::string &path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec) absolute = path;
    fs::path c = fs::weakly_canonical(absolute, ec);
    if (ec) c = absolute.lexically_normal();
    return c.string();
}

}  // namespace prism
