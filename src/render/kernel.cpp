#include "render/kernel.h"

#include "render/render_scene.h"

namespace prism {

template <uint32_t K>
void RenderTileKernel(const TileContext &ctx, const KernelParams &params, TileSamples &out,
                      RayCounters &rc);  // instantiated in kernel_*.cpp

uint32_t KernelMaskFor(const RenderScene &scene, const TraceSettings &trace) {
    const EffectSet &e = scene.features.effects;
    // Media: the one general kernel with media compiled in (kernel_media.cpp).
    if (e.Has(Effect::Media)) return KernelMediaMask;
    uint32_t mask = 0;
    // Recursion (specular or glossy) needs a second bounce.
    const bool recursion = trace.maxDepth > 1;
    if (recursion && (e.Has(Effect::SpecularReflection) || e.Has(Effect::Refraction)))
        mask |= KernelSpecular;
    if (recursion && scene.integrator && scene.integrator->Traits().glossyRays &&
        (e.Has(Effect::GlossyReflection) || e.Has(Effect::GlossyTransmission)))
        mask |= KernelGlossy;
    if (e.Has(Effect::SoftShadows) || e.Has(Effect::Environment)) mask |= KernelLightSamples;
    if (e.Has(Effect::DepthOfField) || e.Has(Effect::MotionBlur)) mask |= KernelCameraSamples;
    // Details no effect names, read from the scene itself: lights that take stratified samples
    // (whatever builds them) and "none" materials.
    for (const auto &light : scene.lights)
        if (light->UsesSample() || light->NumSamples() != 1 || light->IsArea())
            mask |= KernelLightSamples;
    for (const Material &m : scene.materials) {
        if (m.IsPassThrough()) mask |= KernelPassThrough;
        if (!m.IsLambertian() && !m.IsPassThrough()) mask |= KernelBsdf;
    }
    return KernelCanonical(mask);
}

uint32_t KernelMaskFor(const RenderScene &scene) { return KernelMaskFor(scene, scene.trace); }

RGB KernelDirectLiCamera(const RenderScene &scene, const KernelParams &params, const Ray &ray,
                         const RawHit &hit, RayCounters &rc, const SampleContext &sc) {
    KernelParams p = params;
    p.glossyRays = false;
    p.effects = KernelAll & ~(KernelSpecular | KernelGlossy);
    return Kernel<KernelBsdf>(scene, p).LiCamera(ray, hit, rc, sc);
}

uint32_t KernelAllFor(const RenderScene &scene) {
    return scene.features.effects.Has(Effect::Media) ? KernelMediaMask : KernelAll;
}

std::string KernelMaskName(uint32_t mask) {
    if (mask == KernelAll) return "all";
    if (mask == KernelMediaMask) return "all+media";
    static const char *const names[KernelBits] = {"specular",       "glossy",       "light samples",
                                                  "camera samples", "pass-through", "BSDF"};
    std::string s;
    for (int i = 0; i < KernelBits; ++i)
        if (mask & (1u << i)) {
            if (!s.empty()) s += '+';
            s += names[i];
        }
    return s.empty() ? "Lambertian" : s;
}

KernelTileFn KernelRenderTile(uint32_t mask) {
    switch (KernelCompiled(mask)) {
        case 0:
            return &RenderTileKernel<0>;
        case KernelBsdf:
            return &RenderTileKernel<KernelBsdf>;
        case KernelGeneral:
            return &RenderTileKernel<KernelGeneral>;
        default:
            return &RenderTileKernel<KernelMediaMask>;
    }
}

}  // namespace prism
