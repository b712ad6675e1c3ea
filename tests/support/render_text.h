// Scenes from text, built and rendered as `prism render` would, for the render tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "assembly/build_scene.h"
#include "core/error.h"
#include "image/image.h"
#include "render/renderer.h"

namespace prism::test {

struct Rendered {
    RenderScene scene;  // as built
    Image image;
    RenderStats stats;
    std::vector<Warning> warnings;  // what loading and building the scene warned of
};

struct Built {
    RenderScene scene;
    std::vector<Warning> warnings;  // what loading and building the scene warned of
};

// The scene file `path`, loaded and built with `opts`.
Built BuildSceneFile(const std::string &path, const BuildSettings &opts = {});

// The scene file `path`, loaded, built with `opts` and rendered with its own sampler.
Rendered RenderSceneFile(const std::string &path, const BuildSettings &opts = {});

// Scene text `text` written as `name` (".pbrt" appended when `name` has no extension) in the
// scratch folder `dir` (a folder per test file), then loaded and built / rendered.
std::string WriteSceneText(const std::string &dir, const std::string &name,
                           const std::string &text);
RenderScene BuildSceneText(const std::string &dir, const std::string &name, const std::string &text,
                           const BuildSettings &opts = {});
Rendered RenderSceneText(const std::string &dir, const std::string &name, const std::string &text,
                         const BuildSettings &opts = {});

// The material of a sphere declared after `world` (a pbrt world block's text: Material,
// MakeNamedMaterial, Texture ...) under a point light, built at 8x8 into `keep`, with what it
// warned of in `diag`. Throws SceneError as the scene builder does.
const Material &BuildSphereMaterial(const std::string &world, Diagnostics &diag, RenderScene &keep);

// Material `type` with each one of `bad` (parameter text) must be a SceneError at that
// material's parameter line (BuildSphereMaterial's test.pbrt:4) whose message says `fragment`.
void ExpectMaterialErrors(const std::string &type, const std::vector<std::string> &bad,
                          const std::string &fragment);

// A sphere of radius 0.8 declared after `material` (a Material line) at the origin, seen from
// 4 away, under a 2 × 2 quad light of radiance 10 two above it and, when sky > 0, a constant
// sky of that radiance: 32 × 32 pixels at `spp` samples of pbrt-v3's "random" sampler, path
// traced to maxdepth 8. The material tests compare its means with pbrt-v3's renders of the
// same text.
std::string LitSphereScene(const std::string &material, int spp, float sky = 0);

// Build settings of a w x h image at `spp` samples a pixel (0: the file's) with integrator
// `integrator` ("": the file's).
BuildSettings SizedSettings(int w, int h, int spp, const std::string &integrator = "");

// The scene rendered with its sampler at pattern seed `seed` (0: a plain render's); its
// counters go to `stats` when given.
Image RenderWithSeed(const RenderScene &scene, uint32_t seed, RenderStats *stats = nullptr);

// The scene rendered on a TBB arena of `threads` threads.
Image RenderOnThreads(const RenderScene &scene, int threads);

}  // namespace prism::test
