#include "scene/pbrt_parser.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "scene/spectrum.h"
#include "scene/tokenizer.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

// Reads a whole file; on failure returns false with the OS reason in *why.
bool ReadWholeFile(const std::string &path, std::string *out, std::string *why) {
    // Refuse devices and pipes: reading /dev/zero or a FIFO would never finish.
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (st.type() == fs::file_type::directory) {
        *why = std::strerror(EISDIR);
        return false;
    }
    if (!ec && fs::exists(st) && st.type() != fs::file_type::regular) {
        *why = "not a regular file";
        return false;
    }
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) {
        *why = std::strerror(errno);
        return false;
    }
    out->clear();
    char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) out->append(buf, n);
    bool failed = std::ferror(f);
    int err = errno;
    std::fclose(f);
    if (failed) {
        *why = std::strerror(err);
        return false;
    }
    return true;
}

std::string Quoted(std::string_view s) {
    std::string r;
    r.reserve(s.size() + 2);
    r.append(1, '"').append(s).append(1, '"');
    return r;
}

fs::path CanonicalOrNormal(const fs::path &p) {
    std::error_code ec;
    fs::path c = fs::weakly_canonical(p, ec);
    if (ec) c = fs::absolute(p, ec).lexically_normal();
    return c;
}

// Saved graphics state: what AttributeBegin/End scope besides the transform and named maps.
struct GraphicsState {
    int material = -1;
    int areaLight = -1;
    bool reverseOrientation = false;
};

enum class FrameKind { Attribute, Transform, Object };

const char *FrameName(FrameKind k) {
    switch (k) {
    case FrameKind::Attribute: return "AttributeBegin";
    case FrameKind::Transform: return "TransformBegin";
    case FrameKind::Object: return "ObjectBegin";
    }
    return "";
}

struct Frame {
    FrameKind kind;
    FileLoc loc;
    Transform ctm;
    bool applyToStart;
    GraphicsState gs;
    size_t undoMark;  // size of the named-definition undo log when the frame was pushed
};

// Named materials and textures are scoped by AttributeBegin/End. Instead of copying the maps
// at every AttributeBegin (real scenes have tens of thousands), definitions are logged and
// undone when their scope closes.
enum class Namespace { Material, FloatTexture, SpectrumTexture };

struct UndoEntry {
    Namespace ns;
    std::string name;
    std::optional<int> previous;
};

// Grouped by handler: transform/scope directives up to ReverseOrientation, options-block
// directives up to Accelerator, world-block directives after (ParseDirective relies on this).
enum class Directive {
    AttributeBegin, AttributeEnd, TransformBegin, TransformEnd, Translate, Scale, Rotate, LookAt,
    Transform, ConcatTransform, Identity, CoordinateSystem, CoordSysTransform, ActiveTransform,
    TransformTimes, ReverseOrientation, Camera, Film, Sampler, PixelFilter, Integrator,
    Accelerator, WorldBegin, WorldEnd, Include, Import, Material, MakeNamedMaterial,
    NamedMaterial, Texture, LightSource, AreaLightSource, Shape, ObjectBegin, ObjectEnd,
    ObjectInstance, MakeNamedMedium, MediumInterface, Option, ColorSpace, Attribute
};

const std::unordered_map<std::string_view, Directive> &DirectiveTable() {
    static const std::unordered_map<std::string_view, Directive> table = {
        {"AttributeBegin", Directive::AttributeBegin}, {"AttributeEnd", Directive::AttributeEnd},
        {"TransformBegin", Directive::TransformBegin}, {"TransformEnd", Directive::TransformEnd},
        {"Translate", Directive::Translate}, {"Scale", Directive::Scale},
        {"Rotate", Directive::Rotate}, {"LookAt", Directive::LookAt},
        {"Transform", Directive::Transform}, {"ConcatTransform", Directive::ConcatTransform},
        {"Identity", Directive::Identity}, {"CoordinateSystem", Directive::CoordinateSystem},
        {"CoordSysTransform", Directive::CoordSysTransform},
        {"ActiveTransform", Directive::ActiveTransform},
        {"TransformTimes", Directive::TransformTimes},
        {"ReverseOrientation", Directive::ReverseOrientation}, {"Camera", Directive::Camera},
        {"Film", Directive::Film}, {"Sampler", Directive::Sampler},
        {"PixelFilter", Directive::PixelFilter}, {"Integrator", Directive::Integrator},
        {"Accelerator", Directive::Accelerator}, {"WorldBegin", Directive::WorldBegin},
        {"WorldEnd", Directive::WorldEnd}, {"Include", Directive::Include},
        {"Import", Directive::Import}, {"Material", Directive::Material},
        {"MakeNamedMaterial", Directive::MakeNamedMaterial},
        {"NamedMaterial", Directive::NamedMaterial}, {"Texture", Directive::Texture},
        {"LightSource", Directive::LightSource}, {"AreaLightSource", Directive::AreaLightSource},
        {"Shape", Directive::Shape}, {"ObjectBegin", Directive::ObjectBegin},
        {"ObjectEnd", Directive::ObjectEnd}, {"ObjectInstance", Directive::ObjectInstance},
        {"MakeNamedMedium", Directive::MakeNamedMedium},
        {"MediumInterface", Directive::MediumInterface}, {"Option", Directive::Option},
        {"ColorSpace", Directive::ColorSpace}, {"Attribute", Directive::Attribute},
    };
    return table;
}

