// The app side of AOVs (render/aov.h): which AOVs a render writes (--aov or Film "aovs"), and
// the multi-channel EXR with their id manifests.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "image/image.h"
#include "render/aov.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace prism {

// --aov before any work: a valid list and, when -o is given, an .exr output (UsageError).
void CheckAovOption(const std::string &aovOption, const std::string &output);
// The AOVs to write to `out`: --aov's, else the Film's (dropped with a warning when `out` is
// not an EXR). Direct and indirect need Integrator "whitted": named explicitly under
// "distribution" they are a UsageError, from "all" they are left out with a warning.
std::vector<Aov> ChooseAovs(const std::string &aovOption, const RenderScene &scene,
                            const std::string &out, Diagnostics &diag);
// Renders the AOVs and writes `beauty` (already exposed; `scale` = 2^EV of the exposure, applied
// to the radiance layers too) with them into the EXR `out`.
void WriteAovExr(const std::string &out, const Image &beauty, float scale, const RenderScene &scene,
                 const SceneDescription &desc, const std::vector<Aov> &aovs);

}  // namespace prism
