#include "scene/paramset.h"

#include <climits>
#include <cmath>

namespace prism {

const char *ParamTypeName(ParamType t) {
    switch (t) {
    case ParamType::Float: return "float";
    case ParamType::Integer: return "integer";
    case ParamType::Bool: return "bool";
    case ParamType::String: return "string";
    case ParamType::Point2: return "point2";
    case ParamType::Vector2: return "vector2";
    case ParamType::Point3: return "point3";
    case ParamType::Vector3: return "vector3";
    case ParamType::Normal: return "normal";
    case ParamType::RGB: return "rgb";
    case ParamType::Texture: return "texture";
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
    throw SceneError(p->loc, "parameter \"" + name + "\" must be " + want + ", not " +
                                 WrittenType(*p));
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
        throw SceneError(p->loc, "parameter \"" + name + "\" must have an even number of "
                                 "values, got " + std::to_string(p->numbers.size()));
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

std::vector<std::string> ParamSet::GetStrings(const std::string &name) const {
    const Param *p = FindTyped(name, {ParamType::String}, "string");
    if (!p) return {};
    return p->strings;
}

void ParamSet::MarkUsed(const std::string &name) const {
    if (const Param *p = Find(name)) p->lookedUp = true;
}

void ParamSet::ReportUnused(Diagnostics &diag, const std::string &context) const {
    for (const Param &p : params_) {
        if (p.lookedUp) continue;
        std::string msg = "unused parameter \"" + p.name + "\"";
        if (!context.empty()) msg += " (" + context + ")";
        diag.Warn(p.loc, msg);
    }
}

}  // namespace prism
