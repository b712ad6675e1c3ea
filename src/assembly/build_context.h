// What the build steps share: their inputs, the RenderScene they fill, and the tables one
// step leaves for the next (textures for materials; decoded images for textures and lights).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "assembly/build_scene.h"
#include "assembly/scene_options.h"
#include "core/animated_transform.h"
#include "image/image.h"
#include "render/texture.h"
#include "scene/paramset.h"

namespace prism {

struct BuildContext {
    const SceneDescription &desc;
    const BuildSettings &settings;
    Diagnostics &diag;
    RenderScene &scene;
    MemoryBudget &budget;  // settings.budget, or the build's own
    std::map<std::string, TexturePtr> floatTextures, rgbTextures;    // by texture name
    std::map<std::string, std::shared_ptr<const Image>> imageCache;  // by path and encoding
    // MIP pyramids of those images for filtered lookups, by image and wrap mode.
    std::map<std::pair<const Image *, TextureWrap>, std::shared_ptr<const MIPMap>> mipCache;
    // The camera's shutter (pbrt-v3 "shutteropen"/"shutterclose", default 0 1; BuildCamera):
    // motion is sampled over it, rays carrying their time as a fraction of it (Ray::time).
    double shutterOpen = 0, shutterClose = 1;
    // pbrt-v4's Option directives that change the image (ReadSceneOptions).
    SceneOptions options;
    // The subsurface materials whose interface-only rendering has been warned of.
    std::set<const void *> subsurfaceWarned;
};

// A directive's render-space transform at the shutter's opening (*atOpen) and, when it moves
// while the shutter is open, its motion with times as fractions of the shutter (the form
// Accel and the shapes take). `renderFromWorld` is applied to both keyframes; a transform
// that cannot be decomposed is an error at `loc`. (Null renderFromWorld: the identity, for
// shapes of a prototype, which live in instance space.)
std::optional<AnimatedTransform> ShutterMotion(const BuildContext &ctx,
                                               const Transform *renderFromWorld,
                                               const Transform &worldFromX,
                                               const std::optional<TransformMotion> &motion,
                                               const FileLoc &loc, Transform *atOpen);

// pbrt-v3 reads "scale" as a spectrum; v4 files write a float. Accept both.
inline RGB ScaleParam(const ParamSet &ps) {
    const Param *p = ps.Find("scale");
    if (p && p->type == ParamType::Float) return RGB(ps.GetFloat("scale", 1.f));
    return ps.GetRGB("scale", RGB(1));
}

// Base of the steps' private builder classes: the context under short names, so each step
// reads like pbrt-v4's *::Create functions.
struct BuildStep {
    explicit BuildStep(BuildContext &c)
        : ctx(c),
          desc(c.desc),
          settings(c.settings),
          diag(c.diag),
          scene(c.scene),
          budget(c.budget) {}
    BuildContext &ctx;
    const SceneDescription &desc;
    const BuildSettings &settings;
    Diagnostics &diag;
    RenderScene &scene;
    MemoryBudget &budget;
};

}  // namespace prism