class PbrtParser {
public:
    PbrtParser(SceneDescription &scene, Diagnostics &diag, const PbrtParseOptions &opts)
        : scene_(scene), diag_(diag), opts_(opts) {}

    void ParseTopLevel(std::string text, const std::string &filename);

private:
    void ParseFile(std::string text, const std::string &displayName, const fs::path &canonical);
    void ParseDirective(Tokenizer &tok, const Token &dir);
    void ParseTransformDirective(Tokenizer &tok, const Token &dir, Directive d);
    void ParseOptionDirective(Tokenizer &tok, const Token &dir, Directive d);
    void ParseWorldDirective(Tokenizer &tok, const Token &dir, Directive d);
    SceneEntity ReadEntity(Tokenizer &tok, const Token &dir, const char *what);

    // Positional arguments.
    std::vector<double> ReadNumbers(Tokenizer &tok, const Token &dir, size_t count);
    std::string ReadString(Tokenizer &tok, const Token &dir, const char *what);
    ParamSet ReadParams(Tokenizer &tok);
    void ReadParamValues(Tokenizer &tok, const Token &decl, std::string_view name,
                         std::vector<double> *numbers, std::vector<std::string> *strings);
    void ConvertParam(Param &p, std::string_view type, std::vector<double> &numbers,
                      std::vector<std::string> &strings);
    RGB SpectrumFile(const std::string &name, const FileLoc &loc);

    // Transform and graphics-state helpers.
    void ApplyTransform(const Transform &t, bool replace);
    void PushFrame(FrameKind kind, const FileLoc &loc);
    void PopFrame(FrameKind kind, const Token &dir);
    void DefineNamed(Namespace ns, const std::string &name, int index);
    std::unordered_map<std::string, int> &Names(Namespace ns);
    void CheckWorld(const Token &dir);
    void WarnUnclosedFrames();
    void Include(const Token &dir, const std::string &name);

    fs::path ResolvePath(const std::string &name) const;
    bool InsideBaseDir(const fs::path &canonical) const;

    SceneDescription &scene_;
    Diagnostics &diag_;
    PbrtParseOptions opts_;
    fs::path baseCanonical_;

    Transform ctm_;
    bool applyToStart_ = true;
    GraphicsState gs_;
    std::vector<Frame> frames_;
    std::vector<UndoEntry> undo_;
    std::unordered_map<std::string, int> namedMaterials_, floatTextures_, spectrumTextures_;
    std::unordered_map<std::string, Transform> namedCoordSys_;
    std::unordered_map<std::string, int> objectIndex_;
    std::optional<ObjectDesc> currentObject_;
    std::unordered_map<std::string, RGB> spdCache_;

    bool inWorld_ = false, worldEnded_ = false, warnedMotion_ = false;
    int shapeCount_ = 0;
    std::vector<fs::path> includeCanonical_;  // files being parsed, outermost first
    std::vector<std::string> includeNames_;
};

void PbrtParser::ParseTopLevel(std::string text, const std::string &filename) {
    scene_.format = "pbrt";
    scene_.sourceFile = filename;
    scene_.baseDir = fs::path(filename).parent_path().string();
    baseCanonical_ = CanonicalOrNormal(scene_.baseDir.empty() ? fs::path(".")
                                                              : fs::path(scene_.baseDir));
    ParseFile(std::move(text), filename, CanonicalOrNormal(filename));
    if (currentObject_) {
        diag_.Warn(currentObject_->loc, "ObjectBegin without matching ObjectEnd");
        objectIndex_[currentObject_->name] = int(scene_.objects.size());
        scene_.objects.push_back(std::move(*currentObject_));
        currentObject_.reset();
    }
    if (!worldEnded_) WarnUnclosedFrames();
}

void PbrtParser::WarnUnclosedFrames() {
    for (const Frame &f : frames_)
        if (f.kind != FrameKind::Object)
            diag_.Warn(f.loc, std::string(FrameName(f.kind)) + " without matching " +
                                  (f.kind == FrameKind::Attribute ? "AttributeEnd"
                                                                  : "TransformEnd"));
}

