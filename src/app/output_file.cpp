#include "app/output_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace prism {

void WriteFileAtomically(const std::string &path, const std::string &contents) {
    namespace fs = std::filesystem;
    static std::atomic<int> counter{0};
    fs::path target(path);
    fs::path tmp =
        target.parent_path() / ("." + target.filename().string() + ".tmp-" +
                                std::to_string(getpid()) + "-" + std::to_string(counter++));
    auto fail = [&](int err) {
        return std::runtime_error("cannot write \"" + path + "\": " + std::strerror(err));
    };
    FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw fail(errno);
    bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
    int err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) ok = false, err = errno;
    std::error_code ec;
    if (ok) fs::rename(tmp, target, ec);
    if (!ok || ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw fail(ok ? ec.value() : err);
    }
}

}  // namespace prism
