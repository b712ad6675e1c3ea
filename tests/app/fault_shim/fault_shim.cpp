// An LD_PRELOAD library for the fault tests (tests/app/fault_cli_test.cpp): it makes the faults a
// render farm sees happen on demand, in any build and without privileges. Each is switched on by
// an environment variable (and otherwise the library does nothing):
//   PRISM_FAULT_ENOSPC_AFTER=N   fwrite() and write() to files (descriptors above 2) fail with
//                                ENOSPC once N bytes have been written: a full disk.
//   PRISM_FAULT_TRUNCATE=NAME    the first read() of a file whose name is NAME reads half of it
//                                and truncates the file to that half: a file cut short while
//                                it is read (a copy in progress).
//   PRISM_FAULT_KILL=TEXT        a `prism render` process whose arguments contain TEXT kills
//                                itself with SIGKILL at start-up, as the OOM killer would.
//   PRISM_FAULT_FORBID_OPEN=NAME opening (open, openat, fopen) a path whose last component is
//                                NAME prints "fault_shim: NAME opened" and exits with status
//                                99: proof that a file Prism must refuse is never opened.
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>

// The next definition of `name` (libc's), looked up once per call site.
template <typename F>
static F Next(const char *name) {
    return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}

extern "C" {

static long long g_written = 0;
static int g_truncated = 0;

static long long EnospcLimit(void) {
    const char *v = getenv("PRISM_FAULT_ENOSPC_AFTER");
    return v ? atoll(v) : -1;
}

// How many of `n` bytes may still be written to a file, or -1 when no limit is set.
static long long Allowance(int fd, size_t n) {
    long long limit = EnospcLimit();
    if (limit < 0 || fd <= 2) return -1;
    long long left = limit - g_written;
    if (left < 0) left = 0;
    return (long long)n < left ? (long long)n : left;
}

size_t fwrite(const void *ptr, size_t size, size_t count, FILE *stream) {
    static size_t (*real)(const void *, size_t, size_t, FILE *) = nullptr;
    if (!real)
        real = reinterpret_cast<size_t (*)(const void *, size_t, size_t, FILE *)>(
            dlsym(RTLD_NEXT, "fwrite"));
    size_t bytes = size * count;
    long long allowed = size ? Allowance(fileno(stream), bytes) : -1;
    if (allowed < 0) return real(ptr, size, count, stream);
    size_t items = (size_t)allowed / size;
    size_t done = items ? real(ptr, size, items, stream) : 0;
    g_written += (long long)(done * size);
    if (done < count) {
        stream->_flags |= _IO_ERR_SEEN;  // as glibc marks a stream whose write failed
        errno = ENOSPC;
    }
    return done;
}

ssize_t write(int fd, const void *buf, size_t n) {
    static ssize_t (*real)(int, const void *, size_t) = nullptr;
    if (!real)
        real = reinterpret_cast<ssize_t (*)(int, const void *, size_t)>(dlsym(RTLD_NEXT, "write"));
    long long allowed = Allowance(fd, n);
    if (allowed < 0) return real(fd, buf, n);
    if (allowed == 0) {
        errno = ENOSPC;
        return -1;
    }
    ssize_t r = real(fd, buf, (size_t)allowed);
    if (r > 0) g_written += r;
    return r;
}

ssize_t read(int fd, void *buf, size_t n) {
    static ssize_t (*real)(int, void *, size_t) = nullptr;
    if (!real) real = reinterpret_cast<ssize_t (*)(int, void *, size_t)>(dlsym(RTLD_NEXT, "read"));
    const char *name = getenv("PRISM_FAULT_TRUNCATE");
    if (!name || g_truncated || fd <= 2) return real(fd, buf, n);
    char link[64], path[4096];
    snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
    ssize_t len = readlink(link, path, sizeof(path) - 1);
    if (len <= 0) return real(fd, buf, n);
    path[len] = '\0';
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    struct stat st;
    if (strcmp(base, name) != 0 || fstat(fd, &st) != 0 || st.st_size < 2) return real(fd, buf, n);
    g_truncated = 1;
    size_t half = (size_t)st.st_size / 2;
    ssize_t r = real(fd, buf, n < half ? n : half);
    if (truncate(path, (off_t)half) != 0) return -1;
    return r;
}

static void ForbidOpen(const char *path) {
    const char *name = getenv("PRISM_FAULT_FORBID_OPEN");
    if (!name || !*name || !path) return;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    if (strcmp(base, name) != 0) return;
    static const char msg[] = "fault_shim: forbidden file opened\n";
    ssize_t ignored = syscall(SYS_write, 2, msg, sizeof(msg) - 1);
    (void)ignored;
    _exit(99);
}

static mode_t ModeArg(int flags, va_list ap) {
    return (flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE ? mode_t(va_arg(ap, int)) : 0;
}

int open(const char *path, int flags, ...) {
    static auto real = Next<int (*)(const char *, int, ...)>("open");
    ForbidOpen(path);
    va_list ap;
    va_start(ap, flags);
    mode_t mode = ModeArg(flags, ap);
    va_end(ap);
    return real(path, flags, mode);
}

int open64(const char *path, int flags, ...) {
    static auto real = Next<int (*)(const char *, int, ...)>("open64");
    ForbidOpen(path);
    va_list ap;
    va_start(ap, flags);
    mode_t mode = ModeArg(flags, ap);
    va_end(ap);
    return real(path, flags, mode);
}

int openat(int dirfd, const char *path, int flags, ...) {
    static auto real = Next<int (*)(int, const char *, int, ...)>("openat");
    ForbidOpen(path);
    va_list ap;
    va_start(ap, flags);
    mode_t mode = ModeArg(flags, ap);
    va_end(ap);
    return real(dirfd, path, flags, mode);
}

FILE *fopen(const char *path, const char *mode) {
    static auto real = Next<FILE *(*)(const char *, const char *)>("fopen");
    ForbidOpen(path);
    return real(path, mode);
}

FILE *fopen64(const char *path, const char *mode) {
    static auto real = Next<FILE *(*)(const char *, const char *)>("fopen64");
    ForbidOpen(path);
    return real(path, mode);
}

__attribute__((constructor)) static void KillIfAsked(void) {
    const char *text = getenv("PRISM_FAULT_KILL");
    if (!text || !*text) return;
    FILE *f = fopen("/proc/self/cmdline", "r");
    if (!f) return;
    char args[8192];
    size_t n = fread(args, 1, sizeof(args) - 1, f);
    fclose(f);
    args[n] = '\0';
    // argv[0] '\0' argv[1] '\0' ...: a render whose arguments name TEXT.
    size_t first = strlen(args) + 1;
    if (first >= n || strcmp(args + first, "render") != 0) return;
    for (size_t i = first; i < n; i += strlen(args + i) + 1)
        if (strstr(args + i, text)) raise(SIGKILL);
}

}  // extern "C"