void PbrtParser::ParseFile(std::string text, const std::string &displayName,
                           const fs::path &canonical) {
    includeCanonical_.push_back(canonical);
    includeNames_.push_back(displayName);
    Tokenizer tok(std::move(text), displayName);
    while (true) {
        Token t = tok.Next();
        if (t.kind == TokenKind::End) break;
        if (t.kind == TokenKind::Word) {
            ParseDirective(tok, t);
        } else if (t.kind == TokenKind::String) {
            throw SceneError(t.Loc(), "unexpected string " + Quoted(t.text));
        } else {
            throw SceneError(t.Loc(), "unexpected token " + Quoted(t.text));
        }
    }
    includeCanonical_.pop_back();
    includeNames_.pop_back();
}

std::vector<double> PbrtParser::ReadNumbers(Tokenizer &tok, const Token &dir, size_t count) {
    std::vector<double> v;
    v.reserve(count);
    if (tok.Peek().kind == TokenKind::LBracket) {
        Token open = tok.Next();
        while (true) {
            Token t = tok.Next();
            if (t.kind == TokenKind::RBracket) break;
            if (t.kind == TokenKind::End)
                throw SceneError(open.Loc(), "missing \"]\" for " + std::string(dir.text));
            if (t.kind != TokenKind::Number)
                throw SceneError(t.Loc(), std::string(dir.text) + " expects numbers, got " +
                                              Tokenizer::Describe(t));
            v.push_back(t.number);
        }
    } else {
        while (tok.Peek().kind == TokenKind::Number) v.push_back(tok.Next().number);
    }
    if (v.size() != count)
        throw SceneError(dir.Loc(), std::string(dir.text) + " expects " + std::to_string(count) +
                                        (count == 1 ? " number" : " numbers") + ", got " +
                                        std::to_string(v.size()));
    return v;
}

std::string PbrtParser::ReadString(Tokenizer &tok, const Token &dir, const char *what) {
    const Token &t = tok.Peek();
    if (t.kind != TokenKind::String)
        throw SceneError(dir.Loc(), std::string(dir.text) + " expects a quoted " + what +
                                        ", got " + Tokenizer::Describe(t));
    return Tokenizer::StringValue(tok.Next());
}

ParamSet PbrtParser::ReadParams(Tokenizer &tok) {
    ParamSet ps;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    while (tok.Peek().kind == TokenKind::String) {
        Token decl = tok.Next();
        std::string declText = Tokenizer::StringValue(decl);
        // "type name", separated by any whitespace.
        std::string_view s = declText;
        auto skipSpace = [&](size_t i) {
            while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
            return i;
        };
        auto skipWord = [&](size_t i) {
            while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
            return i;
        };
        size_t t0 = skipSpace(0), t1 = skipWord(t0), n0 = skipSpace(t1), n1 = skipWord(n0);
        if (t0 == t1 || n0 == n1 || skipSpace(n1) != s.size())
            throw SceneError(decl.Loc(), "invalid parameter declaration " + Quoted(declText) +
                                             " (expected \"type name\")");
        std::string_view type = s.substr(t0, t1 - t0), name = s.substr(n0, n1 - n0);

        numbers.clear();
        strings.clear();
        ReadParamValues(tok, decl, name, &numbers, &strings);

        Param p;
        p.name = std::string(name);
        p.loc = decl.Loc();
        p.spelledType = std::string(type);
        ConvertParam(p, type, numbers, strings);
        ps.Add(std::move(p));
    }
    return ps;
}

void PbrtParser::ReadParamValues(Tokenizer &tok, const Token &decl, std::string_view name,
                                 std::vector<double> *numbers,
                                 std::vector<std::string> *strings) {
    auto take = [&](const Token &t) {
        if (t.kind == TokenKind::Number) {
            numbers->push_back(t.number);
        } else if (t.kind == TokenKind::String) {
            strings->push_back(Tokenizer::StringValue(t));
        } else if (t.kind == TokenKind::Word && (t.text == "true" || t.text == "false")) {
            strings->emplace_back(t.text);  // bare bools, tolerated
        } else {
            return false;
        }
        return true;
    };
    const Token &first = tok.Peek();
    if (first.kind == TokenKind::LBracket) {
        Token open = tok.Next();
        while (true) {
            Token t = tok.Next();
            if (t.kind == TokenKind::RBracket) break;
            if (t.kind == TokenKind::End)
                throw SceneError(open.Loc(), "missing \"]\" for parameter " + Quoted(name));
            if (!take(t))
                throw SceneError(t.Loc(), "unexpected token " + Quoted(t.text) +
                                              " in the values of parameter " + Quoted(name));
        }
    } else if (first.kind == TokenKind::Number || first.kind == TokenKind::String ||
               (first.kind == TokenKind::Word && (first.text == "true" || first.text == "false"))) {
        take(tok.Next());
    } else {
        throw SceneError(decl.Loc(), "parameter " + Quoted(name) + " has no value");
    }
    if (!numbers->empty() && !strings->empty())
        throw SceneError(decl.Loc(),
                         "parameter " + Quoted(name) + ": cannot mix numbers and strings");
}

