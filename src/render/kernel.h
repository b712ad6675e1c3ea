// The render kernel of Integrator "whitted" and "distribution". Kernel<K> is the shading kernel
// compiled for one of four masks K (KernelCompiled): the Lambertian kernel (f = kd/π, no BSDF
// is built), the BSDF kernel without specular recursion, the general kernel, and the general
// kernel with media. The other effects of a scene's kernel mask (KernelMaskFor: glossy rays,
// light samples, pass-through surfaces, camera samples) are decided at run time from
// KernelParams::effects, one predictable branch per hit: measured with their own
// instantiations they paid nothing the machine could resolve (docs/EFFECTS.md, "Which effects
// are compiled"), while the BSDF and specular bits pay 10-18%. `--effects all` runs the general
// kernel with every effect on. All give bit-identical images (tests/render/kernel_test.cpp).
//
// Textures, CSG and instancing live below the kernel (in materials and in the BVH) and cost
// nothing where absent without a bit of their own. Participating media run one instantiation,
// KernelMediaMask (render/kernel_media.h), so media-free scenes run exactly the kernels they
// ran before.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/accel.h"
#include "image/bounds2.h"
#include "render/integrator.h"
#include "render/ray_tree.h"

namespace prism {

struct BSDF;
struct TextureContext;
struct RenderScene;
enum class GlossyRays;

// Identifies the camera sample being traced, so that light samples form stratified patterns
// across the pixel's samples and are a pure function of (pixel, sample); and carries the
// throughput of the path down to the ray being traced (for the ray-weight cutoff).
struct SampleContext {
    int x = 0, y = 0;
    uint32_t sample = 0, spp = 1;
    RGB beta = RGB(1);         // product of the specular weights from the camera to this ray
    bool afterGlossy = false;  // a glossy bounce lies between the camera and this ray
    // The ray's differentials (RenderScene::differentials), or null: unfiltered lookups.
    const RayDifferential *diff = nullptr;
    int medium = -1;  // the medium the ray starts in (RenderScene::media; -1: none)
    // The secondary rays the tree below this ray may still trace (render/ray_tree.h).
    uint64_t treeRays = kRayTreeBudget;
};

// What the kernel reads beside the scene: whether it traces glossy rays (Integrator
// "distribution") and how many, and the seed of the render's sample patterns.
struct KernelParams {
    bool glossyRays = false;
    int glossySamples = 8;
    uint32_t seed = 0;
    // The scene's kernel mask (KernelMaskFor; KernelAll: every effect): the effects outside
    // the compiled mask that the kernel applies, decided at run time.
    uint32_t effects = 0x3f;
    TraceSettings trace;  // the render's (TileContext::trace)
};

enum KernelBit : uint32_t {
    KernelSpecular = 1u << 0,       // delta reflection and transmission: recursion
    KernelGlossy = 1u << 1,         // glossy rays (Integrator "distribution" only)
    KernelLightSamples = 1u << 2,   // area or infinite lights: stratified light samples,
                                    // emission of hit surfaces, radiance of escaping rays
    KernelCameraSamples = 1u << 3,  // lens samples (depth of field) and ray times (motion blur)
    KernelPassThrough = 1u << 4,    // "none" materials: rays continue through surfaces
    // Materials other than Lambertian matte: BSDFs are built and evaluated. Without it (every
    // material Lambertian, so nothing specular or glossy either) f is kd/π.
    KernelBsdf = 1u << 5,
    // Participating media: rays carry their medium (SampleContext::medium), every segment is
    // attenuated and ray-marched for single scattering. Only in KernelMediaMask.
    KernelMedia = 1u << 6,
};
inline constexpr int KernelBits = 6;  // the bits of the per-effect masks (not KernelMedia)
inline constexpr uint32_t KernelAll = (1u << KernelBits) - 1;
// The one kernel of scenes with media.
inline constexpr uint32_t KernelMediaMask = KernelAll | KernelMedia;
// The bits that are compiled (the others are run-time flags): the general kernel is
// KernelGeneral, the Lambertian kernel 0.
inline constexpr uint32_t KernelGeneral = KernelSpecular | KernelBsdf;
static_assert(KernelAll == 0x3f, "KernelParams::effects defaults to KernelAll");

// The smallest kernel mask that renders `scene` exactly (from scene.features.effects);
// KernelMediaMask for scenes with media.
uint32_t KernelMaskFor(const RenderScene &scene, const TraceSettings &trace);
// With the scene's own trace settings (RenderScene::trace).
uint32_t KernelMaskFor(const RenderScene &scene);
// The general kernel for `scene` (--effects all): KernelAll, or KernelMediaMask with media.
uint32_t KernelAllFor(const RenderScene &scene);
// "specular+light samples", "none" (the diffuse kernel), "all".
std::string KernelMaskName(uint32_t mask);

// The compiled mask that runs kernel mask `mask`.
constexpr uint32_t KernelCompiled(uint32_t mask) {
    if (mask & KernelMedia) return KernelMediaMask;
    if (mask & (KernelSpecular | KernelGlossy | KernelBsdf))
        return (mask & KernelSpecular) ? KernelGeneral : uint32_t(KernelBsdf);
    return 0;
}

template <uint32_t K>
class Kernel {
  public:
    static constexpr bool Specular = (K & KernelSpecular) != 0;
    static constexpr bool GeneralBsdf = (K & KernelBsdf) != 0;
    static constexpr bool Media = (K & KernelMedia) != 0;
    static_assert(K == KernelCompiled(K), "Kernel<K> exists for the compiled masks only");

