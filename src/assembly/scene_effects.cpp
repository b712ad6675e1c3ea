#include "assembly/scene_effects.h"

#include <algorithm>

#include "render/bsdf.h"

namespace prism {

std::string MaterialWhy(const SceneDescription &desc, const ShapeDesc &s, FileLoc *loc) {
    if (s.material < 0) {
        *loc = s.loc;
        return "shape " + Quote(s.type) + " (default material)";
    }
    const MaterialDesc &md = desc.materials[size_t(s.material)];
    *loc = md.loc;
    return "material " + Quote(md.name.empty() ? md.type : md.name);
}

void NoteMaterialEffects(BuildContext &ctx, const Material &m, const std::string &why,
                         const FileLoc &loc) {
    EffectSet &e = ctx.scene.features.effects;
    // The distribution, directlighting and path integrators turn rough glass into glossy lobes
    // and sample glossy lobes; Whitted follows rough glass's delta lobes (pbrt-v3's
    // "whitted"): it is specular there.
    const bool distribution = ctx.scene.integrator->Traits().roughGlass;
    const bool roughGlassOnly = distribution && m.Model().IsRoughGlass();
    if (m.MayReflectSpecularly() && !roughGlassOnly) e.Enable(Effect::SpecularReflection, why, loc);
    if (m.MayTransmit() && !roughGlassOnly) e.Enable(Effect::Refraction, why, loc);
    if (distribution) {
        if (m.MayReflectGlossily()) e.Enable(Effect::GlossyReflection, why, loc);
        if (m.MayTransmitGlossily()) e.Enable(Effect::GlossyTransmission, why, loc);
    }
    if (m.TextureNeeds() & NeedUV) e.Enable(Effect::Textures, why + " (textured)", loc);
    if (m.bump) e.Enable(Effect::BumpMapping, why + " (bumpmap)", loc);
    if (m.normalMap) e.Enable(Effect::NormalMapping, why + " (normal map)", loc);
    if (m.HasSubsurface()) {
        if (ctx.scene.integrator->Traits().subsurface)
            e.Enable(Effect::Subsurface, why, loc);
        else if (ctx.subsurfaceWarned.insert(&m.Model()).second)
            ctx.diag.Warn(loc, why + ": Integrator \"" + ctx.scene.integrator->Name() +
                                   "\" renders a subsurface material's interface alone, as " +
                                   (ctx.desc.pbrtVersion.version == 4
                                        ? "pbrt-v4 does (\"volpath\" follows"
                                        : "pbrt-v3 does (\"path\" and \"volpath\" follow") +
                                   " the light through it)");
    }
}

void NoteLightEffects(BuildContext &ctx, const std::string &why, const FileLoc &loc) {
    EffectSet &e = ctx.scene.features.effects;
    const Light &light = *ctx.scene.lights.back();
    std::string where = loc.Valid() ? why + " at " + loc.ToString() : why;
    e.lights.push_back({where, light.UsesSample() ? light.NumSamples() : 1});
    e.Enable(Effect::Shadows, why, loc);
    if (std::string(light.Name()) == "infinite")
        e.Enable(Effect::Environment, why, loc);
    else if (light.IsArea() || light.UsesSample())
        e.Enable(Effect::SoftShadows, why, loc);
}

void FinishEffects(BuildContext &ctx) {
    RenderScene &scene = ctx.scene;
    EffectSet &e = scene.features.effects;
    const bool bounces = e.Has(Effect::SpecularReflection) || e.Has(Effect::Refraction) ||
                         e.Has(Effect::GlossyReflection) || e.Has(Effect::GlossyTransmission) ||
                         e.Has(Effect::IndirectIllumination);
    e.maxUsefulDepth = bounces ? std::max(scene.trace.maxDepth, 1) : 1;
}

}  // namespace prism
