// pbrt syntax: directives and their positional arguments, parameter lists and Include.
#include "scene/pbrt_parser.h"

#include <cctype>
#include <unordered_map>

#include "core/file_io.h"
#include "core/memory.h"
#include "scene/scene_builder.h"
#include "scene/tokenizer.h"

namespace prism {

namespace {

enum class Directive {
    AttributeBegin,
    AttributeEnd,
    TransformBegin,
    TransformEnd,
    Translate,
    Scale,
    Rotate,
    LookAt,
    Transform,
    ConcatTransform,
    Identity,
    CoordinateSystem,
    CoordSysTransform,
    ActiveTransform,
    TransformTimes,
    ReverseOrientation,
    Camera,
    Film,
    Sampler,
    PixelFilter,
    Integrator,
    Accelerator,
    WorldBegin,
    WorldEnd,
    Include,
    Import,
    Material,
    MakeNamedMaterial,
    NamedMaterial,
    Texture,
    LightSource,
    AreaLightSource,
    Shape,
    ObjectBegin,
    ObjectEnd,
    ObjectInstance,
    MakeNamedMedium,
    MediumInterface,
    Option,
    ColorSpace,
    Attribute,
    CSGBegin,
    CSGEnd
};

const std::unordered_map<std::string_view, Directive> &DirectiveTable() {
    static const std::unordered_map<std::string_view, Directive> table = {
        {"AttributeBegin", Directive::AttributeBegin},
        {"AttributeEnd", Directive::AttributeEnd},
        {"TransformBegin", Directive::TransformBegin},
        {"TransformEnd", Directive::TransformEnd},
        {"Translate", Directive::Translate},
        {"Scale", Directive::Scale},
        {"Rotate", Directive::Rotate},
        {"LookAt", Directive::LookAt},
        {"Transform", Directive::Transform},
        {"ConcatTransform", Directive::ConcatTransform},
        {"Identity", Directive::Identity},
        {"CoordinateSystem", Directive::CoordinateSystem},
        {"CoordSysTransform", Directive::CoordSysTransform},
        {"ActiveTransform", Directive::ActiveTransform},
        {"TransformTimes", Directive::TransformTimes},
        {"ReverseOrientation", Directive::ReverseOrientation},
        {"Camera", Directive::Camera},
        {"Film", Directive::Film},
        {"Sampler", Directive::Sampler},
        {"PixelFilter", Directive::PixelFilter},
        {"Integrator", Directive::Integrator},
        {"Accelerator", Directive::Accelerator},
        {"WorldBegin", Directive::WorldBegin},
        {"WorldEnd", Directive::WorldEnd},
        {"Include", Directive::Include},
        {"Import", Directive::Import},
        {"Material", Directive::Material},
        {"MakeNamedMaterial", Directive::MakeNamedMaterial},
        {"NamedMaterial", Directive::NamedMaterial},
        {"Texture", Directive::Texture},
        {"LightSource", Directive::LightSource},
        {"AreaLightSource", Directive::AreaLightSource},
        {"Shape", Directive::Shape},
        {"ObjectBegin", Directive::ObjectBegin},
        {"ObjectEnd", Directive::ObjectEnd},
        {"ObjectInstance", Directive::ObjectInstance},
        {"MakeNamedMedium", Directive::MakeNamedMedium},
        {"MediumInterface", Directive::MediumInterface},
        {"Option", Directive::Option},
        {"ColorSpace", Directive::ColorSpace},
        {"Attribute", Directive::Attribute},
        {"CSGBegin", Directive::CSGBegin},  // Prism extension (docs/FORMAT.md)
        {"CSGEnd", Directive::CSGEnd},
    };
    return table;
}

bool IsBoolWord(const Token &t) {
    return t.kind == TokenKind::Word && (t.text == "true" || t.text == "false");
}

class PbrtParser {
  public:
    PbrtParser(PbrtTarget &target, const PbrtParseOptions &opts, const std::string &filename)
        : target_(target), opts_(opts), baseDir_(DirectoryOf(filename)) {}

    void ParseFile(std::string text, const std::string &displayName, const std::string &canonical);

