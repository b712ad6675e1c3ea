// Typed pbrt parameter lists ("float radius" [1]) with source locations and use tracking.
// The parser hands over parameters as written (ParsedParameter: a type name and untyped
// values); MakeParamSet checks and converts them. Spectral types (rgb/color, blackbody,
// spectrum, xyz) become linear sRGB there, so lookups only ever see RGB.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"
#include "core/color_space.h"
#include "core/error.h"
#include "core/vecmath.h"

namespace prism {

enum class ParamType {
    Float,
    Integer,
    Bool,
    String,
    Point2,
    Vector2,
    Point3,
    Vector3,
    Normal,
    RGB,
    Texture
};
const char *ParamTypeName(ParamType t);

struct Param {
    ParamType type = ParamType::Float;
    std::string name;
    std::vector<double> numbers;       // Float/Integer/Point*/Vector*/Normal/RGB (3 per RGB)
    std::vector<std::string> strings;  // String/Texture
    std::vector<bool> bools;           // Bool
    FileLoc loc;                       // location of the "type name" string
    mutable bool lookedUp = false;
    // Spelling as written in the file ("color", "point", "blackbody", ...), for messages.
    std::string spelledType;
    // An "rgb"/"color" parameter written under a ColorSpace other than sRGB: `numbers` hold
    // its values mapped to sRGB as a reflectance (SRGBFromReflectance, clipped at 0) and
    // `written` the values as written, for a light to map as an emission (EmissionRGB).
    ColorSpaceId colorSpace = ColorSpaceId::SRGB;
    std::vector<double> written;
};

// The sRGB emission of RGB parameter `p`'s value `i` (SRGBFromIlluminant of its colour
// space, clipped at 0); its plain value when written in sRGB or not as RGB.
RGB EmissionRGB(const Param &p, size_t i = 0);

class ParamSet {
  public:
    // Adds or replaces (a later parameter of the same name wins, as in pbrt).
    void Add(Param p);
    bool Has(const std::string &name) const { return Find(name) != nullptr; }
    const Param *Find(const std::string &name) const;
    const std::vector<Param> &Params() const { return params_; }

    // Single-value lookups. Absent → default. Present with the wrong type → SceneError at the
    // parameter's location ("parameter "radius" must be float, not string").
    float GetFloat(const std::string &name, float def) const;
    int GetInt(const std::string &name, int def) const;
    bool GetBool(const std::string &name, bool def) const;
    std::string GetString(const std::string &name, const std::string &def) const;
    Vec3f GetPoint3(const std::string &name, const Vec3f &def) const;
    Vec3f GetVector3(const std::string &name, const Vec3f &def) const;
    Vec3f GetNormal(const std::string &name, const Vec3f &def) const;
    RGB GetRGB(const std::string &name, const RGB &def) const;
    // Name of the texture bound by a "texture NAME" parameter, or "" if absent or if the
    // parameter has another type (material parameters may be a texture or a constant).
    std::string GetTexture(const std::string &name) const;

    // Array lookups: empty vector when absent.
    std::vector<float> GetFloats(const std::string &name) const;
    std::vector<int> GetInts(const std::string &name) const;
    std::vector<Vec2f> GetPoint2s(const std::string &name) const;
    std::vector<Vec3f> GetPoint3s(const std::string &name) const;
    std::vector<Vec3f> GetNormals(const std::string &name) const;
    std::vector<RGB> GetRGBs(const std::string &name) const;
    std::vector<std::string> GetStrings(const std::string &name) const;

    // Marks a parameter used without reading it (e.g. parameters Prism accepts and ignores).
    void MarkUsed(const std::string &name) const;
    // Marks every parameter used (an entity that is ignored as a whole).
    void MarkAllUsed() const;
    // Warns (with location) for every parameter never looked up: "unused parameter "foo"".
    void ReportUnused(Diagnostics &diag, const std::string &context) const;

  private:
    const Param *FindTyped(const std::string &name, std::initializer_list<ParamType> ok,
                           const char *want) const;
    std::vector<Param> params_;
};

// Parameters Prism accepts but does not simulate. Marks each of `names` used and warns once
// per parameter name and `context` (the first one present, at its own location), so a file
// with a thousand such textures gets one line per parameter:
//   parameter "filter" (imagemap texture) has no effect: <why>
// `why` may be empty. WarnIgnoredRest does the same for every parameter not yet looked up.
void WarnIgnored(const ParamSet &ps, std::initializer_list<const char *> names, Diagnostics &diag,
                 std::string_view context, std::string_view why = {});
void WarnIgnoredRest(const ParamSet &ps, Diagnostics &diag, std::string_view context,
                     std::string_view why = {});

// Heap bytes held by the values of `ps`: 8 per number (they are doubles), each string's
// characters plus 32, one bit per bool, plus each Param's own size. For the memory budget.
uint64_t ParamStorageBytes(const ParamSet &ps);

// A parameter as the parser read it: `"type name" values`, before the type is interpreted.
struct ParsedParameter {
    std::string type, name;            // "float", "radius"
    FileLoc loc;                       // location of the "type name" string
    std::vector<double> numbers;       // numeric values, or
    std::vector<std::string> strings;  // string values (and the bare words true / false)
};
using ParsedParameterVector = std::vector<ParsedParameter>;

// Reads a spectrum file named by a `"spectrum name" "file.spd"` parameter (the name as
// written, located at `loc`) and returns its RGB value.
using SpectrumFileReader = std::function<RGB(const std::string &name, const FileLoc &loc)>;

// Converts parsed parameters by their type names ("float", "integer", "point2", "point"/
// "point3", "vector"/"vector3", "normal"/"normal3", "rgb"/"color", "xyz", "blackbody",
// "spectrum", "bool", "string", "texture"). Throws SceneError at the parameter for an unknown
// type, values of the wrong kind or count, non-integral integers, ... A later parameter of the
// same name replaces an earlier one, as in pbrt.
// "rgb"/"color" values are read in colour space `cs` (pbrt-v4's ColorSpace; Param::colorSpace).
ParamSet MakeParamSet(ParsedParameterVector params, const SpectrumFileReader &spectrumFile,
                      ColorSpaceId cs = ColorSpaceId::SRGB);

}  // namespace prism
