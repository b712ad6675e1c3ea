// Helpers of the render tests that build scenes from pbrt text and render them.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "assembly/build_scene.h"
#include "core/error.h"
#include "image/image.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "test_util.h"

namespace prism::test {

// The scene of pbrt text `text`, written to `name`.pbrt in the scratch folder `dir` (a folder
// per test file: ctest runs test files in parallel).
inline RenderScene BuildSceneText(const std::string &dir, const std::string &name,
                                  const std::string &text, const BuildSettings &opts = {}) {
    const std::string file = WriteTestFile(ScratchDir(dir) / (name + ".pbrt"), text);
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(file, diag);
    return BuildRenderScene(desc, opts, diag);
}

// The scene rendered with its sampler at pattern seed `seed` (0: a plain render's).
inline Image RenderWithSeed(const RenderScene &scene, uint32_t seed) {
    RenderOptions o;
    o.sampler = scene.sampler;
    o.sampler.seed = seed;
    RenderStats stats;
    return Render(scene, o, &stats);
}

// The mean of every channel of every pixel.
inline double MeanValue(const Image &img) {
    double s = 0;
    for (float v : img.pixels) s += v;
    return s / double(img.pixels.size());
}

// Mean |a - b| over mean |b| (all channels).
inline double RelL1(const Image &a, const Image &b) {
    double d = 0, m = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        d += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
        m += std::abs(double(b.pixels[i]));
    }
    return d / m;
}

}  // namespace prism::test
