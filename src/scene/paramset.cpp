#include "scene/paramset.h"

#include <climits>
#include <cmath>
#include <cstdio>

#include "scene/spectrum.h"

namespace prism {

const char *ParamTypeName(ParamType t) {
    switch (t) {
        case ParamType::Float:
            return "float";
        case ParamType::Integer:
            return "integer";
        case ParamType::Bool:
            return "bool";
        case ParamType::String:
            return "string";
        case ParamType::Point2:
            return "point2";
        case ParamType::Vector2:
            return "vector2";
        case ParamType::Point3:
            return "point3";
        case ParamType::Vector3:
            return "vector3";
        case ParamType::Normal:
            return "normal";
        case ParamType::RGB:
            return "rgb";
        case ParamType::Texture:
            return "texture";
    }
    return "unknown";
}

// The spelling the user wrote ("color", "blackbody") is what they will search their file for.
static std::string WrittenType(const Param &p) {
    return p.spelledType.empty() ? std::string(ParamTypeName(p.type)) : p.spelledType;
}

void ParamSet::Add(Param p) {
    for (Param &existing : params_) {
        if (existing.name == p.name) {
            existing = std::move(p);
            return;
        }
    }
    params_.push_back(std::move(p));
}

const Param *ParamSet::Find(const std::string &name) const {
    for (const Param &p : params_)
        if (p.name == name) return &p;
    return nullptr;
}

const Param *ParamSet::FindTyped(const std::string &name, std::initializer_list<ParamType> ok,
                                 const char *want) const {
    const Param *p = Find(name);
    if (!p) return nullptr;
    for (ParamType t : ok) {
        if (p->type == t) {
            p->lookedUp = true;
            return p;
        }
    }
    throw SceneError(p->loc,
                     "parameter " + Quote(name) + " must be " + want + ", not " + WrittenType(*p));
}

// The parser rejects non-integral and out-of-range integers; this guard only keeps a
// programmatically built ParamSet from invoking undefined float→int conversion.
static int ToInt(double v) {
    if (!(v >= double(INT_MIN) && v <= double(INT_MAX))) return v > 0 ? INT_MAX : INT_MIN;
    return int(v);
}

float ParamSet::GetFloat(const std::string &name, float def) const {
    const Param *p = FindTyped(name, {ParamType::Float, ParamType::Integer}, "float");
    if (!p || p->numbers.empty()) return def;
    return float(p->numbers[0]);
}

int ParamSet::GetInt(const std::string &name, int def) const {
    const Param *p = FindTyped(name, {ParamType::Integer}, "integer");
    if (!p || p->numbers.empty()) return def;
    return ToInt(p->numbers[0]);
}

bool ParamSet::GetBool(const std::string &name, bool def) const {
    const Param *p = FindTyped(name, {ParamType::Bool}, "bool");
    if (!p || p->bools.empty()) return def;
    return p->bools[0];
}

std::string ParamSet::GetString(const std::string &name, const std::string &def) const {
    const Param *p = FindTyped(name, {ParamType::String}, "string");
    if (!p || p->strings.empty()) return def;
    return p->strings[0];
}

static Vec3f First3(const Param *p, const Vec3f &def) {
    if (!p || p->numbers.size() < 3) return def;
    return {float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
}

Vec3f ParamSet::GetPoint3(const std::string &name, const Vec3f &def) const {
    return First3(FindTyped(name, {ParamType::Point3}, "point3"), def);
}

Vec3f ParamSet::GetVector3(const std::string &name, const Vec3f &def) const {
    return First3(FindTyped(name, {ParamType::Vector3}, "vector3"), def);
}

Vec3f ParamSet::GetNormal(const std::string &name, const Vec3f &def) const {
    return First3(FindTyped(name, {ParamType::Normal}, "normal"), def);
}

RGB ParamSet::GetRGB(const std::string &name, const RGB &def) const {
    const Param *p = FindTyped(name, {ParamType::RGB}, "rgb");
    if (!p || p->numbers.size() < 3) return def;
    return {float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
}

std::string ParamSet::GetTexture(const std::string &name) const {
    // A non-texture parameter of this name is not an error here: material parameters such as
    // "Kd" may be either a texture or a constant, and callers try the texture form first.
    const Param *p = Find(name);
    if (!p || p->type != ParamType::Texture || p->strings.empty()) return "";
    p->lookedUp = true;
    return p->strings[0];
}

std::vector<float> ParamSet::GetFloats(const std::string &name) const {
    const Param *p = FindTyped(name, {ParamType::Float, ParamType::Integer}, "float");
    if (!p) return {};
    std::vector<float> out(p->numbers.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = float(p->numbers[i]);
    return out;
}

std::vector<int> ParamSet::GetInts(const std::string &name) const {
    const Param *p = FindTyped(name, {ParamType::Integer}, "integer");
    if (!p) return {};
    std::vector<int> out(p->numbers.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = ToInt(p->numbers[i]);
    return out;
}

std::vector<Vec2f> ParamSet::GetPoint2s(const std::string &name) const {
    // pbrt-v3 scenes write texture coordinates as "float uv"/"float st" flat arrays.
    const Param *p = FindTyped(name, {ParamType::Point2, ParamType::Float}, "point2");
    if (!p) return {};
    if (p->numbers.size() % 2 != 0)
        throw SceneError(p->loc, "parameter " + Quote(name) +
                                     " must have an even number of "
                                     "values, got " +
                                     std::to_string(p->numbers.size()));
    std::vector<Vec2f> out(p->numbers.size() / 2);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = {float(p->numbers[2 * i]), float(p->numbers[2 * i + 1])};
    return out;
}

static std::vector<Vec3f> Triples(const Param *p) {
    if (!p) return {};
    std::vector<Vec3f> out(p->numbers.size() / 3);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = {float(p->numbers[3 * i]), float(p->numbers[3 * i + 1]),
                  float(p->numbers[3 * i + 2])};
    return out;
}

std::vector<Vec3f> ParamSet::GetPoint3s(const std::string &name) const {
    return Triples(FindTyped(name, {ParamType::Point3}, "point3"));
}

std::vector<Vec3f> ParamSet::GetNormals(const std::string &name) const {
    return Triples(FindTyped(name, {ParamType::Normal}, "normal"));
}

std::vector<RGB> ParamSet::GetRGBs(const std::string &name) const {
    std::vector<RGB> out;
    for (const Vec3f &v : Triples(FindTyped(name, {ParamType::RGB}, "rgb")))
        out.emplace_back(v.x, v.y, v.z);
    return out;
}

std::vector<std::string> ParamSet::GetStrings(const std::string &name) const {
    const Param *p = FindTyped(name, {ParamType::String}, "string");
    if (!p) return {};
    return p->strings;
}

void ParamSet::MarkUsed(const std::string &name) const {
    if (const Param *p = Find(name)) p->lookedUp = true;
}

void ParamSet::MarkAllUsed() const {
    for (const Param &p : params_) p.lookedUp = true;
}

void ParamSet::ReportUnused(Diagnostics &diag, const std::string &context) const {
    for (const Param &p : params_) {
        if (p.lookedUp) continue;
        std::string msg = "unused parameter " + Quote(p.name);
        if (!context.empty()) msg += " (" + context + ")";
        diag.Warn(p.loc, msg);
    }
}

static void WarnIgnoredParam(const Param &p, Diagnostics &diag, std::string_view context,
                             std::string_view why) {
    p.lookedUp = true;
    std::string msg =
        "parameter " + Quote(p.name) + " (" + std::string(context) + ") has no effect";
    if (!why.empty()) msg += ": " + std::string(why);
    diag.WarnOnce("ignored parameter:" + std::string(context) + ":" + p.name, p.loc, msg);
}

void WarnIgnored(const ParamSet &ps, std::initializer_list<const char *> names, Diagnostics &diag,
                 std::string_view context, std::string_view why) {
    for (const char *n : names)
        if (const Param *p = ps.Find(n)) WarnIgnoredParam(*p, diag, context, why);
}

void WarnIgnoredRest(const ParamSet &ps, Diagnostics &diag, std::string_view context,
                     std::string_view why) {
    for (const Param &p : ps.Params())
        if (!p.lookedUp) WarnIgnoredParam(p, diag, context, why);
}

uint64_t ParamStorageBytes(const ParamSet &ps) {
    uint64_t bytes = 0;
    for (const Param &p : ps.Params()) {
        bytes += sizeof(Param) + p.name.size() +
                 (p.numbers.size() + p.written.size()) * sizeof(double) + (p.bools.size() + 7) / 8;
        for (const std::string &s : p.strings) bytes += sizeof(std::string) + s.size();
    }
    return bytes;
}

RGB EmissionRGB(const Param &p, size_t i) {
    if (p.colorSpace == ColorSpaceId::SRGB || p.written.size() < 3 * i + 3)
        return RGB(float(p.numbers.at(3 * i)), float(p.numbers.at(3 * i + 1)),
                   float(p.numbers.at(3 * i + 2)));
    const RGB w(float(p.written[3 * i]), float(p.written[3 * i + 1]), float(p.written[3 * i + 2]));
    return MapClipped(SRGBFromIlluminant(p.colorSpace), w);
}

static Param ConvertParameter(ParsedParameter &in, const SpectrumFileReader &spectrumFile,
                              ColorSpaceId cs) {
    Param p;
    p.name = std::move(in.name);
    p.loc = std::move(in.loc);
    p.spelledType = std::move(in.type);
    const std::string &type = p.spelledType;
    std::vector<double> &numbers = in.numbers;
    std::vector<std::string> &strings = in.strings;
    const std::string qname = Quote(p.name);
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
        p.numbers = std::move(numbers);
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
        if (cs != ColorSpaceId::SRGB) {
            p.colorSpace = cs;
            p.written = p.numbers;
            const ColorMatrix m = SRGBFromReflectance(cs);
            for (size_t i = 0; i < p.numbers.size(); i += 3) {
                const RGB c = MapClipped(
                    m, RGB(float(p.numbers[i]), float(p.numbers[i + 1]), float(p.numbers[i + 2])));
                for (int k = 0; k < 3; ++k) p.numbers[i + size_t(k)] = c[k];
            }
        }
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
                throw SceneError(p.loc,
                                 "parameter " + qname + ": blackbody temperature must be positive");
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
            c = spectrumFile(strings[0], p.loc);
        } else {
            if (numbers.size() < 2)
                throw SceneError(p.loc,
                                 "parameter " + qname + ": expected (wavelength, value) pairs");
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
            if (s == "true")
                p.bools.push_back(true);
            else if (s == "false")
                p.bools.push_back(false);
            else
                throw SceneError(p.loc, "parameter " + qname +
                                            ": expected \"true\" or \"false\", got " + Quote(s));
        }
    } else if (type == "string") {
        needStrings();
        p.type = ParamType::String;
        p.strings = std::move(strings);
    } else if (type == "texture") {
        needStrings();
        p.type = ParamType::Texture;
        p.strings = std::move(strings);
    } else {
        throw SceneError(p.loc, "unknown parameter type " + Quote(type));
    }
    return p;
}

ParamSet MakeParamSet(ParsedParameterVector params, const SpectrumFileReader &spectrumFile,
                      ColorSpaceId cs) {
    ParamSet ps;
    for (ParsedParameter &pp : params) ps.Add(ConvertParameter(pp, spectrumFile, cs));
    return ps;
}

}  // namespace prism
