// User-facing diagnostics: source locations, located errors and collected warnings.
// Scene-data problems throw SceneError (caught in main: exit status 2); programmer errors use
// CHECK (core/check.h). No global state: a Diagnostics object is passed where warnings arise.
#pragma once

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace prism {

// `s` in double quotes, as names are shown in messages: unknown directive "Sphere".
inline std::string Quote(std::string_view s) {
    std::string r;
    r.reserve(s.size() + 2);
    r.append(1, '"').append(s).append(1, '"');
    return r;
}

struct FileLoc {
    std::string file;  // shared by every token of one file; empty for command-line input
    int line = 0, column = 0;
    std::string ToString() const;  // "file:line:col", or "file" when line is 0
    bool Valid() const { return !file.empty(); }
};

class SceneError : public std::runtime_error {
  public:
    SceneError(const FileLoc &loc, const std::string &msg);
    explicit SceneError(const std::string &msg) : std::runtime_error(msg) {}
    const FileLoc &Loc() const { return loc_; }
    const std::string &Message() const { return msg_; }

  private:
    FileLoc loc_;
    std::string msg_;
};

struct Warning {
    FileLoc loc;
    std::string message;
    std::string ToString() const;  // "file:line:col: warning: message"
};

// Thread-safe collector of warnings. Identical warnings are kept once (with a count), so a
// per-pixel or per-shape problem does not flood the terminal.
class Diagnostics {
  public:
    explicit Diagnostics(bool echo = false) : echo_(echo) {}
    void Warn(const FileLoc &loc, const std::string &message);
    void Warn(const std::string &message) { Warn(FileLoc{}, message); }
    // Warns only the first time `key` is seen (e.g. one warning per unsupported feature,
    // at its first location); later occurrences are counted in OnceCount(key).
    void WarnOnce(const std::string &key, const FileLoc &loc, const std::string &message);
    int OnceCount(const std::string &key) const;
    std::vector<Warning> Warnings() const;
    size_t Count() const;
    void SetEcho(bool echo) { echo_ = echo; }

  private:
    mutable std::mutex mutex_;
    std::vector<Warning> warnings_;
    std::vector<std::pair<std::string, int>> once_;
    bool echo_;
};

}  // namespace prism
