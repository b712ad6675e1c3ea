// Which version of the pbrt format a file is written for. pbrt-v3 and pbrt-v4 share most of
// their syntax, but some names mean different things (a file without an Integrator renders with
// "path" in pbrt-v3 and "volpath" in pbrt-v4; a blackbody light is normalised differently; a
// spot light's falloff has another curve). Each version also has constructs the other lacks
// (pbrt-v3's Film "image" and Material "matte", pbrt-v4's Option directive and Film "rgb"): the
// first such construct decides, unless the user names the version (--pbrt-version).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace prism {

struct ParsedParameter;

// What decided a file's version: the rules applied, the construct that chose them and where.
struct PbrtVersionChoice {
    int version = 3;  // 3 or 4
    std::string why;  // "Film \"rgb\" (pbrt-v4 only)", "--pbrt-version 4", ...
    FileLoc loc;      // the construct, when a construct decided
    // The first construct of the other version, when the file mixes them (`prism info`
    // prints it; the file renders).
    std::string conflict;
    FileLoc conflictLoc;
};

// Collects the evidence of one file's version as the scene builder sees its directives.
class PbrtVersionDetector {
  public:
    // A directive ("Film", "Shape", ...) of class `type` ("" for directives without one) with
    // its parameters as written.
    void Observe(std::string_view directive, std::string_view type,
                 const std::vector<ParsedParameter> &params, const FileLoc &loc);
    // A construct only `version` has (a directive such as Import, a named spectrum, ...).
    void Note(int version, const std::string &what, const FileLoc &loc);

    // The rules to apply: `forced` (3 or 4; 0 to detect) wins; otherwise the version of the
    // first version-specific construct; pbrt-v3 for a file with none (every pbrt-v3 file is
    // such a file, and the common subset means the same in both).
    PbrtVersionChoice Choose(int forced) const;

  private:
    struct Evidence {
        std::string what;
        FileLoc loc;
        bool seen = false;
        uint64_t order = 0;
    };
    Evidence first_[2];  // pbrt-v3, pbrt-v4
    uint64_t count_ = 0;
};

}  // namespace prism
