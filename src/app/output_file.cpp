#include "app/output_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
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
    FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write \"" + path + "\"");
    bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
    ok = (std::fclose(f) == 0) && ok;
    std::error_code ec;
    if (ok) fs::rename(tmp, target, ec);
    if (!ok || ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error("cannot write \"" + path + "\"");
    }
}

}  // namespace prism
