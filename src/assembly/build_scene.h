// BuildRenderScene: SceneDescription (plain data, scene/) → RenderScene (runtime objects,
// render/). The settings are plain values; the command line that fills them lives in app/.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/memory.h"
#include "core/transform.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace prism {

// Limits on what a scene (or a setting) may ask for; larger values are bad input.
inline constexpr int MaxImageResolution = 1 << 16;  // per axis
inline constexpr int MaxSamplesPerPixel = 1 << 16;
inline constexpr int MaxTraceDepth = 1000;

// Replaces the geometry of an analytic shape (e.g. by its tessellated twin, validate/); returns
// nullptr to keep the analytic shape. Calls `charge` with the mesh's size before allocating it
// (the builder charges it to the render's budget as the shape). May throw std::length_error
// when too large.
using ShapeReplacement =
    std::function<std::unique_ptr<TriangleMesh>(const AnalyticShape &, const MeshCharge &charge)>;

// The sample count the description's Sampler asks for (pbrt-v3's defaults: 16, "random" 4,
// "stratified" xsamples x ysamples), before BuildSettings::spp replaces it; unchecked.
int SceneSamplesPerPixel(const SceneDescription &desc);

// The Sampler types Prism reads (pbrt-v3's and pbrt-v4's), for --sampler.
std::vector<std::string> SamplerNames();

struct BuildSettings {
    // Replacements for what the description says; the default keeps the description's value.
    int spp = 0;                               // 0: the Sampler's
    Vec2i resolution{0, 0};                    // 0: the Film's
    int maxDepth = -1;                         // -1: the Integrator's
    std::optional<std::array<float, 4>> crop;  // NDC x0 x1 y0 y1, like Film "cropwindow"
    std::optional<Transform> worldFromCamera;  // replaces the camera's placement
    float fovDeg = 0;                          // 0: the Camera's; degrees on the shorter axis
    int lightSamples = 0;                      // 0: each area/infinite light's own nsamples
    std::string integrator;  // a name of render/integrator_list.inc; "": the scene's
    // A sampler type whose samples replace the Sampler's (its count stays): "": the scene's.
    std::string sampler;
    // How the path integrators choose lights ("bvh", "power", "uniform"; --light-sampler):
    // "": the Integrator's "lightsampler" / "lightsamplestrategy".
    std::string lightSampler;
    // The integrator of a pbrt scene without an Integrator directive ("": pbrt-v3's default,
    // "path"); tests written for Whitted set "whitted".
    std::string defaultIntegrator;
    int glossySamples = 0;  // 0: the Integrator's "glossysamples"
    // Image-texture lookups: "point", "bilinear", "trilinear" or "ewa" for every imagemap
    // (--texture-filter); "": each texture's own "filter" (pbrt-v3's default, EWA).
    std::string textureFilter;
    // How to build.
    Precision precision = Precision::Double;
    // Accuracy knobs (`prism study`, docs/ACCURACY.md). Defaults are Prism's normal choices.
    // Ray-weight cutoff: a secondary ray is traced only if its throughput can change the pixel
    // by more than this (0: every ray; counted in RayCounters::cutoff when skipped).
    float rayCutoff = 0;
    // How secondary rays leave a surface: error bounds (default), a fixed epsilon in scene
    // units along the geometric normal, or no offset at all.
    RayOffset offset{};
    bool robust = false;                       // Embree's RTC_SCENE_FLAG_ROBUST
    BvhQuality bvhQuality = BvhQuality::Auto;  // Auto: by triangles and samples (accel.h)
    // The render's memory budget (core/memory.h), usually the one LoadOptions::budget charged
    // the scene files to. The build charges to it, and keeps charged, the film (EstimateFilmBytes),
    // decoded image textures, every triangle mesh (trianglemesh, plymesh, loopsubdiv,
    // tessellated twins) and the BVH (EstimateBvhBytes), each before it is allocated; exceeding
    // it is a MemoryBudgetError (a SceneError), not an OOM kill. The caller keeps it alive for
    // the render. Null: a budget of the default limit (75% of physical RAM) for this build.
    MemoryBudget *budget = nullptr;
    // Render in camera-centred world space (default). `prism trace` turns it off so that
    // world-space rays are traced without re-rounding.
    bool cameraRelative = true;
    // false: build everything but the top-level BVH (`prism info`: every build warning, no
    // Embree commit); the scene cannot be rendered then.
    bool buildBvh = true;
    // --effects all: the renderer runs its general kernel rather than the one specialized for
    // the scene's effects (RenderScene::allEffects; the same image, for comparison).
    bool allEffects = false;
    // --stats: the film also keeps each pixel's even and odd samples apart, for the noise
    // estimate (RenderScene::estimateNoise).
    bool estimateNoise = false;
    ShapeReplacement replaceAnalyticShape;  // empty: every analytic shape stays analytic
};

// Creates textures, materials, lights, the camera and film settings, shapes, instances and the
// BVH. Throws SceneError (with the entity's location) for bad input; warns for what it
// approximates or skips.
RenderScene BuildRenderScene(const SceneDescription &desc, const BuildSettings &settings,
                             Diagnostics &diag);

}  // namespace prism
