#include "core/output_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"

namespace prism {

namespace {

std::string Reason(const char *what, int err) {
    return std::string(what) + ": " + std::strerror(err);
}

// Six characters from [0-9a-z]: getrandom, or (should it fail) the clock and a counter.
std::string RandomSuffix() {
    static std::atomic<uint64_t> counter{0};
    unsigned char bytes[6];
    if (getrandom(bytes, sizeof(bytes), GRND_NONBLOCK) != ssize_t(sizeof(bytes))) {
        uint64_t v = uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                     (counter.fetch_add(1) * 0x9e3779b97f4a7c15ull);
        for (unsigned char &b : bytes) b = (unsigned char)(v >>= 8);
    }
    static const char kChars[] = "0123456789abcdefghijklmnopqrstuvwxyz";
    std::string s;
    for (unsigned char b : bytes) s += kChars[b % 36];
    return s;
}

}  // namespace

int CreateUniqueFile(const std::string &dir, std::string_view suffix, std::string *path) {
    namespace fs = std::filesystem;
    const std::string base = std::string(kTemporaryOutputPrefix) + std::to_string(::getpid()) + "-";
    int err = EEXIST;
    for (int attempt = 0; attempt < 100 && err == EEXIST; ++attempt) {
        std::string name = base + RandomSuffix() + std::string(suffix);
        std::string p = dir.empty() ? name : (fs::path(dir) / name).string();
        // 0666 as fopen: the umask decides, as it did for every output before.
        int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) {
            *path = p;
            return fd;
        }
        err = errno;
    }
    throw std::runtime_error("could not create a temporary file in " +
                             Quote(dir.empty() ? "." : dir) + ": " + std::strerror(err));
}

AtomicOutputFile::AtomicOutputFile(const std::string &target, bool sync)
    : target_(target), sync_(sync) {
    fd_ = CreateUniqueFile(std::filesystem::path(target).parent_path().string(), ".tmp", &tmp_);
}

AtomicOutputFile::~AtomicOutputFile() { Discard(); }

void AtomicOutputFile::Discard() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!tmp_.empty()) ::unlink(tmp_.c_str());
    tmp_.clear();
}

void AtomicOutputFile::Write(const void *data, size_t n) {
    if (fd_ < 0) throw std::runtime_error("write error: the file is closed");
    const char *p = static_cast<const char *>(data);
    while (n > 0) {
        ssize_t w = ::write(fd_, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) throw std::runtime_error(Reason("write error", w < 0 ? errno : ENOSPC));
        p += w;
        n -= size_t(w);
    }
}

uint64_t AtomicOutputFile::Tell() const {
    off_t pos = fd_ < 0 ? -1 : ::lseek(fd_, 0, SEEK_CUR);
    if (pos < 0) throw std::runtime_error(Reason("seek error", errno));
    return uint64_t(pos);
}

void AtomicOutputFile::Seek(uint64_t pos) {
    if (fd_ < 0 || ::lseek(fd_, off_t(pos), SEEK_SET) < 0)
        throw std::runtime_error(Reason("seek error", errno));
}

void AtomicOutputFile::Commit() {
    if (fd_ < 0) throw std::runtime_error("write error: the file is closed");
    // fsync reports what a delayed write could not store (network and quota file systems
    // report a full disk only here); close can report it too.
    int err = 0;
    if (sync_ && ::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) err = errno;
    if (::close(fd_) != 0 && err == 0 && errno != EINTR) err = errno;
    fd_ = -1;
    if (err == 0 && ::rename(tmp_.c_str(), target_.c_str()) != 0) {
        err = errno;
        Discard();
        throw std::runtime_error(std::strerror(err));
    }
    if (err != 0) {
        Discard();
        throw std::runtime_error(Reason("write error", err));
    }
    tmp_.clear();
}

void WriteFileAtomically(const std::string &path, std::string_view contents, bool sync) {
    try {
        AtomicOutputFile f(path, sync);
        f.Write(contents);
        f.Commit();
    } catch (const std::runtime_error &e) {
        throw std::runtime_error("cannot write " + Quote(path) + ": " + e.what());
    }
}

long TemporaryOutputPid(std::string_view name) {
    if (name.substr(0, kTemporaryOutputPrefix.size()) != kTemporaryOutputPrefix) return -1;
    name.remove_prefix(kTemporaryOutputPrefix.size());
    long pid = 0;
    size_t i = 0;
    for (; i < name.size() && i < 10 && name[i] >= '0' && name[i] <= '9'; ++i)
        pid = pid * 10 + (name[i] - '0');
    if (i == 0 || i >= name.size() || name[i] != '-') return -1;
    std::string_view rest = name.substr(i + 1);  // XXXXXX.tmp or XXXXXX.log.tmp
    if (rest.size() < 6) return -1;
    for (char c : rest.substr(0, 6))
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z'))) return -1;
    rest.remove_prefix(6);
    if (rest != ".tmp" && rest != ".log.tmp") return -1;
    return pid;
}

int RemoveStaleTemporaries(const std::string &dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::directory_iterator it(dir.empty() ? "." : dir, ec), end;
    int removed = 0;
    const time_t now = ::time(nullptr);
    for (; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        long pid = TemporaryOutputPid(name);
        if (pid <= 0 || pid == long(::getpid())) continue;
        struct stat st;
        if (::lstat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode) ||
            st.st_uid != ::geteuid() || now - st.st_mtime < kStaleTemporarySeconds)
            continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours
        if (::unlink(it->path().c_str()) == 0) ++removed;
    }
    return removed;
}

}  // namespace prism
