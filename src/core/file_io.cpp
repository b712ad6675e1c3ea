#include "core/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/memory.h"

namespace prism {

namespace {

template <typename Buffer>
bool ReadInto(const std::string &path, Buffer *out, FileReadError *error, uint64_t maxBytes) {
    *error = FileReadError{};
    auto fail = [&](int err) {
        error->reason = std::strerror(err);
        return false;
    };
    // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below.
    int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return fail(errno);
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
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
    throw SceneError(loc, "cannot open file " + Quote(path) + ": " + err.reason);
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