    // params.effects: the glossy, light-sample and pass-through effects applied at run time
    // (glossy ones need a BSDF kernel); params.glossyRays: trace glossy rays (Integrator
    // "distribution").
    Kernel(const RenderScene &scene, const KernelParams &params)
        : scene_(scene),
          params_(params),
          glossy_(GeneralBsdf && (params.effects & KernelGlossy) != 0),
          lightSamples_((params.effects & KernelLightSamples) != 0),
          passThrough_((params.effects & KernelPassThrough) != 0) {}
    // Radiance along a ray; depth counts specular bounces (camera rays are depth 0). emitted
    // false (glossy rays only): the area light of the first hit is not added, because light
    // samples at the previous hit estimated it.
    RGB Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc,
           bool emitted = true) const;
    // The same for a camera ray whose closest hit is already known (hit.shape < 0: a miss).
    RGB LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                 const SampleContext &sc) const;

  private:
    // Radiance of a ray that leaves the scene (infinite lights).
    RGB Escaped(const Ray &ray) const;
    // Radiance along ray given its closest hit si (continues through pass-through surfaces).
    RGB Shade(const Ray &ray, SurfaceInteraction si, int depth, RayCounters &counters,
              const SampleContext &sc, bool emitted) const;
    // Adds the specular reflection and transmission of every BSDF part to L; returns how many
    // rays it spawned (traced or left out by the ray tree's budget, which they share with the
    // hit's `glossyRays` glossy rays). tc holds the hit's footprint where the ray carries
    // differentials (diff not null).
    uint64_t AddSpecular(const SurfaceInteraction &si, const TextureContext &tc,
                         const RayDifferential *diff, const BSDF &bsdf, int depth,
                         RayCounters &counters, const SampleContext &sc, uint64_t glossyRays,
                         RGB &L) const;
    // Turns rough glass glossy; says how glossy rays are traced from this hit.
    GlossyRays PrepareGlossy(BSDF &bsdf, int depth) const;
    // Adds the glossy reflection and transmission of every BSDF part to L: the scene's
    // glossySamples rays per part at the first glossy bounce of a path, 1 deeper down.
    // `specularRays`: the hit's specular rays, which come first in its share of the ray tree.
    void AddGlossy(const SurfaceInteraction &si, const BSDF &bsdf, GlossyRays mode, int depth,
                   RayCounters &counters, const SampleContext &sc, uint64_t specularRays,
                   RGB &L) const;
    // The most glossy rays AddGlossy spawns at a hit.
    uint64_t GlossyRayCount(const BSDF &bsdf, const SampleContext &sc) const;
    // The ray-weight cutoff: true when a secondary ray of throughput beta is traced.
    bool AboveCutoff(const RGB &beta) const;
    // Direct lighting through f(wi, byGlossyRays) (a BSDF, or kd/π in Lambertian kernels).
    // `ambient` scales the environment lights' share (Material::AmbientOcclusion).
    template <class F>
    [[gnu::always_inline]] void AddDirect(const SurfaceInteraction &si, const Vec3f &ns, const F &f,
                                          GlossyRays glossy, bool hasDiffuse, int depth,
                                          RayCounters &counters, const SampleContext &sc, RGB &L,
                                          float ambient = 1) const;
    template <class F>
    [[gnu::noinline]] void AddDirectSampled(const SurfaceInteraction &si, const Vec3f &ns,
                                            const F &f, GlossyRays glossy, bool hasDiffuse,
                                            int depth, RayCounters &counters,
                                            const SampleContext &sc, RGB &L, float ambient) const;

    // Media (render/kernel_media.h). The radiance along ray (in sc.medium) whose closest hit
    // is si (hit false: it escapes): single scattering along each segment plus the
    // transmittance times what lies beyond, continuing through "none" surfaces (which may
    // change the medium) up to the first visible surface.
    RGB LiMedia(Ray ray, bool hit, SurfaceInteraction si, int depth, RayCounters &counters,
                const SampleContext &sc, bool emitted) const;
    // Light scattered toward ray.o by the medium along [0, tEnd) of ray, ray-marched toward
    // the delta lights (pbrt-v2's SingleScatteringIntegrator).
    RGB InScattered(const Ray &ray, float tEnd, int medium, int depth, RayCounters &counters,
                    const SampleContext &sc) const;

    const RenderScene &scene_;
    KernelParams params_;
    // The run-time effects (params.effects).
    bool glossy_, lightSamples_, passThrough_;
};

// Fills the camera samples of one tile with Kernel<KernelCompiled(mask)> (packets of camera
// rays); params.effects is the mask.
using KernelTileFn = void (*)(const TileContext &ctx, const KernelParams &params, TileSamples &out,
                              RayCounters &rc);
KernelTileFn KernelRenderTile(uint32_t mask);
// The direct part of a camera ray whose closest hit is known (the direct AOV): emission and
// direct lighting at the first surface, by the kernel without specular or glossy rays.
RGB KernelDirectLiCamera(const RenderScene &scene, const KernelParams &params, const Ray &ray,
                         const RawHit &hit, RayCounters &rc, const SampleContext &sc);

// The kernel mask with KernelBsdf added where the mask bounces (a Lambertian kernel has no
// specular or glossy code).
constexpr uint32_t KernelCanonical(uint32_t mask) {
    return (mask & (KernelSpecular | KernelGlossy)) ? mask | KernelBsdf : mask;
}

}  // namespace prism
