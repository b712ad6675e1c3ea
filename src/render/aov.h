// Arbitrary output variables (AOVs): per-pixel layers beside the beauty image, written into one
// multi-channel EXR (`prism render --aov`, Film "string aovs"; README "AOVs"). They are computed
// by a pass of their own after the beauty render, chosen once per render: a render without AOVs
// runs none of this code and its image is unchanged.
//
// Filtering: the geometric layers (depth, P, N, Ng, uv) and the ids come from one sample per
// pixel, the one nearest the pixel centre (the centre itself at 1 spp), so ids are never blended
// at edges. albedo is the mean over the pixel's samples (a box over the pixel). direct and
// indirect are splatted through the Film's pixel filter like the beauty, so
// direct + indirect = RGB (to float rounding). variance is the unbiased sample variance of the
// pixel's own samples (0 at 1 spp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "geometry/interaction.h"

namespace prism {

struct RenderScene;

enum class Aov {
    Depth,        // Z: view-space distance along the camera axis (+inf where nothing is hit)
    Position,     // P.X P.Y P.Z: world-space hit point
    Normal,       // N.X N.Y N.Z: shading normal (world space)
    GeoNormal,    // Ng.X Ng.Y Ng.Z: geometric normal, turned toward the ray
    Albedo,       // albedo.R albedo.G albedo.B: diffuse reflectance of the first hit
    UV,           // uv.U uv.V
    ShapeId,      // shape_id: declaration number (1-based; 0: no hit)
    PrimitiveId,  // primitive_id: triangle index (0 for analytic shapes; -1: no hit)
    InstanceId,   // instance_id: 1 + ObjectInstance index (0: not in an instance)
    MaterialId,   // material_id: 1 the default matte, 2 + Material declaration index
    Direct,       // direct.R/G/B: emission + direct lighting at the first hit (whitted)
    Indirect,     // indirect.R/G/B: everything else (specular reflection and refraction)
    Variance,     // variance.R/G/B: per-pixel sample variance of the beauty
    Count
};

const char *AovName(Aov a);  // "depth", "P", "N", "Ng", "albedo", "uv", "shape_id", ...
// The EXR channel names of one AOV ("Z"; "P.X", "P.Y", "P.Z"; ...).
std::vector<std::string> AovChannels(Aov a);
// "all" or a comma-separated list of AovName()s (case-sensitive; duplicates are merged, the
// order is Aov's). Returns false with a message naming the bad entry.
bool ParseAovList(const std::string &list, std::vector<Aov> *aovs, std::string *error);

// The ids of the declaration a hit belongs to (shape, material, instance); app/shape_lookup.h.
using AovIdFn =
    std::function<void(const SurfaceInteraction &si, int *shape, int *material, int *instance)>;

// One AOV's pixels over the render's pixel bounds, channels interleaved, top row first.
struct AovLayer {
    Aov aov;
    std::vector<std::string> channels;
    std::vector<float> pixels;
};

// Renders the requested AOVs of `scene` (after the beauty: it turns on uv and tangents of
// every top-level shape). Direct and indirect need Integrator "whitted": for "distribution"
// they are an error reported by the caller (AovsNeedWhitted).
std::vector<AovLayer> RenderAovs(const RenderScene &scene, const std::vector<Aov> &aovs,
                                 const AovIdFn &ids);
bool AovsNeedWhitted(const std::vector<Aov> &aovs);

}  // namespace prism
