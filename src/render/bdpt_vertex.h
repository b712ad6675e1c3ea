// The vertices of the bidirectional integrator's subpaths (render/bdpt_integrator.h) and the
// steps that make and join them: the camera and light random walks (bdpt_walk.cpp) and the
// connection of a light subpath's prefix with a camera subpath's, weighted by multiple
// importance sampling over every strategy that could have made the same path
// (bdpt_connect.cpp). Veach's thesis, chapter 10; pbrt-v3 16.3 (no code copied). In
// participating media the walks also stop at scattering points (medium vertices, with the
// medium's phase function for a BSDF) and every connection carries the transmittance between
// its ends, as pbrt-v3's bdpt does.
#pragma once

#include <optional>
#include <vector>

#include "geometry/interaction.h"
#include "render/bdpt_camera.h"
#include "render/bsdf.h"
#include "render/light.h"
#include "render/light_sampling.h"

namespace prism {

struct RenderScene;
struct RayCounters;
struct ShapeInfo;
class HenyeyGreenstein;

enum class BdptVertexType : uint8_t { Camera, Light, Surface, Medium };

// One vertex of a subpath. Densities are per unit area of the vertex (per unit volume in a
// medium, per unit solid angle for a vertex at infinity, an infinite light's); 0 for a delta
// bounce, whose strategies MIS skips. As in pbrt-v3, the densities leave out the medium's
// distance sampling: the weights stay a function of the path alone, so they still sum to one.
struct BdptVertex {
    // Every member has its initializer: a user-provided constructor keeps value-initialization
    // (emplace_back()) from first zeroing the whole vertex, the BSDF's storage (4.7 KB) too.
    BdptVertex() {}
    BdptVertexType type = BdptVertexType::Surface;
    RGB beta;     // the subpath's throughput up to this vertex
    Vec3f p, ng;  // position and geometric normal (zero for point lights, the camera, media)
    Vec3f ns;     // surface vertices: the shading normal
    Vec3f wo;     // surface vertices: unit direction back to the previous vertex
    float pdfFwd = 0, pdfRev = 0;  // the density of its own subpath, and of the other's
    bool delta = false;            // a delta lobe was sampled here (or a delta light)
    bool infinite = false;         // an infinite or distant light: p is a direction (wo)
    int light = -1;                // light vertices: the light; surfaces: the area light hit
    SurfaceInteraction si;         // surfaces (and area-light origins): for spawned rays
    std::optional<BSDF> bsdf;      // surfaces
    RGB emitted;                   // surfaces: emission the material carries (glTF)
    // The medium the vertex lies in (RenderScene::media, -1: vacuum); for a surface, the
    // medium of the ray that reached it, and its shape, whose MediumInterface decides the
    // medium of the rays leaving it (MediumToward).
    int medium = -1;
    const ShapeInfo *shape = nullptr;
    const HenyeyGreenstein *phase = nullptr;  // medium vertices: the medium's phase function

    // Light paths can connect here: a surface with non-delta lobes, a point in a medium, or a
    // light.
    bool Connectible() const {
        return type != BdptVertexType::Surface || (bsdf && bsdf->HasNonSpecular());
    }
    // |cos| between a connection's direction w and the normal: 1 off surfaces (media, lights
    // without a normal).
    float AbsCos(const Vec3f &w) const {
        return type == BdptVertexType::Surface ? AbsDot(ns, w) : 1.f;
    }
};

// What a subpath's steps share: the scene, its light choice and the camera as light tracing
// sees it.
struct BdptContext {
    const RenderScene &scene;
    const LightChooser &chooser;
    const CameraImportance &camera;
    const SceneSphere &sphere;
    int maxDepth;
    // pbrt-v4's "regularize": after a subpath's first non-specular bounce, its surfaces'
    // BSDFs are regularized (BSDF::Regularize).
    bool regularize = false;
    // The medium rays escaping the scene end in (MediumAtInfinity): where the light subpaths
    // of infinite and distant lights begin.
    int infinityMedium = -1;
};

// The medium a ray leaving vertex v in direction w travels in.
int MediumToward(const RenderScene &scene, const BdptVertex &v, const Vec3f &w);

// Where a path's subpaths and connections draw their random numbers, by dimension
// (BdptCameraDim, BdptLightDim): a camera sample's PixelSamples (bdpt) or a state of a
// primary-sample-space Markov chain (mlt, render/mlt_sampler.h).
class BdptSamples {
  public:
    virtual float Get1D(uint32_t dim) const = 0;
    virtual Vec2f Get2D(uint32_t dim) const = 0;

  protected:
    ~BdptSamples() = default;
};

// A camera sample's PixelSamples as BdptSamples.
class BdptPixelSamples final : public BdptSamples {
  public:
    explicit BdptPixelSamples(const PixelSamples &ps) : ps_(ps) {}
    float Get1D(uint32_t dim) const override { return ps_.Get1D(dim); }
    Vec2f Get2D(uint32_t dim) const override { return ps_.Get2D(dim); }

  private:
    const PixelSamples &ps_;
};

// The dimensions a path draws, per subpath vertex: 0 (2-D) the direction leaving it, 1 the
// lobe, 2 the light choice (camera vertices) or the lens point (light vertices), 3 (2-D) the
// light sample (the light vertex: 0 the light, 1 and 2 its ray), 4 (2-D) the first numbers of
// the medium sampling of the segment leaving it and 5 the seed of the rest, 6 the seed of the
// transmittance of the connections ending there (t > 1: the camera vertex's; t = 1: the light
// vertex's), 7 (light vertex 0) that of the medium beyond the scene (infinite lights).
uint32_t BdptCameraDim(int vertex, uint32_t d);  // d < 8
uint32_t BdptLightDim(int vertex, uint32_t d);   // d < 8
// A seed for a PCG32 stream from sample dimension dim and a salt.
uint64_t SampleSeed(const BdptSamples &ps, uint32_t dim, uint32_t salt);

// The camera subpath of a camera ray: the camera vertex and up to maxDepth + 1 surfaces (or
// an escape to the infinite lights). diff: the camera ray's differentials (first hit only).
void CameraSubpath(const BdptContext &ctx, const Ray &ray, const BdptSamples &ps,
                   const RayDifferential *diff, std::vector<BdptVertex> &path, RayCounters &rc);
// The light subpath: a light chosen by power, its emitted ray and up to maxDepth surfaces.
void LightSubpath(const BdptContext &ctx, const BdptSamples &ps, std::vector<BdptVertex> &path,
                  RayCounters &rc);

// The contribution of strategy (s, t): the first s light vertices joined to the first t camera
// vertices, times its MIS weight. t = 1 gives the radiance onto *raster (a splat) instead of
// the camera sample's own pixel.
RGB ConnectStrategy(const BdptContext &ctx, const std::vector<BdptVertex> &light,
                    const std::vector<BdptVertex> &camera, int s, int t, const BdptSamples &ps,
                    Vec2f *raster, RayCounters &rc);

}  // namespace prism
