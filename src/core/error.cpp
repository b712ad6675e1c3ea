#include "core/error.h"

#include <cstdio>

namespace prism {

std::string FileLoc::ToString() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

static std::string Located(const FileLoc &loc, const std::string &msg) {
    return loc.Valid() ? loc.ToString() + ": error: " + msg : "error: " + msg;
}

SceneError::SceneError(const FileLoc &loc, const std::string &msg)
    : std::runtime_error(Located(loc, msg)), loc_(loc), msg_(msg) {}

std::string Warning::ToString() const {
    return loc.Valid() ? loc.ToString() + ": warning: " + message : "warning: " + message;
}

void Diagnostics::Warn(const FileLoc &loc, const std::string &message) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Warning &w : warnings_)
        if (w.message == message && w.loc.ToString() == loc.ToString()) return;
    warnings_.push_back({loc, message});
    if (echo_) std::fprintf(stderr, "%s\n", warnings_.back().ToString().c_str());
}

void Diagnostics::WarnOnce(const std::string &key, const FileLoc &loc, const std::string &message) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto &[k, n] : once_)
            if (k == key) {
                ++n;
                return;
            }
        once_.emplace_back(key, 1);
    }
    Warn(loc, message);
}

int Diagnostics::OnceCount(const std::string &key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto &[k, n] : once_)
        if (k == key) return n;
    return 0;
}

std::vector<Warning> Diagnostics::Warnings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_;
}

size_t Diagnostics::Count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_.size();
}

}  // namespace prism