void PbrtParser::ConvertParam(Param &p, std::string_view type, std::vector<double> &numbers,
                              std::vector<std::string> &strings) {
    const std::string qname = Quoted(p.name);
    auto needNumbers = [&] {
        if (!strings.empty())
            throw SceneError(p.loc, "parameter " + qname + ": expected numbers, got strings");
    };
    auto needStrings = [&] {
        if (!numbers.empty())
            throw SceneError(p.loc, "parameter " + qname + ": expected strings, got numbers");
    };
    auto needMultiple = [&](size_t k) {
        if (numbers.size() % k != 0)
            throw SceneError(p.loc, "parameter " + qname + ": expected a multiple of " +
                                        std::to_string(k) + " values, got " +
                                        std::to_string(numbers.size()));
    };
    auto numeric = [&](ParamType t, size_t multiple) {
        needNumbers();
        needMultiple(multiple);
        p.type = t;
        p.numbers = numbers;
    };

    if (type == "float") {
        numeric(ParamType::Float, 1);
    } else if (type == "integer") {
        numeric(ParamType::Integer, 1);
        for (double v : p.numbers) {
            if (v != std::floor(v) || v < double(INT_MIN) || v > double(INT_MAX)) {
                char buf[64];
                std::snprintf(buf, sizeof(buf), "%g", v);
                throw SceneError(p.loc, "parameter " + qname + ": expected integers, got " + buf);
            }
        }
    } else if (type == "point2") {
        numeric(ParamType::Point2, 2);
    } else if (type == "vector2") {
        numeric(ParamType::Vector2, 2);
    } else if (type == "point" || type == "point3") {
        numeric(ParamType::Point3, 3);
    } else if (type == "vector" || type == "vector3") {
        numeric(ParamType::Vector3, 3);
    } else if (type == "normal" || type == "normal3") {
        numeric(ParamType::Normal, 3);
    } else if (type == "rgb" || type == "color") {
        numeric(ParamType::RGB, 3);
    } else if (type == "xyz") {
        numeric(ParamType::RGB, 3);
        for (size_t i = 0; i < p.numbers.size(); i += 3) {
            RGB c = XYZToRGB(p.numbers[i], p.numbers[i + 1], p.numbers[i + 2]);
            for (int k = 0; k < 3; ++k) p.numbers[i + k] = c[k];
        }
    } else if (type == "blackbody") {
        needNumbers();
        p.type = ParamType::RGB;
        // v3 writes [T scale] pairs; v4 a single temperature (normalized, scale 1).
        if (numbers.size() == 1) numbers.push_back(1.0);
        needMultiple(2);
        for (size_t i = 0; i < numbers.size(); i += 2) {
            if (!(numbers[i] > 0))
                throw SceneError(p.loc, "parameter " + qname +
                                            ": blackbody temperature must be positive");
            RGB c = BlackbodyToRGB(numbers[i], numbers[i + 1]);
            p.numbers.insert(p.numbers.end(), {c.r, c.g, c.b});
        }
    } else if (type == "spectrum") {
        p.type = ParamType::RGB;
        RGB c;
        if (!strings.empty()) {
            if (strings.size() != 1)
                throw SceneError(p.loc, "parameter " + qname +
                                            ": expected one spectrum file name, got " +
                                            std::to_string(strings.size()));
            c = SpectrumFile(strings[0], p.loc);
        } else {
            if (numbers.size() < 2)
                throw SceneError(p.loc, "parameter " + qname +
                                            ": expected (wavelength, value) pairs");
            needMultiple(2);
            std::vector<std::pair<double, double>> samples(numbers.size() / 2);
            for (size_t i = 0; i < samples.size(); ++i)
                samples[i] = {numbers[2 * i], numbers[2 * i + 1]};
            c = SampledToRGB(std::move(samples));
        }
        p.numbers = {c.r, c.g, c.b};
    } else if (type == "bool") {
        needStrings();
        p.type = ParamType::Bool;
        for (const std::string &s : strings) {
            if (s == "true") p.bools.push_back(true);
            else if (s == "false") p.bools.push_back(false);
            else
                throw SceneError(p.loc, "parameter " + qname +
                                            ": expected \"true\" or \"false\", got " + Quoted(s));
        }
    } else if (type == "string") {
        needStrings();
        p.type = ParamType::String;
        p.strings = strings;
    } else if (type == "texture") {
        needStrings();
        p.type = ParamType::Texture;
        p.strings = strings;
    } else {
        throw SceneError(p.loc, "unknown parameter type " + Quoted(type));
    }
}

