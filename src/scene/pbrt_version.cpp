#include "scene/pbrt_version.h"

#include <array>

#include "scene/named_spectra.h"
#include "scene/paramset.h"

namespace prism {

namespace {

// A construct only one version of the format has. An empty `type` matches every type of the
// directive; an empty `param` means the type itself is the construct.
struct VersionRule {
    std::string_view directive, type, param;
    int version;
};

// pbrt-v3's and pbrt-v4's documentation of the format (pbrt.org/fileformat-v3 and
// /fileformat-v4) and pbrt-v4's --upgrade, which rewrites each of the pbrt-v3 rows.
constexpr std::array kRules = {
    // Film, camera, sampler, integrator.
    VersionRule{"Film", "image", "", 3},
    VersionRule{"Film", "rgb", "", 4},
    VersionRule{"Film", "gbuffer", "", 4},
    VersionRule{"Film", "spectral", "", 4},
    VersionRule{"Camera", "environment", "", 3},
    VersionRule{"Camera", "spherical", "", 4},
    VersionRule{"Sampler", "lowdiscrepancy", "", 3},
    VersionRule{"Sampler", "02sequence", "", 3},
    VersionRule{"Sampler", "random", "", 3},
    VersionRule{"Sampler", "maxmindist", "", 3},
    VersionRule{"Sampler", "zsobol", "", 4},
    VersionRule{"Sampler", "paddedsobol", "", 4},
    VersionRule{"Sampler", "pmj02bn", "", 4},
    VersionRule{"Sampler", "independent", "", 4},
    VersionRule{"Integrator", "whitted", "", 3},
    VersionRule{"Integrator", "directlighting", "", 3},
    VersionRule{"Integrator", "simplepath", "", 4},
    VersionRule{"Integrator", "simplevolpath", "", 4},
    VersionRule{"Integrator", "lightpath", "", 4},
    VersionRule{"Integrator", "randomwalk", "", 4},
    // Materials (MakeNamedMaterial's "string type" counts as its type).
    VersionRule{"Material", "matte", "", 3},
    VersionRule{"Material", "plastic", "", 3},
    VersionRule{"Material", "uber", "", 3},
    VersionRule{"Material", "substrate", "", 3},
    VersionRule{"Material", "metal", "", 3},
    VersionRule{"Material", "glass", "", 3},
    VersionRule{"Material", "mirror", "", 3},
    VersionRule{"Material", "translucent", "", 3},
    VersionRule{"Material", "fourier", "", 3},
    VersionRule{"Material", "kdsubsurface", "", 3},
    VersionRule{"Material", "disney", "", 3},
    VersionRule{"Material", "diffuse", "", 4},
    VersionRule{"Material", "coateddiffuse", "", 4},
    VersionRule{"Material", "coatedconductor", "", 4},
    VersionRule{"Material", "conductor", "", 4},
    VersionRule{"Material", "dielectric", "", 4},
    VersionRule{"Material", "thindielectric", "", 4},
    VersionRule{"Material", "diffusetransmission", "", 4},
    VersionRule{"Material", "measured", "", 4},
    VersionRule{"Material", "hair", "color", 3},
    VersionRule{"Material", "hair", "reflectance", 4},
    VersionRule{"Material", "mix", "namedmaterial1", 3},
    VersionRule{"Material", "mix", "materials", 4},
    // Shapes.
    VersionRule{"Shape", "cone", "", 3},
    VersionRule{"Shape", "paraboloid", "", 3},
    VersionRule{"Shape", "hyperboloid", "", 3},
    VersionRule{"Shape", "heightfield", "", 3},
    VersionRule{"Shape", "nurbs", "", 3},
    VersionRule{"Shape", "bilinearmesh", "", 4},
    VersionRule{"Shape", "plymesh", "displacement", 4},
    // Textures.
    VersionRule{"Texture", "uv", "", 3},
    VersionRule{"Texture", "directionmix", "", 4},
    VersionRule{"Texture", "imagemap", "gamma", 3},
    VersionRule{"Texture", "imagemap", "encoding", 4},
    VersionRule{"Texture", "scale", "tex1", 3},
    VersionRule{"Texture", "scale", "tex", 4},
    // Lights.
    VersionRule{"LightSource", "", "mapname", 3},
    VersionRule{"LightSource", "", "filename", 4},
    VersionRule{"LightSource", "", "power", 4},
    VersionRule{"LightSource", "", "illuminance", 4},
    VersionRule{"AreaLightSource", "", "power", 4},
    VersionRule{"AreaLightSource", "", "filename", 4},
    // Media.
    VersionRule{"MakeNamedMedium", "heterogeneous", "", 3},
    VersionRule{"MakeNamedMedium", "uniformgrid", "", 4},
    VersionRule{"MakeNamedMedium", "rgbgrid", "", 4},
    VersionRule{"MakeNamedMedium", "cloud", "", 4},
    VersionRule{"MakeNamedMedium", "nanovdb", "", 4},
};

std::string Describe(std::string_view directive, std::string_view type, std::string_view param) {
    std::string s(directive);
    if (!type.empty()) s += " \"" + std::string(type) + "\"";
    if (!param.empty()) s += " parameter \"" + std::string(param) + "\"";
    return s;
}

}  // namespace

void PbrtVersionDetector::Note(int version, const std::string &what, const FileLoc &loc) {
    Evidence &e = first_[version == 4 ? 1 : 0];
    ++count_;
    if (e.seen) return;
    e = {what, loc, true, count_};
}

void PbrtVersionDetector::Observe(std::string_view directive, std::string_view type,
                                  const std::vector<ParsedParameter> &params, const FileLoc &loc) {
    if (first_[0].seen && first_[1].seen) return;  // nothing more can change the choice
    const std::string_view rulesDirective =
        directive == "MakeNamedMaterial" ? "Material" : directive;
    for (const VersionRule &r : kRules) {
        if (r.directive != rulesDirective || (!r.type.empty() && r.type != type)) continue;
        if (r.param.empty()) {
            Note(r.version, Describe(directive, type, ""), loc);
            continue;
        }
        for (const ParsedParameter &p : params)
            if (p.name == r.param) Note(r.version, Describe(directive, type, r.param), p.loc);
    }
    for (const ParsedParameter &p : params) {
        // pbrt-v3 writes a blackbody as [temperature scale] pairs, pbrt-v4 as one temperature.
        if (p.type == "blackbody" && p.numbers.size() == 1)
            Note(4, "a blackbody of one value (parameter \"" + p.name + "\")", p.loc);
        else if (p.type == "blackbody" && p.numbers.size() == 2)
            Note(3, "a blackbody of two values (parameter \"" + p.name + "\")", p.loc);
        if (p.type == "spectrum" && p.strings.size() == 1 && IsNamedSpectrum(p.strings[0]))
            Note(4, "the named spectrum \"" + p.strings[0] + "\"", p.loc);
    }
}

PbrtVersionChoice PbrtVersionDetector::Choose(int forced) const {
    PbrtVersionChoice c;
    const Evidence &v3 = first_[0], &v4 = first_[1];
    if (forced == 3 || forced == 4) {
        c.version = forced;
        c.why = "--pbrt-version " + std::to_string(forced);
        return c;
    }
    if (!v3.seen && !v4.seen) {
        c.version = 3;
        c.why = "nothing in the file is only pbrt-v3's or only pbrt-v4's";
        return c;
    }
    const bool four = v4.seen && (!v3.seen || v4.order < v3.order);
    const Evidence &decided = four ? v4 : v3, &other = four ? v3 : v4;
    c.version = four ? 4 : 3;
    c.why = decided.what + " (pbrt-v" + std::to_string(c.version) + " only)";
    c.loc = decided.loc;
    if (other.seen) {
        c.conflict = other.what + " (pbrt-v" + std::to_string(four ? 3 : 4) + " only)";
        c.conflictLoc = other.loc;
    }
    return c;
}

}  // namespace prism
