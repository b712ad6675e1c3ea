// User-facing diagnostics: source locations, located errors and collected warnings.
// Scene-data problems throw SceneError (caught in main: exit status 2); programmer errors use
// CHECK (core/check.h). No global state: a Diagnostics object is passed where warnings arise.
#pragma once

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace prism {

// `s` with every control character (bytes 0x00-0x1f and 0x7f: NUL, newline, escape, ...)
// written as `\xNN`: names from a scene reach terminals, logs and summary.txt, where an escape
// sequence would act and a NUL or newline would cut or split the message. Other bytes, and
// backslashes, are kept, so escaping twice changes nothing more.
std::string EscapeControlChars(std::string_view s);

// `s` in double quotes, as names are shown in messages: unknown directive "Sphere"; control
// characters escaped (EscapeControlChars).
inline std::string Quote(std::string_view s) {
    std::string r;
    r.reserve(s.size() + 2);
    r.append(1, '"').append(EscapeControlChars(s)).append(1, '"');
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
    std::string ToString() const;  // "file:line:col: warning: message", control chars escaped
};

// Thread-safe collector of warnings. Identical warnings (same location and message) are kept
// once, so a per-pixel or per-shape problem does not flood the terminal; and of warnings of
// one kind (the same message but for the names in quotes and the numbers: `unused parameter
// "a" (shape "sphere")` and `unused parameter "b" ...`) the first kMaxPerKind are kept and the
// rest only counted, summed up in one `and N more warnings like: MESSAGE` line. Both checks
// are hash lookups, so 40,000 warnings cost no more than 40,000 times one.
class Diagnostics {
  public:
    static constexpr int kMaxPerKind = 10;

    explicit Diagnostics(bool echo = false) : echo_(echo) {}
    // Echoes the summary lines not printed yet (see Flush).
    ~Diagnostics();
    Diagnostics(const Diagnostics &) = delete;
    Diagnostics &operator=(const Diagnostics &) = delete;

    void Warn(const FileLoc &loc, const std::string &message);
    void Warn(const std::string &message) { Warn(FileLoc{}, message); }
    // Warns only the first time `key` is seen (e.g. one warning per unsupported feature,
    // at its first location); later occurrences are counted in OnceCount(key).
    void WarnOnce(const std::string &key, const FileLoc &loc, const std::string &message);
    int OnceCount(const std::string &key) const;
    // The warnings kept, then one `and N more warnings like: ...` per kind over the cap.
    std::vector<Warning> Warnings() const;
    // Warnings() .size().
    size_t Count() const;
    // How many warnings were counted but not kept (over kMaxPerKind), in all.
    size_t Suppressed() const;
    // When echoing: prints the summary line of every kind that went over the cap since the
    // last Flush (the app calls it once the scene is loaded and built).
    void Flush();
    void SetEcho(bool echo) { echo_ = echo; }

  private:
    struct Kind {
        int count = 0;             // warnings of this kind, kept or not
        std::string firstDropped;  // the first one not kept
        int echoedDropped = 0;     // the number of dropped ones the last echoed summary named
    };
    std::vector<Warning> SummaryLines() const;  // under mutex_

    mutable std::mutex mutex_;
    std::vector<Warning> warnings_;
    std::unordered_set<std::string> seen_;  // location "\n" message of every warning
    std::unordered_map<std::string, Kind> kinds_;
    // kinds_' keys (stable: a node's key never moves) in the order they went over the cap.
    std::vector<const std::string *> overflowed_;
    std::unordered_map<std::string, int> once_;
    size_t suppressed_ = 0;
    bool echo_;
};

}  // namespace prism