RGB PbrtParser::SpectrumFile(const std::string &name, const FileLoc &loc) {
    fs::path path = ResolvePath(name);
    auto cached = spdCache_.find(path.string());
    if (cached != spdCache_.end()) return cached->second;
    RGB result(1.f);
    std::string text, why;
    if (opts_.confineIncludes && !InsideBaseDir(CanonicalOrNormal(path))) {
        diag_.Warn(loc, "spectrum file " + Quoted(name) +
                            " is outside the scene directory; using a constant 1");
    } else if (!ReadWholeFile(path.string(), &text, &why)) {
        diag_.Warn(loc, "cannot open spectrum file " + Quoted(name) + ": " + why +
                            "; using a constant 1");
    } else {
        // Whitespace-separated (wavelength, value) pairs with '#' comments.
        std::vector<double> values;
        bool ok = true;
        size_t i = 0;
        while (i < text.size() && ok) {
            char c = text[i];
            if (c == '#') {
                while (i < text.size() && text[i] != '\n') ++i;
            } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
                ++i;
            } else {
                const char *first = text.data() + i, *last = text.data() + text.size();
                if (*first == '+') ++first;
                double v;
                auto [ptr, ec] = std::from_chars(first, last, v);
                if (ec != std::errc() || !std::isfinite(v)) ok = false;
                else values.push_back(v);
                i = size_t(ptr - text.data());
            }
        }
        if (!ok || values.size() < 2 || values.size() % 2 != 0) {
            diag_.Warn(loc, "cannot read spectrum file " + Quoted(name) +
                                ": expected (wavelength, value) pairs; using a constant 1");
        } else {
            std::vector<std::pair<double, double>> samples(values.size() / 2);
            for (size_t k = 0; k < samples.size(); ++k)
                samples[k] = {values[2 * k], values[2 * k + 1]};
            result = SampledToRGB(std::move(samples));
        }
    }
    spdCache_[path.string()] = result;
    return result;
}

fs::path PbrtParser::ResolvePath(const std::string &name) const {
    fs::path p(name);
    if (p.is_absolute() || scene_.baseDir.empty()) return p;
    return fs::path(scene_.baseDir) / p;
}

bool PbrtParser::InsideBaseDir(const fs::path &canonical) const {
    fs::path rel = canonical.lexically_relative(baseCanonical_);
    return !rel.empty() && *rel.begin() != "..";
}

void PbrtParser::ApplyTransform(const Transform &t, bool replace) {
    // With ActiveTransform EndTime only the (unused) end transform would change.
    if (!applyToStart_) return;
    ctm_ = replace ? t : ctm_ * t;
}

std::unordered_map<std::string, int> &PbrtParser::Names(Namespace ns) {
    switch (ns) {
    case Namespace::Material: return namedMaterials_;
    case Namespace::FloatTexture: return floatTextures_;
    case Namespace::SpectrumTexture: return spectrumTextures_;
    }
    return namedMaterials_;
}

void PbrtParser::DefineNamed(Namespace ns, const std::string &name, int index) {
    auto &map = Names(ns);
    auto it = map.find(name);
    std::optional<int> previous;
    if (it != map.end()) previous = it->second;
    // Only scoped definitions need undoing; top-level ones live to the end of the file.
    if (!frames_.empty()) undo_.push_back({ns, name, previous});
    map[name] = index;
}

void PbrtParser::PushFrame(FrameKind kind, const FileLoc &loc) {
    frames_.push_back({kind, loc, ctm_, applyToStart_, gs_, undo_.size()});
}

void PbrtParser::PopFrame(FrameKind kind, const Token &dir) {
    if (frames_.empty() || frames_.back().kind != kind) {
        if (frames_.empty())
            throw SceneError(dir.Loc(), std::string(dir.text) + " without matching " +
                                            FrameName(kind));
        const Frame &top = frames_.back();
        throw SceneError(dir.Loc(), std::string(dir.text) + " does not match " +
                                        FrameName(top.kind) + " at " + top.loc.ToString());
    }
    Frame f = std::move(frames_.back());
    frames_.pop_back();
    ctm_ = f.ctm;
    applyToStart_ = f.applyToStart;
    if (kind == FrameKind::Transform) return;
    gs_ = f.gs;
    while (undo_.size() > f.undoMark) {
        UndoEntry &u = undo_.back();
        auto &map = Names(u.ns);
        if (u.previous) map[u.name] = *u.previous;
        else map.erase(u.name);
        undo_.pop_back();
    }
}

void PbrtParser::CheckWorld(const Token &dir) {
    if (!inWorld_)
        diag_.Warn(dir.Loc(), std::string(dir.text) + " before WorldBegin");
}