  private:
    void ParseDirective(Tokenizer &tok, const Token &dir);
    void Include(const Token &dir, const std::string &name);

    // Positional arguments and parameter lists.
    std::vector<double> ReadNumbers(Tokenizer &tok, const Token &dir, size_t count);
    std::string ReadString(Tokenizer &tok, const Token &dir, const char *what);
    ParsedParameterVector ReadParams(Tokenizer &tok);
    void ReadParamValues(Tokenizer &tok, const Token &decl, ParsedParameter &p);

    PbrtTarget &target_;
    PbrtParseOptions opts_;
    std::string baseDir_;
    bool worldEnded_ = false;
    std::vector<std::string> includeCanonical_;  // files being parsed, outermost first
    std::vector<std::string> includeNames_;
};

void PbrtParser::ParseFile(std::string text, const std::string &displayName,
                           const std::string &canonical) {
    includeCanonical_.push_back(canonical);
    includeNames_.push_back(displayName);
    Tokenizer tok(std::move(text), displayName);
    while (true) {
        Token t = tok.Next();
        if (t.kind == TokenKind::End) break;
        if (t.kind == TokenKind::Word) {
            ParseDirective(tok, t);
        } else if (t.kind == TokenKind::String) {
            throw SceneError(t.Loc(), "unexpected string " + Quote(t.text));
        } else {
            throw SceneError(t.Loc(), "unexpected token " + Quote(t.text));
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
        throw SceneError(dir.Loc(), std::string(dir.text) + " expects a quoted " + what + ", got " +
                                        Tokenizer::Describe(t));
    return Tokenizer::StringValue(tok.Next());
}

ParsedParameterVector PbrtParser::ReadParams(Tokenizer &tok) {
    ParsedParameterVector params;
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
            throw SceneError(decl.Loc(), "invalid parameter declaration " + Quote(declText) +
                                             " (expected \"type name\")");
        ParsedParameter p;
        p.type = std::string(s.substr(t0, t1 - t0));
        p.name = std::string(s.substr(n0, n1 - n0));
        p.loc = decl.Loc();
        ReadParamValues(tok, decl, p);
        params.push_back(std::move(p));
    }
    return params;
}

void PbrtParser::ReadParamValues(Tokenizer &tok, const Token &decl, ParsedParameter &p) {
    auto take = [&](const Token &t) {
        if (t.kind == TokenKind::Number) {
            p.numbers.push_back(t.number);
        } else if (t.kind == TokenKind::String) {
            p.strings.push_back(Tokenizer::StringValue(t));
        } else if (IsBoolWord(t)) {
            p.strings.emplace_back(t.text);  // bare bools, tolerated
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
                throw SceneError(open.Loc(), "missing \"]\" for parameter " + Quote(p.name));
            if (!take(t))
                throw SceneError(t.Loc(), "unexpected token " + Quote(t.text) +
                                              " in the values of parameter " + Quote(p.name));
        }
    } else if (first.kind == TokenKind::Number || first.kind == TokenKind::String ||
               IsBoolWord(first)) {
        take(tok.Next());
    } else {
        throw SceneError(decl.Loc(), "parameter " + Quote(p.name) + " has no value");
    }
    if (!p.numbers.empty() && !p.strings.empty())
        throw SceneError(decl.Loc(),
                         "parameter " + Quote(p.name) + ": cannot mix numbers and strings");
}

void PbrtParser::Include(const Token &dir, const std::string &name) {
    std::string path = ResolveScenePath(baseDir_, name);
    std::string canonical = CanonicalPath(path);
    for (size_t i = 0; i < includeCanonical_.size(); ++i) {
        if (includeCanonical_[i] != canonical) continue;
        std::string chain;
        for (size_t j = i; j < includeNames_.size(); ++j) chain += includeNames_[j] + " -> ";
        throw SceneError(dir.Loc(), "include cycle: " + chain + path);
    }
    if (int(includeCanonical_.size()) > opts_.maxIncludeDepth)
        throw SceneError(dir.Loc(), "includes nested deeper than " +
                                        std::to_string(opts_.maxIncludeDepth) + " levels");
    if (opts_.confineIncludes && !IsInsideDirectory(canonical, baseDir_))
        throw SceneError(dir.Loc(),
                         "included file " + Quote(name) + " is outside the scene directory");
    // Refused under --confine with the name as the scene wrote it, not where it resolves.
    CheckReadConfinement(path, dir.Loc(), "included file", name);
    std::string text = opts_.budget ? ReadFileOrThrow(path, dir.Loc(), *opts_.budget,
                                                      "included file " + Quote(name))
                                    : ReadFileOrThrow(path, dir.Loc());
    ParseFile(std::move(text), path, canonical);
}

void PbrtParser::ParseDirective(Tokenizer &tok, const Token &dir) {
    auto it = DirectiveTable().find(dir.text);
    if (it == DirectiveTable().end())
        throw SceneError(dir.Loc(), "unknown directive " + Quote(dir.text));
    if (worldEnded_) throw SceneError(dir.Loc(), std::string(dir.text) + " after WorldEnd");
    const FileLoc loc = dir.Loc();
    PbrtTarget &t = target_;
    auto str = [&](const char *what) { return ReadString(tok, dir, what); };
    auto params = [&] { return ReadParams(tok); };
    switch (it->second) {
        case Directive::AttributeBegin:
            t.AttributeBegin(loc);
            break;
        case Directive::AttributeEnd:
            t.AttributeEnd(loc);
            break;
        case Directive::TransformBegin:
            t.TransformBegin(loc);
            break;
        case Directive::TransformEnd:
            t.TransformEnd(loc);
            break;
        case Directive::Translate: {
            auto v = ReadNumbers(tok, dir, 3);
            t.Translate(v[0], v[1], v[2], loc);
            break;
        }
        case Directive::Scale: {
            auto v = ReadNumbers(tok, dir, 3);
            t.Scale(v[0], v[1], v[2], loc);
            break;
        }
        case Directive::Rotate: {
            auto v = ReadNumbers(tok, dir, 4);
            t.Rotate(v[0], v[1], v[2], v[3], loc);
            break;
        }
        case Directive::LookAt: {
            auto v = ReadNumbers(tok, dir, 9);
            t.LookAt(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], loc);
            break;
        }
        case Directive::Transform:
            t.Transform(ReadNumbers(tok, dir, 16).data(), loc);
            break;
        case Directive::ConcatTransform:
            t.ConcatTransform(ReadNumbers(tok, dir, 16).data(), loc);
            break;
        case Directive::Identity:
            t.Identity(loc);
            break;
        case Directive::CoordinateSystem:
            t.CoordinateSystem(str("name"), loc);
            break;
        case Directive::CoordSysTransform:
            t.CoordSysTransform(str("name"), loc);
            break;
        case Directive::ActiveTransform: {
            Token w = tok.Next();
            if (w.Is(TokenKind::Word, "StartTime"))
                t.ActiveTransform(ActiveTransformKind::StartTime, loc);
            else if (w.Is(TokenKind::Word, "EndTime"))
                t.ActiveTransform(ActiveTransformKind::EndTime, loc);
            else if (w.Is(TokenKind::Word, "All"))
                t.ActiveTransform(ActiveTransformKind::All, loc);
            else
                throw SceneError(loc, "ActiveTransform expects StartTime, EndTime or All, got " +
                                          Tokenizer::Describe(w));
            break;
        }
        case Directive::TransformTimes: {
            auto v = ReadNumbers(tok, dir, 2);
            t.TransformTimes(v[0], v[1], loc);
            break;
        }
        case Directive::ReverseOrientation:
            t.ReverseOrientation(loc);
            break;
        case Directive::Camera: {
            std::string type = str("camera type");
            t.Camera(type, params(), loc);
            break;
        }
        case Directive::Film: {
            std::string type = str("type");
            t.Film(type, params(), loc);
            break;
        }
        case Directive::Sampler: {
            std::string type = str("type");
            t.Sampler(type, params(), loc);
            break;
        }
        case Directive::PixelFilter: {
            std::string type = str("type");
            t.PixelFilter(type, params(), loc);
            break;
        }
        case Directive::Integrator: {
            std::string type = str("type");
            t.Integrator(type, params(), loc);
            break;
        }
        case Directive::Accelerator: {
            std::string type = str("type");
            t.Accelerator(type, params(), loc);
            break;
        }
        case Directive::WorldBegin:
            t.WorldBegin(loc);
            break;
        case Directive::WorldEnd:
            t.WorldEnd(loc);
            worldEnded_ = true;
            break;
        case Directive::Include:
            Include(dir, str("file name"));
            break;
        case Directive::Import: {
            std::string file = str("file name");
            t.Import(file, loc);
            Include(dir, file);
            break;
        }
        case Directive::Material: {
            std::string type = str("material type");
            t.Material(type, params(), loc);
            break;
        }
        case Directive::MakeNamedMaterial: {
            std::string name = str("material name");
            t.MakeNamedMaterial(name, params(), loc);
            break;
        }
        case Directive::NamedMaterial:
            t.NamedMaterial(str("material name"), loc);
            break;
        case Directive::Texture: {
            std::string name = str("texture name");
            std::string kind = str("texture type (\"float\" or \"spectrum\")");
            std::string type = str("texture class");
            t.Texture(name, kind, type, params(), loc);
            break;
        }
        case Directive::LightSource: {
            std::string type = str("light type");
            t.LightSource(type, params(), loc);
            break;
        }
        case Directive::AreaLightSource: {
            std::string type = str("area light type");
            t.AreaLightSource(type, params(), loc);
            break;
        }
        case Directive::Shape: {
            std::string type = str("shape type");
            t.Shape(type, params(), loc);
            break;
        }
        case Directive::ObjectBegin:
            t.ObjectBegin(str("object name"), loc);
            break;
        case Directive::ObjectEnd:
            t.ObjectEnd(loc);
            break;
        case Directive::ObjectInstance:
            t.ObjectInstance(str("object name"), loc);
            break;
        case Directive::MakeNamedMedium: {
            std::string name = str("medium name");
            t.MakeNamedMedium(name, params(), loc);
            break;
        }
        case Directive::MediumInterface: {
            // pbrt-v3: one name is both the inside and the outside medium.
            std::string inside = str("medium name"), outside = inside;
            if (tok.Peek().kind == TokenKind::String) outside = Tokenizer::StringValue(tok.Next());
            t.MediumInterface(inside, outside, loc);
            break;
        }
        case Directive::Option:
            t.Option(params(), loc);
            break;
        case Directive::ColorSpace:
            t.ColorSpace(str("color space name"), loc);
            break;
        case Directive::Attribute: {
            std::string target = str("attribute target");
            t.Attribute(target, params(), loc);
            break;
        }
        case Directive::CSGBegin:
            t.CSGBegin(str("CSG operation (\"union\", \"intersection\" or \"difference\")"), loc);
            break;
        case Directive::CSGEnd:
            t.CSGEnd(loc);
            break;
    }
}

}  // namespace

void ParsePbrt(std::string text, const std::string &filename, PbrtTarget &target,
               const PbrtParseOptions &opts) {
    PbrtParser parser(target, opts, filename);
    parser.ParseFile(std::move(text), filename, CanonicalPath(filename));
    target.EndOfFiles();
}

SceneDescription ParsePbrtString(const std::string &text, const std::string &filename,
                                 Diagnostics &diag, const PbrtParseOptions &opts) {
    SceneBuilder builder(filename, diag, opts);
    ParsePbrt(text, filename, builder, opts);
    return builder.Result();
}

SceneDescription ParsePbrtFile(const std::string &path, Diagnostics &diag,
                               const PbrtParseOptions &opts) {
    FileLoc loc{path, 0, 0};
    std::string text = opts.budget ? ReadFileOrThrow(path, loc, *opts.budget, "scene file")
                                   : ReadFileOrThrow(path, loc);
    SceneBuilder builder(path, diag, opts);
    ParsePbrt(std::move(text), path, builder, opts);
    return builder.Result();
}

}  // namespace prism
