// The pbrt text rewrites of `prism bench compare`: a Sampler's count and a Film's size set in a
// scene's own text, through the pbrt tokenizer (compare.h).
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "scene/tokenizer.h"
#include "tools/bench/compare.h"

namespace prism {

namespace {

// Byte offsets of the starts of the lines of `text` (Token::line and column are 1-based).
std::vector<size_t> LineStarts(const std::string &text) {
    std::vector<size_t> starts{0};
    for (size_t i = 0; i < text.size(); ++i)
        if (text[i] == '\n') starts.push_back(i + 1);
    return starts;
}

struct Edit {
    size_t begin, end;
    std::string text;
};

}  // namespace

// The integer parameters `values(name)` of every `directive` before WorldBegin set (the values
// replaced, or added after the directive's name), and `insert` put before WorldBegin when the
// file has no such directive.
std::string SetDirectiveInts(
    const std::string &text, const std::string &directive,
    const std::function<std::vector<std::pair<std::string, int>>(const std::string &)> &values,
    const std::string &insert, const std::string &file) {
    const std::vector<size_t> starts = LineStarts(text);
    auto offset = [&](const Token &t) { return starts[size_t(t.line - 1)] + size_t(t.column - 1); };
    // A token's end: a string's text excludes its quotes.
    auto end = [&](const Token &t) {
        return offset(t) + t.text.size() + (t.kind == TokenKind::String ? 2 : 0);
    };
    Tokenizer tok(text, file);
    std::vector<Edit> edits;
    bool seen = false;
    while (true) {
        Token t = tok.Next();
        if (t.kind == TokenKind::End)
            throw SceneError(FileLoc{file}, "no WorldBegin: not a pbrt-v3 scene");
        if (t.kind != TokenKind::Word) continue;
        if (t.text == "WorldBegin") {
            if (!seen) edits.push_back({offset(t), offset(t), insert});
            break;
        }
        if (t.text != directive) continue;
        seen = true;
        Token name = tok.Next();
        if (name.kind != TokenKind::String)
            throw SceneError(name.Loc(), directive + " needs a name");
        const std::vector<std::pair<std::string, int>> wanted =
            values(Tokenizer::StringValue(name));
        std::vector<bool> done(wanted.size(), false);
        while (tok.Peek().kind == TokenKind::String) {
            Token decl = tok.Next();
            std::istringstream words(Tokenizer::StringValue(decl));
            std::string type, param;
            words >> type >> param;
            size_t vBegin = 0, vEnd = 0;
            if (tok.Peek().kind == TokenKind::LBracket) {
                vBegin = offset(tok.Next());
                Token v = tok.Next();
                while (v.kind != TokenKind::RBracket && v.kind != TokenKind::End) v = tok.Next();
                if (v.kind == TokenKind::End)
                    throw SceneError(decl.Loc(), "unterminated values of \"" + param + "\"");
                vEnd = end(v);
            } else {
                Token v = tok.Next();
                vBegin = offset(v);
                vEnd = end(v);
            }
            for (size_t i = 0; i < wanted.size(); ++i)
                if (param == wanted[i].first) {
                    edits.push_back({vBegin, vEnd, "[ " + std::to_string(wanted[i].second) + " ]"});
                    done[i] = true;
                }
        }
        std::string add;
        for (size_t i = 0; i < wanted.size(); ++i)
            if (!done[i])
                add += " \"integer " + wanted[i].first + "\" [ " +
                       std::to_string(wanted[i].second) + " ]";
        if (!add.empty()) edits.push_back({end(name), end(name), add});
    }
    std::sort(edits.begin(), edits.end(),
              [](const Edit &a, const Edit &b) { return a.begin < b.begin; });
    std::string out;
    size_t pos = 0;
    for (const Edit &e : edits) {
        out.append(text, pos, e.begin - pos);
        out += e.text;
        pos = e.end;
    }
    out.append(text, pos, std::string::npos);
    return out;
}

std::string SetPbrtV3SampleCount(const std::string &text, int spp, const std::string &file) {
    // pbrt-v4's split of --spp for the stratified sampler: the largest divisor up to sqrt(n).
    int xs = std::max(1, int(std::sqrt(double(spp))));
    while (spp % xs) --xs;
    const int ys = spp / xs;
    return SetDirectiveInts(
        text, "Sampler",
        [&](const std::string &name) -> std::vector<std::pair<std::string, int>> {
            if (name == "stratified") return {{"xsamples", xs}, {"ysamples", ys}};
            return {{"pixelsamples", spp}};
        },
        "Sampler \"halton\" \"integer pixelsamples\" [ " + std::to_string(spp) + " ]\n", file);
}

std::string SetPbrtResolution(const std::string &text, int width, int height,
                              const std::string &defaultFilm, const std::string &file) {
    return SetDirectiveInts(
        text, "Film",
        [&](const std::string &) -> std::vector<std::pair<std::string, int>> {
            return {{"xresolution", width}, {"yresolution", height}};
        },
        "Film \"" + defaultFilm + "\" \"integer xresolution\" [ " + std::to_string(width) +
            " ] \"integer yresolution\" [ " + std::to_string(height) + " ]\n",
        file);
}

}  // namespace prism
