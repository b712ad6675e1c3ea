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

}  // namespace prism
