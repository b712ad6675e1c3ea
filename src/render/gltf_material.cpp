#include "render/gltf_material.h"

#include <algorithm>
#include <cmath>

namespace prism {

RGB GltfDielectricF0(float ior, float specular, const RGB &specularColor) {
    float r = (ior - 1) / (ior + 1);
    RGB f0 = (specularColor * (r * r)).Clamped(0.f, 1.f);
    return f0 * specular;
}

void GltfMaterialParams::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    const RGB base = baseColor->Evaluate(tc).Clamped(0.f, 1.f);
    float m = metallic, r = roughness;
    if (metallicRoughness) {
        RGB mr = metallicRoughness->Evaluate(tc);
        m *= mr.b;  // glTF: metalness in B, roughness in G
        r *= mr.g;
    }
    m = Clamp(m, 0.f, 1.f);
    r = Clamp(r, 0.f, 1.f);
    const float alpha = r * r;
    const float t = Clamp(transmission, 0.f, 1.f);
    const RGB f0d = GltfDielectricF0(ior, specular, specularColor);
    const RGB f90d(Clamp(specular, 0.f, 1.f));

    BxDFLobes &l = b.AddPart(weight);
    l.gltfDiffuse = true;
    l.dielectricF0 = f0d;
    l.dielectricF90 = f90d;
    l.kd = base * ((1 - m) * (1 - t));
    l.coat = Clamp(clearcoat, 0.f, 1.f);
    Fresnel fr;
    fr.kind = FresnelKind::Schlick;
    fr.f0 = base * m + f0d * (1 - m);
    fr.f90 = RGB(m) + f90d * (1 - m);
    const RGB transmit = base * ((1 - m) * t);
    if (alpha <= SpecularMetalAlpha) {
        // Polished: a mirror and a straight-through transmission (the limit of the GGX lobes).
        l.kr = RGB(1);
        l.specularFresnel = fr;
        l.kt = transmit;
        l.eta = 1;
    } else {
        l.ks = RGB(1);
        l.glossyFresnel = fr;
        l.alphaX = l.alphaY = alpha;
        l.thinTransmit = transmit;
    }

    if (l.coat > 0) {
        const float cr = Clamp(clearcoatRoughness, 0.f, 1.f);
        const float ca = cr * cr;
        const float coatWeight = l.coat;
        Fresnel fc;
        fc.kind = FresnelKind::Schlick;
        fc.f0 = RGB(0.04f);
        fc.f90 = RGB(1);
        BxDFLobes &c = b.AddPart(weight);  // invalidates l
        if (ca <= SpecularMetalAlpha) {
            c.kr = RGB(coatWeight);
            c.specularFresnel = fc;
        } else {
            c.ks = RGB(coatWeight);
            c.glossyFresnel = fc;
            c.alphaX = c.alphaY = ca;
        }
    }
}

Vec2f UVTransformTexture::Map(Vec2f uv) const {
    const float u = uv.x, v = 1 - uv.y;  // glTF's coordinates
    const float c = std::cos(rotation_), s = std::sin(rotation_);
    const float su = scale_.x * u, sv = scale_.y * v;
    const float x = c * su + s * sv + offset_.x;
    const float y = -s * su + c * sv + offset_.y;
    return {x, 1 - y};
}

RGB UVTransformTexture::Evaluate(const TextureContext &c) const {
    TextureContext t = c;
    t.uv = Map(c.uv);
    // The footprint through the linear part of the map (v runs the other way in glTF's
    // coordinates, and back).
    const float co = std::cos(rotation_), si = std::sin(rotation_);
    auto lin = [&](float du, float dv, float *du2, float *dv2) {
        const float su = scale_.x * du, sv = -scale_.y * dv;
        *du2 = co * su + si * sv;
        *dv2 = -(-si * su + co * sv);
    };
    lin(c.dudx, c.dvdx, &t.dudx, &t.dvdx);
    lin(c.dudy, c.dvdy, &t.dudy, &t.dvdy);
    return child_->Evaluate(t);
}

