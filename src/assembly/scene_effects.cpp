#include "assembly/scene_effects.h"

#include <algorithm>

#include "render/bsdf.h"

namespace prism {

namespace {

const ConstantTexture *AsConstant(const TexturePtr &t) {
    return dynamic_cast<const ConstantTexture *>(t.get());
}
// False only when the texture is absent or a constant black.
bool MaybeNonBlack(const TexturePtr &t) {
    if (!t) return false;
    const ConstantTexture *c = AsConstant(t);
    return !c || !c->Value().Clamped(0.f).IsBlack();
}
// False only when the (float) texture is absent or the constant 0.
bool MaybeNonZero(const TexturePtr &t) {
    if (!t) return false;
    const ConstantTexture *c = AsConstant(t);
    return !c || c->Value().r != 0;
}
// Rough glass: either roughness may be non-zero (pbrt-v3 GlassMaterial).
bool MaybeRoughGlass(const Material &m) {
    return MaybeNonZero(m.uRoughness) || MaybeNonZero(m.vRoughness);
}

}  // namespace

bool MayReflectGlossily(const Material &m) {
    switch (m.kind) {
        case Material::Kind::Plastic:
        case Material::Kind::Uber:
            return MaybeNonBlack(m.Ks);
        case Material::Kind::Metal: {
            const ConstantTexture *cu = AsConstant(m.uRoughness), *cv = AsConstant(m.vRoughness);
            if (!cu || !cv) return true;
            float au = m.remapRoughness ? RoughnessToAlpha(cu->Value().r) : cu->Value().r;
            float av = m.remapRoughness ? RoughnessToAlpha(cv->Value().r) : cv->Value().r;
            return std::max(au, av) > SpecularMetalAlpha;
        }
        case Material::Kind::Substrate:
            return MaybeNonBlack(m.Kd) || MaybeNonBlack(m.Ks);
        case Material::Kind::Translucent:
            return MaybeNonBlack(m.Ks) && MaybeNonBlack(m.reflect);
        case Material::Kind::Glass:
            return MaybeRoughGlass(m) && MaybeNonBlack(m.Kr);
        case Material::Kind::Mix:
            return MayReflectGlossily(*m.mix1) || MayReflectGlossily(*m.mix2);
        case Material::Kind::Gltf:
            return m.gltf.metallicRoughness ||
                   m.gltf.roughness * m.gltf.roughness > SpecularMetalAlpha ||
                   (m.gltf.clearcoat > 0 &&
                    m.gltf.clearcoatRoughness * m.gltf.clearcoatRoughness > SpecularMetalAlpha);
        default:
            return false;
    }
}

bool MayTransmitGlossily(const Material &m) {
    switch (m.kind) {
        case Material::Kind::Translucent:
            return MaybeNonBlack(m.Ks) && MaybeNonBlack(m.transmit);
        case Material::Kind::Glass:
            return MaybeRoughGlass(m) && MaybeNonBlack(m.Kt);
        case Material::Kind::Mix:
            return MayTransmitGlossily(*m.mix1) || MayTransmitGlossily(*m.mix2);
        case Material::Kind::Gltf:
            return m.MayTransmit() && (m.gltf.metallicRoughness ||
                                       m.gltf.roughness * m.gltf.roughness > SpecularMetalAlpha);
        default:
            return false;
    }
}

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
    bool roughGlassOnly = false;
    if (distribution && m.kind == Material::Kind::Glass) {
        const ConstantTexture *cu = AsConstant(m.uRoughness), *cv = AsConstant(m.vRoughness);
        roughGlassOnly = cu && cv && (cu->Value().r != 0 || cv->Value().r != 0);
    }
    if (m.MayReflectSpecularly() && !roughGlassOnly) e.Enable(Effect::SpecularReflection, why, loc);
    if (m.MayTransmit() && !roughGlassOnly) e.Enable(Effect::Refraction, why, loc);
    if (distribution) {
        if (MayReflectGlossily(m)) e.Enable(Effect::GlossyReflection, why, loc);
        if (MayTransmitGlossily(m)) e.Enable(Effect::GlossyTransmission, why, loc);
    }
    if (m.SurfaceNeeds() & NeedUV) e.Enable(Effect::Textures, why + " (textured)", loc);
    if (m.bump) e.Enable(Effect::BumpMapping, why + " (bumpmap)", loc);
    if (m.normalMap) e.Enable(Effect::NormalMapping, why + " (normal map)", loc);
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
    e.maxUsefulDepth = bounces ? std::max(scene.maxDepth, 1) : 1;
}

}  // namespace prism
