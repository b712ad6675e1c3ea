#include "core/error.h"

#include <cstdio>

namespace prism {

std::string EscapeControlChars(std::string_view s) {
    static const char kHex[] = "0123456789abcdef";
    std::string r;
    r.reserve(s.size());
    for (char c : s) {
        unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            r += "\\x";
            r += kHex[u >> 4];
            r += kHex[u & 15];
        } else {
            r += c;
        }
    }
    return r;
}

std::string FileLoc::ToString() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// The message's control characters are escaped here too (not only the names it quoted):
// what() is a C string, so a NUL in a path would otherwise end the message there.
static std::string Located(const FileLoc &loc, const std::string &msg) {
    return EscapeControlChars(loc.Valid() ? loc.ToString() + ": error: " + msg : "error: " + msg);
}

SceneError::SceneError(const FileLoc &loc, const std::string &msg)
    : std::runtime_error(Located(loc, msg)), loc_(loc), msg_(EscapeControlChars(msg)) {}

std::string Warning::ToString() const {
    return EscapeControlChars(loc.Valid() ? loc.ToString() + ": warning: " + message
                                          : "warning: " + message);
}

namespace {

// The kind of a warning: its message with every quoted part and every number left out.
std::string WarningKind(const std::string &message) {
    std::string kind;
    kind.reserve(message.size());
    bool quoted = false;
    for (size_t i = 0; i < message.size(); ++i) {
        char c = message[i];
        if (c == '"') {
            quoted = !quoted;
            kind += '"';
        } else if (quoted) {
            continue;
        } else if (c >= '0' && c <= '9') {
            if (kind.empty() || kind.back() != '#') kind += '#';
        } else {
            kind += c;
        }
    }
    return kind;
}

// 39990 -> "39,990".
std::string WithThousands(size_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

}  // namespace

Diagnostics::~Diagnostics() { Flush(); }

void Diagnostics::Warn(const FileLoc &loc, const std::string &message) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string key = loc.ToString();
    key += '\n';
    key += message;
    if (!seen_.insert(std::move(key)).second) return;
    auto it = kinds_.try_emplace(WarningKind(message)).first;
    Kind &kind = it->second;
    if (++kind.count > kMaxPerKind) {
        if (kind.count == kMaxPerKind + 1) {
            kind.firstDropped = message;
            overflowed_.push_back(&it->first);
        }
        ++suppressed_;
        return;
    }
    warnings_.push_back({loc, message});
    if (echo_) std::fprintf(stderr, "%s\n", warnings_.back().ToString().c_str());
}

void Diagnostics::WarnOnce(const std::string &key, const FileLoc &loc, const std::string &message) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (++once_[key] > 1) return;
    }
    Warn(loc, message);
}

int Diagnostics::OnceCount(const std::string &key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = once_.find(key);
    return it == once_.end() ? 0 : it->second;
}

std::vector<Warning> Diagnostics::SummaryLines() const {
    std::vector<Warning> lines;
    for (const std::string *k : overflowed_) {
        const Kind &kind = kinds_.at(*k);
        lines.push_back({FileLoc{}, "and " + WithThousands(size_t(kind.count - kMaxPerKind)) +
                                        " more warnings like: " + kind.firstDropped});
    }
    return lines;
}

std::vector<Warning> Diagnostics::Warnings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Warning> all = warnings_;
    for (Warning &w : SummaryLines()) all.push_back(std::move(w));
    return all;
}

size_t Diagnostics::Count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_.size() + overflowed_.size();
}

size_t Diagnostics::Suppressed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return suppressed_;
}

void Diagnostics::Flush() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!echo_) return;
    for (const std::string *k : overflowed_) {
        Kind &kind = kinds_.at(*k);
        int dropped = kind.count - kMaxPerKind;
        if (dropped == kind.echoedDropped) continue;
        // After an earlier summary of this kind, only the ones since.
        std::fprintf(stderr, "warning: and %s more warnings like: %s\n",
                     WithThousands(size_t(dropped - kind.echoedDropped)).c_str(),
                     EscapeControlChars(kind.firstDropped).c_str());
        kind.echoedDropped = dropped;
    }
}

}  // namespace prism