bool GltfMaterial::MayReflectSpecularly() const {
    // Textured roughness may go either way; a smooth base or coat is a mirror.
    if (p_.metallicRoughness) return true;
    float a = p_.roughness * p_.roughness;
    float ca = p_.clearcoatRoughness * p_.clearcoatRoughness;
    return a <= SpecularMetalAlpha || (p_.clearcoat > 0 && ca <= SpecularMetalAlpha);
}

bool GltfMaterial::MayReflectGlossily() const {
    return p_.metallicRoughness || p_.roughness * p_.roughness > SpecularMetalAlpha ||
           (p_.clearcoat > 0 && p_.clearcoatRoughness * p_.clearcoatRoughness > SpecularMetalAlpha);
}

bool GltfMaterial::MayTransmitGlossily() const {
    return MayTransmit() &&
           (p_.metallicRoughness || p_.roughness * p_.roughness > SpecularMetalAlpha);
}

float GltfMaterial::AmbientOcclusion(const TextureContext &tc) const {
    if (!p_.occlusion) return 1;
    const float ao = std::clamp(p_.occlusion->Evaluate(tc).r, 0.f, 1.f);
    return 1 + p_.occlusionStrength * (ao - 1);
}

namespace {
TexturePtr ConstantRGB(RGB v) { return std::make_shared<ConstantTexture>(v); }
}  // namespace

// Material "gltf" (a Prism extension the glTF reader writes, usable in .pbrt files;
// material_list.inc): the glTF 2.0 metallic-roughness model. Parameters:
//   basecolor (rgb 1) x basecolormap, metallic (1), roughness (1) x metallicroughnessmap
//   (B: metallic, G: roughness), emissive (rgb 0) x emissivemap, occlusionmap with
//   occlusionstrength (1), ior (1.5), transmission (0), specular (1), specularcolor (rgb 1),
//   clearcoat (0), clearcoatroughness (0). Maps are named textures; "<map>transform" is
//   KHR_texture_transform as [offset.u offset.v rotation scale.u scale.v], "<map>texcoord" 1
//   reads the mesh's second uv set.
std::shared_ptr<const MaterialModel> CreateGltfMaterial(const MaterialParams &mp, const FileLoc &) {
    GltfMaterialParams g;
    const RGB baseFactor = mp.Spectrum("basecolor", RGB(1));
    if (TexturePtr t = mp.Map("basecolormap"))
        g.baseColor = std::make_shared<ScaleTexture>(t, ConstantRGB(baseFactor));
    else
        g.baseColor = ConstantRGB(baseFactor);
    g.metallic = mp.Float("metallic", 1.f);
    g.roughness = mp.Float("roughness", 1.f);
    g.metallicRoughness = mp.Map("metallicroughnessmap");
    const RGB emissive = mp.Spectrum("emissive", RGB(0));
    // Emission the material carries itself (the glTF reader turns untextured emission into an
    // area light on the mesh instead, which light samples reach).
    if (TexturePtr t = mp.Map("emissivemap")) {
        if (!emissive.IsBlack())
            g.emissive = std::make_shared<ScaleTexture>(t, ConstantRGB(emissive));
    } else if (!emissive.IsBlack()) {
        g.emissive = ConstantRGB(emissive);
    }
    g.occlusion = mp.Map("occlusionmap");
    g.occlusionStrength = mp.Float("occlusionstrength", 1.f);
    g.ior = mp.Float("ior", 1.5f);
    g.transmission = mp.Float("transmission", 0.f);
    g.specular = mp.Float("specular", 1.f);
    g.specularColor = mp.Spectrum("specularcolor", RGB(1));
    g.clearcoat = mp.Float("clearcoat", 0.f);
    g.clearcoatRoughness = mp.Float("clearcoatroughness", 0.f);
    return std::make_shared<GltfMaterial>(std::move(g));
}

}  // namespace prism
