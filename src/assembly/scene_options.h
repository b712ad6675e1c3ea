// pbrt-v4's Option directive: the options that change the image are honoured, the others
// are named in a warning with why (SceneDescription::options).
#pragma once

#include <cstdint>

#include "assembly/build_scene.h"

namespace prism {

struct SceneOptions {
    uint32_t seed = 0;                     // "seed": every sampler's seed
    bool disablePixelJitter = false;       // "disablepixeljitter": pixel centres
    bool disableTextureFiltering = false;  // "disabletexturefiltering": point lookups
};

// Reads the description's options (marking them read) and warns of those without an effect,
// each at its location; SceneError for a bad value.
SceneOptions ReadSceneOptions(const SceneDescription &desc, Diagnostics &diag);

}  // namespace prism
