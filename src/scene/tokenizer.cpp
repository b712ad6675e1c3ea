#include "scene/tokenizer.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace prism {

Tokenizer::Tokenizer(std::string text, std::string filename)
    : text_(std::move(text)), filename_(std::move(filename)) {
    // Skip a UTF-8 byte-order mark left by some Windows editors.
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = lineStart_ = 3;
}

void Tokenizer::Fail(int line, int column, const std::string &msg) const {
    throw SceneError(FileLoc{filename_, line, column}, msg);
}

const Token &Tokenizer::Peek() {
    if (!hasPeeked_) {
        peeked_ = Scan();
        hasPeeked_ = true;
    }
    return peeked_;
}

Token Tokenizer::Next() {
    if (hasPeeked_) {
        hasPeeked_ = false;
        return peeked_;
    }
    return Scan();
}

void Tokenizer::SkipSpaceAndComments() {
    const size_t n = text_.size();
    while (pos_ < n) {
        char c = text_[pos_];
        if (c == '\n') {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < n && text_[pos_] != '\n') ++pos_;
        } else {
            return;
        }
    }
}

static bool IsWordStart(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static bool IsWordChar(char c) { return IsWordStart(c) || (c >= '0' && c <= '9'); }
static bool IsNumberStart(char c) {
    return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+';
}
static bool IsNumberChar(char c) {
    return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E';
}

Token Tokenizer::Scan() {
    SkipSpaceAndComments();
    Token t;
    t.file = &filename_;
    t.line = line_;
    t.column = int(pos_ - lineStart_) + 1;
    const size_t n = text_.size();
    if (pos_ >= n) return t;  // End

    const char *base = text_.data();
    char c = text_[pos_];
    size_t start = pos_;
    if (c == '[' || c == ']') {
        t.kind = c == '[' ? TokenKind::LBracket : TokenKind::RBracket;
        t.text = std::string_view(base + pos_, 1);
        ++pos_;
        return t;
    }
    if (c == '"') {
        ++pos_;
        while (true) {
            if (pos_ >= n) Fail(t.line, t.column, "unterminated string");
            char d = text_[pos_];
            if (d == '"') break;
            if (d == '\n') Fail(t.line, t.column, "unterminated string (a newline inside quotes)");
            if (d == '\\') {
                t.hasEscapes = true;
                ++pos_;
                if (pos_ >= n) Fail(t.line, t.column, "unterminated string");
                if (text_[pos_] == '\n')
                    Fail(t.line, t.column, "unterminated string (a newline inside quotes)");
                switch (text_[pos_]) {
                    case '"':
                    case '\\':
                    case 'n':
                    case 't':
                    case 'r':
                    case 'b':
                    case 'f':
                    case '\'':
                        break;
                    default:
                        Fail(line_, int(pos_ - lineStart_),
                             std::string("unknown escape sequence \"\\") + text_[pos_] + "\"");
                }
            }
            ++pos_;
        }
        t.kind = TokenKind::String;
        t.text = std::string_view(base + start + 1, pos_ - start - 1);
        ++pos_;  // closing quote
        return t;
    }
    if (IsWordStart(c)) {
        while (pos_ < n && IsWordChar(text_[pos_])) ++pos_;
        t.kind = TokenKind::Word;
        t.text = std::string_view(base + start, pos_ - start);
        return t;
    }
    if (IsNumberStart(c)) {
        // Take the maximal run of number characters (and any letters glued to it, so "1x"
        // is reported whole), then require from_chars to consume all of it.
        while (pos_ < n && (IsNumberChar(text_[pos_]) || IsWordChar(text_[pos_]))) ++pos_;
        t.kind = TokenKind::Number;
        t.text = std::string_view(base + start, pos_ - start);
        const char *first = base + start, *last = base + pos_;
        // from_chars rejects a leading '+', so skip it (but not a second sign after it).
        if (*first == '+' && first + 1 < last && first[1] != '-' && first[1] != '+') ++first;
        double v = 0;
        auto [ptr, ec] = std::from_chars(first, last, v);
        // Out-of-range values such as 1e999 fail here too; pbrt numbers are finite.
        if (ec != std::errc() || ptr != last || !std::isfinite(v))
            Fail(t.line, t.column, "invalid number \"" + std::string(t.text) + "\"");
        t.number = v;
        return t;
    }
    std::string shown;
    if (static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f)
        shown = std::string("'") + c + "'";
    else {
        char buf[8];
        std::snprintf(buf, sizeof(buf), "0x%02x", unsigned(static_cast<unsigned char>(c)));
        shown = buf;
    }
    Fail(t.line, t.column, "unexpected character " + shown);
}

std::string Tokenizer::StringValue(const Token &t) {
    if (!t.hasEscapes) return std::string(t.text);
    std::string out;
    out.reserve(t.text.size());
    for (size_t i = 0; i < t.text.size(); ++i) {
        char c = t.text[i];
        if (c != '\\' || i + 1 == t.text.size()) {
            out += c;
            continue;
        }
        switch (t.text[++i]) {
            case 'n':
                out += '\n';
                break;
            case 't':
                out += '\t';
                break;
            case 'r':
                out += '\r';
                break;
            case 'b':
                out += '\b';
                break;
            case 'f':
                out += '\f';
                break;
            default:
                out += t.text[i];
                break;  // \" \\ \'
        }
    }
    return out;
}

std::string Tokenizer::Describe(const Token &t) {
    switch (t.kind) {
        case TokenKind::End:
            return "end of file";
        case TokenKind::String: {
            std::string s;
            s.reserve(t.text.size() + 2);
            s.append(1, '"').append(t.text).append(1, '"');
            return s;
        }
        default:
            return std::string(t.text);
    }
}

}  // namespace prism