void PbrtParser::Include(const Token &dir, const std::string &name) {
    fs::path path = ResolvePath(name);
    fs::path canonical = CanonicalOrNormal(path);
    std::string display = path.string();
    for (size_t i = 0; i < includeCanonical_.size(); ++i) {
        if (includeCanonical_[i] != canonical) continue;
        std::string chain;
        for (size_t j = i; j < includeNames_.size(); ++j) chain += includeNames_[j] + " -> ";
        throw SceneError(dir.Loc(), "include cycle: " + chain + display);
    }
    if (int(includeCanonical_.size()) > opts_.maxIncludeDepth)
        throw SceneError(dir.Loc(), "includes nested deeper than " +
                                        std::to_string(opts_.maxIncludeDepth) + " levels");
    if (opts_.confineIncludes && !InsideBaseDir(canonical))
        throw SceneError(dir.Loc(), "included file " + Quoted(name) +
                                        " is outside the scene directory");
    std::string text, why;
    if (!ReadWholeFile(display, &text, &why))
        throw SceneError(dir.Loc(), "cannot open file " + Quoted(display) + ": " + why);
    ParseFile(std::move(text), display, canonical);
}

// Small helpers shared by the directive handlers.
SceneEntity PbrtParser::ReadEntity(Tokenizer &tok, const Token &dir, const char *what) {
    SceneEntity e;
    e.type = ReadString(tok, dir, what);
    e.params = ReadParams(tok);
    e.loc = dir.Loc();
    return e;
}

void PbrtParser::ParseDirective(Tokenizer &tok, const Token &dir) {
    auto it = DirectiveTable().find(dir.text);
    if (it == DirectiveTable().end())
        throw SceneError(dir.Loc(), "unknown directive " + Quoted(dir.text));
    if (worldEnded_)
        throw SceneError(dir.Loc(), std::string(dir.text) + " after WorldEnd");
    Directive d = it->second;
    if (d <= Directive::ReverseOrientation) ParseTransformDirective(tok, dir, d);
    else if (d <= Directive::Accelerator) ParseOptionDirective(tok, dir, d);
    else ParseWorldDirective(tok, dir, d);
}

// Transforms and the attribute/transform scopes.
void PbrtParser::ParseTransformDirective(Tokenizer &tok, const Token &dir, Directive d) {
    const FileLoc loc = dir.Loc();
    auto transformOrThrow = [&](auto &&make) -> Transform {
        try {
            return make();
        } catch (const std::invalid_argument &e) {
            throw SceneError(loc, std::string(dir.text) + ": " + e.what());
        }
    };
    auto warnMotion = [&]() {
        if (!warnedMotion_)
            diag_.Warn(loc, "motion blur is not supported; using the start transform");
        warnedMotion_ = true;
    };
    switch (d) {
    case Directive::AttributeBegin:
        PushFrame(FrameKind::Attribute, loc);
        break;
    case Directive::AttributeEnd:
        PopFrame(FrameKind::Attribute, dir);
        break;
    case Directive::TransformBegin:
        PushFrame(FrameKind::Transform, loc);
        break;
    case Directive::TransformEnd:
        PopFrame(FrameKind::Transform, dir);
        break;
    case Directive::Translate: {
        auto v = ReadNumbers(tok, dir, 3);
        ApplyTransform(prism::Translate({v[0], v[1], v[2]}), false);
        break;
    }
    case Directive::Scale: {
        auto v = ReadNumbers(tok, dir, 3);
        ApplyTransform(transformOrThrow([&] { return prism::Scale(v[0], v[1], v[2]); }), false);
        break;
    }
    case Directive::Rotate: {
        auto v = ReadNumbers(tok, dir, 4);
        if (v[1] == 0 && v[2] == 0 && v[3] == 0)
            throw SceneError(loc, "Rotate axis must not be zero");
        ApplyTransform(prism::Rotate(v[0], {v[1], v[2], v[3]}), false);
        break;
    }
    case Directive::LookAt: {
        auto v = ReadNumbers(tok, dir, 9);
        ApplyTransform(transformOrThrow([&] {
                           return prism::LookAt({v[0], v[1], v[2]}, {v[3], v[4], v[5]},
                                                {v[6], v[7], v[8]});
                       }),
                       false);
        break;
    }
    case Directive::Transform:
    case Directive::ConcatTransform: {
        auto v = ReadNumbers(tok, dir, 16);
        ApplyTransform(transformOrThrow([&] { return FromPbrtMatrix(v.data()); }),
                       d == Directive::Transform);
        break;
    }
    case Directive::Identity:
        ApplyTransform(prism::Transform(), true);
        break;
    case Directive::CoordinateSystem:
        namedCoordSys_[ReadString(tok, dir, "name")] = ctm_;
        break;
    case Directive::CoordSysTransform: {
        std::string name = ReadString(tok, dir, "name");
        auto cs = namedCoordSys_.find(name);
        if (cs == namedCoordSys_.end())
            throw SceneError(loc, "unknown coordinate system " + Quoted(name));
        ApplyTransform(cs->second, true);
        break;
    }
    case Directive::ActiveTransform: {
        Token t = tok.Next();
        if (t.kind != TokenKind::Word ||
            (t.text != "StartTime" && t.text != "EndTime" && t.text != "All"))
            throw SceneError(loc, "ActiveTransform expects StartTime, EndTime or All, got " +
                                      Tokenizer::Describe(t));
        applyToStart_ = t.text != "EndTime";
        warnMotion();
        break;
    }
    case Directive::TransformTimes:
        ReadNumbers(tok, dir, 2);
        warnMotion();
        break;
    case Directive::ReverseOrientation:
        gs_.reverseOrientation = !gs_.reverseOrientation;
        break;
    default:
        break;
    }
}

