// Helpers for the non-pbrt readers (OBJ, glTF, PLY): build typed pbrt parameters in code, as
// if they had been written in a .pbrt file, so the renderer reads every format the same way.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/vecmath.h"
#include "scene/paramset.h"

namespace prism::reader {

inline Param MakeParam(ParamType type, const std::string &name, const FileLoc &loc) {
    Param p;
    p.type = type;
    p.name = name;
    p.loc = loc;
    p.spelledType = ParamTypeName(type);
    return p;
}

inline void AddFloat(ParamSet &ps, const std::string &name, double v, const FileLoc &loc) {
    Param p = MakeParam(ParamType::Float, name, loc);
    p.numbers = {v};
    ps.Add(std::move(p));
}

inline void AddBool(ParamSet &ps, const std::string &name, bool v, const FileLoc &loc) {
    Param p = MakeParam(ParamType::Bool, name, loc);
    p.bools = {v};
    ps.Add(std::move(p));
}

inline void AddRGB(ParamSet &ps, const std::string &name, double r, double g, double b,
                   const FileLoc &loc) {
    Param p = MakeParam(ParamType::RGB, name, loc);
    p.numbers = {r, g, b};
    ps.Add(std::move(p));
}

inline void AddString(ParamSet &ps, const std::string &name, const std::string &v,
                      const FileLoc &loc) {
    Param p = MakeParam(ParamType::String, name, loc);
    p.strings = {v};
    ps.Add(std::move(p));
}

inline void AddTexture(ParamSet &ps, const std::string &name, const std::string &tex,
                       const FileLoc &loc) {
    Param p = MakeParam(ParamType::Texture, name, loc);
    p.strings = {tex};
    ps.Add(std::move(p));
}

inline void AddPoint3(ParamSet &ps, const std::string &name, const Vec3d &v, const FileLoc &loc) {
    Param p = MakeParam(ParamType::Point3, name, loc);
    p.numbers = {v.x, v.y, v.z};
    ps.Add(std::move(p));
}

inline void AddInts(ParamSet &ps, const std::string &name, const std::vector<int> &v,
                    const FileLoc &loc) {
    Param p = MakeParam(ParamType::Integer, name, loc);
    p.numbers.assign(v.begin(), v.end());
    ps.Add(std::move(p));
}

inline void AddFloats(ParamSet &ps, const std::string &name, const std::vector<double> &v,
                      const FileLoc &loc) {
    Param p = MakeParam(ParamType::Float, name, loc);
    p.numbers.assign(v.begin(), v.end());
    ps.Add(std::move(p));
}

// Point3 / Normal arrays (3 numbers per element).
inline void AddVec3s(ParamSet &ps, ParamType type, const std::string &name,
                     const std::vector<Vec3f> &v, const FileLoc &loc) {
    Param p = MakeParam(type, name, loc);
    p.numbers.reserve(v.size() * 3);
    for (const Vec3f &x : v) p.numbers.insert(p.numbers.end(), {x.x, x.y, x.z});
    ps.Add(std::move(p));
}

inline void AddPoint2s(ParamSet &ps, const std::string &name, const std::vector<Vec2f> &v,
                       const FileLoc &loc) {
    Param p = MakeParam(ParamType::Point2, name, loc);
    p.numbers.reserve(v.size() * 2);
    for (const Vec2f &x : v) p.numbers.insert(p.numbers.end(), {x.x, x.y});
    ps.Add(std::move(p));
}

// A "trianglemesh" parameter list: indices, P, and N / uv when non-empty.
inline ParamSet TriangleMeshParams(const std::vector<int> &indices, const std::vector<Vec3f> &P,
                                   const std::vector<Vec3f> &N, const std::vector<Vec2f> &uv,
                                   const FileLoc &loc) {
    ParamSet ps;
    AddInts(ps, "indices", indices, loc);
    AddVec3s(ps, ParamType::Point3, "P", P, loc);
    if (!N.empty()) AddVec3s(ps, ParamType::Normal, "N", N, loc);
    if (!uv.empty()) AddPoint2s(ps, "uv", uv, loc);
    return ps;
}

// The loader libraries (tinyobjloader, tinygltf) report several messages in one
// newline-separated string: one trimmed, non-empty line per message.
inline std::vector<std::string> MessageLines(const std::string &s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty()) out.push_back(line);
    }
    return out;
}

}  // namespace prism::reader
