// Reader for pbrt-v3 scene files (plus the common pbrt-v4 spellings): tracks the graphics
// state and transforms of the directive stream and records plain SceneDescription data.
// Entity type names are not validated here; the renderer does that with the stored locations.
#pragma once

#include <string>

#include "core/error.h"
#include "scene/scene_description.h"

namespace prism {

struct PbrtParseOptions {
    int maxIncludeDepth = 32;
    // When set, an Include/Import (or .spd spectrum file) that resolves outside the directory
    // of the top-level file is rejected; for fuzzing and untrusted input.
    bool confineIncludes = false;
};

// Parses the scene file at `path`. Relative paths inside it (Include, .spd files) resolve
// against its directory, which is stored in SceneDescription::baseDir. Throws SceneError.
SceneDescription ParsePbrtFile(const std::string &path, Diagnostics &diag,
                               const PbrtParseOptions &opts = {});

// Parses `text` as if it were the contents of `filename` (which names locations and gives the
// base directory for includes; the file itself is not read).
SceneDescription ParsePbrtString(const std::string &text, const std::string &filename,
                                 Diagnostics &diag, const PbrtParseOptions &opts = {});

}  // namespace prism
