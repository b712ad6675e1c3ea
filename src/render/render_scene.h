// Everything a render needs, built once from a SceneDescription (assembly/build_scene.h) and
// immutable while rendering.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pbrt_defaults.h"
#include "geometry/accel.h"
#include "image/film.h"
#include "image/tonemap.h"
#include "render/camera.h"
#include "render/effects.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/material.h"
#include "render/medium.h"
#include "render/sampler.h"

namespace prism {

// What the scene calls for; the renderer simulates only these effects. `effects` is the full
// record (with reasons; render/kernel.h KernelMaskFor reads it); the bools below predate it
// and are kept for their users (study, bench, the lens samples).
struct SceneFeatures {
    bool specularReflection = false;  // mirror, glass, polished metal
    bool transmission = false;        // glass
    bool textures = false;            // non-constant textures
    bool lens = false;                // depth of field
    bool areaLights = false;          // soft shadows: stratified emitter sampling
    bool environment = false;         // an infinite light
    int analyticShapes = 0, meshes = 0;
    int csgNodes = 0;  // top-level CSGBegin nodes (their operands count as shapes too)
    size_t triangles = 0;
    size_t curveSegments = 0;  // of "curve" shapes (Embree's native curves)
    EffectSet effects;         // what the scene calls for, with reasons (render/effects.h)
};

struct ShapeInfo {
    int material = 0;        // index into RenderScene::materials
    int areaLight = -1;      // index into RenderScene::lights when the shape emits
    int directiveIndex = 0;  // Shape directive order in the scene file
    std::string type;
    int prototype = -1;  // instances: index into RenderScene::prototypes
    int instance = -1;   // instances: index into SceneDescription::instances (pick, AOVs)
    // MediumInterface (RenderScene::media; -1: vacuum). Equal media are no transition: a ray
    // crossing the surface keeps its medium (pbrt-v3 GeometricPrimitive).
    int mediumInside = -1, mediumOutside = -1;
};

// The medium of a ray leaving the surface of si (of shape s) in direction w, when the ray
// that reached it was in `current` (pbrt-v3 Interaction::GetMedium).
inline int MediumAfter(const ShapeInfo &s, const SurfaceInteraction &si, const Vec3f &w,
                       int current) {
    if (s.mediumInside == s.mediumOutside) return current;
    return Dot(w, si.n) > 0 ? s.mediumOutside : s.mediumInside;
}

struct RenderScene {
    std::unique_ptr<Accel> accel;
    std::vector<ShapeInfo> shapes;                   // by accel shape index
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
    Transform renderFromWorld;  // world translated so the camera sits at the origin
    Vec2i resolution{PbrtDefaultXResolution, PbrtDefaultYResolution};
    Bounds2i pixelBounds;  // crop window in pixels
    Filter filter;
    float filmScale = 1;
    // A linear map of each sample's sRGB after filmScale (row-major; pbrt-v4's white balance:
    // assembly/film_sensor.h), or none.
    std::optional<std::array<float, 9>> filmColor;
    // The xy chromaticities (red, green, blue, white) of the film's RGB when its colour space
    // is not sRGB (pbrt-v4's ColorSpace): written into EXR outputs.
    std::optional<std::array<float, 8>> filmChromaticities;
    float maxSampleLuminance = Infinity;
    float maxComponentValue = Infinity;  // pbrt-v4's Film "maxcomponentvalue"
    // The sampler: spp, the pattern of the path integrators' dimensions and the seed (0: a
    // render's; progressive passes render with seeds of their own, render/progressive.h).
    SamplerSettings sampler;
    // --stats: the film also sums each pixel's even and odd samples apart, for the noise
    // estimate (RenderStats::noiseVariance).
    bool estimateNoise = false;
    // The file's maxdepth and the ray-weight cutoff (BuildSettings): a render's unless its
    // RenderOptions say otherwise.
    TraceSettings trace;
    // Accuracy knob (BuildSettings): how spawned rays leave a surface.
    RayOffset offset;
    std::string outputFilename;  // Film "filename"
    // Film "exposure" (EV) and "tonemap" (Prism extensions, image/tonemap.h), the tone map
    // defaulting to the format's; whether an 8-bit output without an exposure is exposed
    // automatically (OBJ, glTF and PLY scenes lit by their own emitters). The command line may
    // replace each.
    float filmExposure = 0;
    ToneMap filmToneMap = ToneMap::None;
    bool autoExposure8Bit = false;
    // Film "aovs" (Prism extension, render/aov.h): "" or a checked AOV list ("all", "Z,N").
    std::string filmAovs;
    // The integrator that runs (render/integrator.h, created from the Integrator directive),
    // and why it is that one: "Integrator \"path\" at f.pbrt:3", "--integrator path".
    std::unique_ptr<Integrator> integrator;
    std::string integratorWhy;
    const char *IntegratorName() const { return integrator ? integrator->Name() : "none"; }
    // Each light's power (luminance), for LightChoice::Power: filled by the build
    // (render/light_sampling.h ComputeLightPower); empty: lights are chosen uniformly.
    std::vector<double> lightPower;
    // Participating media (MakeNamedMedium, in directive order) and the camera's (pbrt-v3: the
    // outside medium of the MediumInterface current at Camera; -1: none). Rays carry their
    // medium only when features.effects has Effect::Media (render/kernel.h KernelMedia).
    std::vector<std::unique_ptr<Medium>> media;
    int cameraMedium = -1;
    // The media around each light (by index into lights), where the rays it emits begin
    // (pbrt-v3's light MediumInterface): an area light's shape's inside and outside, for other
    // lights the outside medium current at LightSource for both. Missing: vacuum.
    struct LightMedia {
        int inside = -1, outside = -1;
    };
    std::vector<LightMedia> lightMedia;
    // The medium of a ray light `light` emits from a point with normal n (zero: none) in
    // direction w.
    int LightMedium(int light, const Vec3f &n, const Vec3f &w) const {
        if (light < 0 || size_t(light) >= lightMedia.size()) return -1;
        const LightMedia &m = lightMedia[size_t(light)];
        return Dot(n, w) > 0 ? m.outside : m.inside;
    }
    SceneFeatures features;
    // Some surface has no BSDF (Material::IsPassThrough): rays cross it without a bounce.
    bool passThrough = false;
    // Some material filters a texture over the ray's footprint (Material::UsesDifferentials):
    // camera rays carry ray differentials (render/differentials.h), specular bounces keep them.
    bool differentials = false;
    // --effects all: render with the general kernel instead of the one specialized for
    // features.effects (render/kernel.h; same image, for comparison).
    bool allEffects = false;
    double buildSeconds = 0;  // BVH build only
    // The build's memory budget (core/memory.h): its limit and what the scene charged to it,
    // so that a render's own large buffers (sppm's visible points and photon grid) are
    // checked against what is left.
    uint64_t memoryLimit = 0, memoryCommitted = 0;
};

}  // namespace prism
