// The app side of AOVs (render/aov.h): which AOVs a render writes (--aov or Film "aovs"), and
// the multi-channel EXR with their id manifests.
#pragma once

#include <memory>
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
// not an EXR). Direct and indirect need an integrator whose direct part is exact (every one
// but "distribution": IntegratorTraits::directAov): named explicitly otherwise they are a
// UsageError, from "all" they are left out with a warning.
std::vector<Aov> ChooseAovs(const std::string &aovOption, const RenderScene &scene,
                            const std::string &out, Diagnostics &diag);

class ShapeLookup;

// A render's AOVs as the app sets them up before the render: the frame the render fills
// (render/aov.h), with the ids of the scene's declarations and their manifests.
class AovOutput {
  public:
    AovOutput(const SceneDescription &desc, const RenderScene &scene, const std::vector<Aov> &aovs);
    ~AovOutput();
    AovFrame &Frame() { return *frame_; }
    // Writes `beauty` (already exposed; `scale` = 2^EV of the exposure, applied to the radiance
    // layers too) with the AOVs into the EXR `out`.
    void Write(const std::string &out, const Image &beauty, float scale) const;

  private:
    std::unique_ptr<ShapeLookup> lookup_;
    size_t materials_, instances_;
    std::unique_ptr<AovFrame> frame_;
};

}  // namespace prism