// Options-block directives (before WorldBegin).
void PbrtParser::ParseOptionDirective(Tokenizer &tok, const Token &dir, Directive d) {
    const FileLoc loc = dir.Loc();
    SceneEntity e = ReadEntity(tok, dir, d == Directive::Camera ? "camera type" : "type");
    if (inWorld_) {
        diag_.Warn(loc, std::string(dir.text) + " inside the world block is ignored");
        return;
    }
    switch (d) {
    case Directive::Camera: {
        CameraDesc &cam = scene_.camera;
        static_cast<SceneEntity &>(cam) = std::move(e);
        cam.cameraFromWorld = ctm_;
        cam.specified = true;
        // As pbrt-v3 pbrtCamera: "camera" names the camera-to-world frame.
        namedCoordSys_["camera"] = ctm_.Inverse();
        break;
    }
    case Directive::Film: scene_.film = std::move(e); break;
    case Directive::Sampler: scene_.sampler = std::move(e); break;
    case Directive::PixelFilter: scene_.filter = std::move(e); break;
    case Directive::Integrator: scene_.integrator = std::move(e); break;
    default: break;  // Accelerator: Embree builds its own BVH
    }
}

// World-block directives: materials, textures, lights, shapes, objects and includes.
void PbrtParser::ParseWorldDirective(Tokenizer &tok, const Token &dir, Directive d) {
    const FileLoc loc = dir.Loc();
    auto entity = [&](const char *what) { return ReadEntity(tok, dir, what); };
    switch (d) {
    case Directive::WorldBegin:
        if (inWorld_) throw SceneError(loc, "WorldBegin inside the world block");
        inWorld_ = true;
        applyToStart_ = true;
        ctm_ = prism::Transform();
        namedCoordSys_["world"] = ctm_;
        break;
    case Directive::WorldEnd:
        WarnUnclosedFrames();
        worldEnded_ = true;
        break;
    case Directive::Include:
    case Directive::Import:
        Include(dir, ReadString(tok, dir, "file name"));
        break;
    case Directive::Material: {
        CheckWorld(dir);
        MaterialDesc m;
        static_cast<SceneEntity &>(m) = entity("material type");
        gs_.material = int(scene_.materials.size());
        scene_.materials.push_back(std::move(m));
        break;
    }
    case Directive::MakeNamedMaterial: {
        CheckWorld(dir);
        MaterialDesc m;
        m.name = ReadString(tok, dir, "material name");
        m.params = ReadParams(tok);
        m.loc = loc;
        const Param *type = m.params.Find("type");
        if (!type || type->type != ParamType::String || type->strings.size() != 1)
            throw SceneError(loc, "MakeNamedMaterial " + Quoted(m.name) +
                                      " needs a \"string type\" parameter");
        m.type = type->strings[0];
        m.params.MarkUsed("type");
        if (namedMaterials_.count(m.name))
            diag_.Warn(loc, "named material " + Quoted(m.name) + " redefined");
        DefineNamed(Namespace::Material, m.name, int(scene_.materials.size()));
        scene_.materials.push_back(std::move(m));
        break;
    }
    case Directive::NamedMaterial: {
        std::string name = ReadString(tok, dir, "material name");
        auto nm = namedMaterials_.find(name);
        if (nm == namedMaterials_.end())
            throw SceneError(loc, "unknown named material " + Quoted(name));
        gs_.material = nm->second;
        break;
    }
    case Directive::Texture: {
        CheckWorld(dir);
        TextureDesc t;
        t.name = ReadString(tok, dir, "texture name");
        std::string kind = ReadString(tok, dir, "texture type (\"float\" or \"spectrum\")");
        if (kind == "float") t.isFloat = true;
        else if (kind != "spectrum" && kind != "color" && kind != "rgb")
            throw SceneError(loc, "texture " + Quoted(t.name) + ": unknown texture type " +
                                      Quoted(kind) + " (expected \"float\" or \"spectrum\")");
        t.type = ReadString(tok, dir, "texture class");
        t.params = ReadParams(tok);
        t.loc = loc;
        t.worldFromTexture = ctm_;
        Namespace ns = t.isFloat ? Namespace::FloatTexture : Namespace::SpectrumTexture;
        if (Names(ns).count(t.name))
            diag_.Warn(loc, "texture " + Quoted(t.name) + " redefined");
        DefineNamed(ns, t.name, int(scene_.textures.size()));
        scene_.textures.push_back(std::move(t));
        break;
    }
    case Directive::LightSource: {
        CheckWorld(dir);
        LightDesc l;
        static_cast<SceneEntity &>(l) = entity("light type");
        l.worldFromLight = ctm_;
        scene_.lights.push_back(std::move(l));
        break;
    }
    case Directive::AreaLightSource: {
        CheckWorld(dir);
        AreaLightDesc a;
        static_cast<SceneEntity &>(a) = entity("area light type");
        gs_.areaLight = int(scene_.areaLights.size());
        scene_.areaLights.push_back(std::move(a));
        break;
    }
    case Directive::Shape: {
        CheckWorld(dir);
        ShapeDesc s;
        static_cast<SceneEntity &>(s) = entity("shape type");
        s.worldFromObject = ctm_;
        s.reverseOrientation = gs_.reverseOrientation;
        s.material = gs_.material;
        s.areaLight = gs_.areaLight;
        if (currentObject_) {
            s.directiveIndex = int(currentObject_->shapes.size());
            currentObject_->shapes.push_back(std::move(s));
        } else {
            s.directiveIndex = shapeCount_++;
            scene_.shapes.push_back(std::move(s));
        }
        break;
    }
    case Directive::ObjectBegin: {
        CheckWorld(dir);
        std::string name = ReadString(tok, dir, "object name");
        if (currentObject_)
            throw SceneError(loc, "ObjectBegin inside ObjectBegin " +
                                      Quoted(currentObject_->name) + " (started at " +
                                      currentObject_->loc.ToString() + ")");
        if (objectIndex_.count(name))
            throw SceneError(loc, "object " + Quoted(name) + " redefined");
        // pbrt-v3 pbrtObjectBegin also begins an attribute scope.
        PushFrame(FrameKind::Object, loc);
        currentObject_ = ObjectDesc{name, loc, {}};
        break;
    }
    case Directive::ObjectEnd:
        if (!currentObject_) throw SceneError(loc, "ObjectEnd without matching ObjectBegin");
        PopFrame(FrameKind::Object, dir);
        objectIndex_[currentObject_->name] = int(scene_.objects.size());
        scene_.objects.push_back(std::move(*currentObject_));
        currentObject_.reset();
        break;
    case Directive::ObjectInstance: {
        CheckWorld(dir);
        std::string name = ReadString(tok, dir, "object name");
        if (currentObject_)
            throw SceneError(loc, "ObjectInstance inside ObjectBegin " +
                                      Quoted(currentObject_->name));
        if (!objectIndex_.count(name))
            throw SceneError(loc, "unknown object " + Quoted(name));
        scene_.instances.push_back({name, ctm_, loc});
        break;
    }
    case Directive::MakeNamedMedium:
        ReadString(tok, dir, "medium name");
        ReadParams(tok);
        diag_.Warn(loc, "participating media are not supported");
        break;
    case Directive::MediumInterface:
        ReadString(tok, dir, "medium name");
        if (tok.Peek().kind == TokenKind::String) tok.Next();
        diag_.Warn(loc, "participating media are not supported");
        break;
    case Directive::Option: {
        ParamSet ps = ReadParams(tok);
        for (const Param &p : ps.Params())
            diag_.Warn(p.loc, "Option " + Quoted(p.name) + " is not supported; ignored");
        break;
    }
    case Directive::ColorSpace:
        ReadString(tok, dir, "color space name");
        diag_.Warn(loc, "ColorSpace is not supported; using sRGB");
        break;
    case Directive::Attribute:
        ReadString(tok, dir, "attribute target");
        ReadParams(tok);
        diag_.Warn(loc, "Attribute is not supported; ignored");
        break;
    default:
        break;
    }
}

}  // namespace

SceneDescription ParsePbrtString(const std::string &text, const std::string &filename,
                                 Diagnostics &diag, const PbrtParseOptions &opts) {
    SceneDescription scene;
    PbrtParser parser(scene, diag, opts);
    parser.ParseTopLevel(text, filename);
    return scene;
}

SceneDescription ParsePbrtFile(const std::string &path, Diagnostics &diag,
                               const PbrtParseOptions &opts) {
    std::string text, why;
    if (!ReadWholeFile(path, &text, &why))
        throw SceneError(FileLoc{path, 0, 0}, "cannot open file " + Quoted(path) + ": " + why);
    SceneDescription scene;
    PbrtParser parser(scene, diag, opts);
    parser.ParseTopLevel(std::move(text), path);
    return scene;
}

}  // namespace prism
