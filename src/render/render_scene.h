// Everything a render needs, built once from a SceneDescription and immutable while rendering.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/accel.h"
#include "image/film.h"
#include "render/camera.h"
#include "render/light.h"
#include "render/material.h"
#include "scene/scene_description.h"

namespace prism {

// Command-line overrides of what the scene file says.
struct RenderOptions {
    int spp = 0;                    // 0: the scene's Sampler
    Vec2i resolution{0, 0};         // 0: the scene's Film
    int maxDepth = -1;              // -1: the scene's Integrator
    std::optional<std::array<float, 4>> crop;  // NDC x0 x1 y0 y1, like Film "cropwindow"
    Precision precision = Precision::Double;
    int threads = 0;                // 0: all cores
    int lightSamples = 0;           // 0: each area/infinite light's own nsamples
    std::optional<std::array<float, 9>> lookAt;  // eye, look, up: replaces the scene's camera
    float fov = 0;                  // degrees on the shorter image axis; 0: the scene's
    bool quiet = false;
    // Memory budget in bytes for the film and image textures (and PLY meshes); 0: the default,
    // 75% of physical RAM (core/memory.h). Exceeding it is a SceneError, not an OOM kill.
    uint64_t maxMemory = 0;
    // Render in camera-centred world space (default). `prism trace` turns it off so that
    // world-space rays are traced without re-rounding.
    bool cameraRelative = true;
    // [validate hook] > 0: every analytic shape is replaced by its triangle twin with this
    // many segments around the axis (validate/tessellate.h).
    int tessellate = 0;
};

// What the scene calls for; the renderer simulates only these effects.
struct SceneFeatures {
    bool specularReflection = false;  // mirror, glass, polished metal
    bool transmission = false;        // glass
    bool textures = false;            // non-constant textures
    bool lens = false;                // depth of field
    bool areaLights = false;          // soft shadows: stratified emitter sampling
    bool environment = false;         // an infinite light
    int analyticShapes = 0, meshes = 0;
    size_t triangles = 0;
};

struct ShapeInfo {
    int material = 0;        // index into RenderScene::materials
    int areaLight = -1;      // index into RenderScene::lights when the shape emits
    int directiveIndex = 0;  // Shape directive order in the scene file
    std::string type;
    int prototype = -1;      // instances: index into RenderScene::prototypes
};

struct RenderScene {
    std::unique_ptr<Accel> accel;
    std::vector<ShapeInfo> shapes;  // by accel shape index
    std::vector<std::vector<ShapeInfo>> prototypes;  // ObjectBegin groups, by prototype shape
    // The shape a hit belongs to (looking inside instances).
    const ShapeInfo &Info(const SurfaceInteraction &si) const {
        const ShapeInfo &top = shapes[size_t(si.shape)];
        if (top.prototype < 0) return top;
        return prototypes[size_t(top.prototype)][size_t(si.instanceShape)];
    }
    std::vector<Material> materials;
    std::vector<std::unique_ptr<Light>> lights;
    std::unique_ptr<Camera> camera;
    Transform renderFromWorld;      // world translated so the camera sits at the origin
    Vec2i resolution{1280, 720};
    Bounds2i pixelBounds;           // crop window in pixels
    Filter filter;
    float filmScale = 1;
    float maxSampleLuminance = Infinity;
    int spp = 1;
    int maxDepth = 5;
    std::string outputFilename;     // Film "filename"
    std::string integratorName;
    SceneFeatures features;
    double buildSeconds = 0;        // BVH build only
};

// Creates lights, materials, camera, shapes and the BVH. Throws SceneError (with the entity's
// location) for bad input; warns for what it approximates or skips.
RenderScene BuildRenderScene(const SceneDescription &desc, const RenderOptions &options,
                             Diagnostics &diag);

}  // namespace prism
