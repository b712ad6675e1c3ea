// glTF surface detail beyond the BRDF: normalTexture (a tangent-space normal map, with the
// primitive's TANGENT attribute when it has one) and alphaMode MASK / BLEND (cut-outs and
// stochastic transparency from the base colour's alpha), as the pbrt-style parameters build/
// reads ("normalmap", "normalscale", "tangent", "alpha", "alphamode", "alphacutoff", and
// "<map>texcoord" / "<map>transform" for TEXCOORD_1 and KHR_texture_transform).
#include <cmath>

#include "scene/gltf_converter.h"
#include "scene/param_builders.h"

namespace prism::gltf_internal {

using namespace reader;

// normalTexture → "string normalmap" (the image, read linearly), "float normalscale", and
// "normalmaptexcoord" / "normalmaptransform" for its texture coordinate set and
// KHR_texture_transform.
void GltfConverter::AddNormalMap(const tinygltf::Material &m, ParamSet &ps) {
    const tinygltf::NormalTextureInfo &nt = m.normalTexture;
    if (nt.index < 0 || size_t(nt.index) >= model_.textures.size()) return;
    const tinygltf::Texture &tex = model_.textures[size_t(nt.index)];
    if (tex.source < 0 || size_t(tex.source) >= model_.images.size()) return;
    std::string file = ImageFilename(tex.source);
    if (file.empty()) return;
    AddString(ps, "normalmap", file, loc_);
    AddFloat(ps, "normalscale", nt.scale, loc_);
    AddTexCoordParams(ps, "normalmap", nt.texCoord, nt.extensions, currentMaterial_);
}

// The base colour's alpha for a MASK or BLEND material: baseColorFactor's alpha times the
// alpha channel of baseColorTexture (a float "imagemap" of its alpha channel, scaled), or ""
// when there is no texture (the factor alone then decides).
std::string GltfConverter::AlphaTextureFor(int material) {
    auto it = alphaTextures_.find(material);
    if (it != alphaTextures_.end()) return it->second;
    const tinygltf::Material &m = model_.materials[size_t(material)];
    const auto &pbr = m.pbrMetallicRoughness;
    double factor = pbr.baseColorFactor.size() >= 4 ? pbr.baseColorFactor[3] : 1.0;
    std::string name;
    if (pbr.baseColorTexture.index >= 0 &&
        size_t(pbr.baseColorTexture.index) < model_.textures.size()) {
        const tinygltf::Texture &tex = model_.textures[size_t(pbr.baseColorTexture.index)];
        std::string file = tex.source >= 0 && size_t(tex.source) < model_.images.size()
                               ? ImageFilename(tex.source)
                               : std::string();
        if (!file.empty()) {
            TextureDesc t;
            t.type = "imagemap";
            t.isFloat = true;
            t.name = "gltf:material" + std::to_string(material) + ":alpha";
            t.loc = loc_;
            AddString(t.params, "filename", file, loc_);
            AddString(t.params, "channel", "alpha", loc_);
            AddFloat(t.params, "scale", factor, loc_);
            AddSamplerWrap(t.params, tex.sampler);
            name = t.name;
            desc_.textures.push_back(std::move(t));
        }
    }
    alphaTextures_[material] = name;
    return name;
}

// A primitive's shape parameters: cut-outs for MASK and stochastic transparency for BLEND
// materials (for camera and shadow rays; AddMesh turns blended emitters' shadows off), and
// the TANGENT attribute when its material has a normal map.
void GltfConverter::AddSurfaceParams(const tinygltf::Primitive &prim, size_t vertices, ParamSet &ps,
                                     const std::vector<Matrix4> *skinFrames) {
    if (prim.material < 0) return;
    const tinygltf::Material &m = model_.materials[size_t(prim.material)];
    if (m.alphaMode == "MASK" || m.alphaMode == "BLEND") {
        const bool mask = m.alphaMode == "MASK";
        std::string tex = AlphaTextureFor(prim.material);
        double factor = m.pbrMetallicRoughness.baseColorFactor.size() >= 4
                            ? m.pbrMetallicRoughness.baseColorFactor[3]
                            : 1.0;
        if (!tex.empty()) {
            AddTexture(ps, "alpha", tex, loc_);
            const auto &bt = m.pbrMetallicRoughness.baseColorTexture;
            AddTexCoordParams(ps, "alpha", bt.texCoord, bt.extensions, prim.material);
        } else if (mask) {
            AddFloat(ps, "alpha", factor >= m.alphaCutoff ? 1 : 0, loc_);
        } else {
            AddFloat(ps, "alpha", factor, loc_);
        }
        AddString(ps, "alphamode", mask ? "mask" : "blend", loc_);
        if (mask) AddFloat(ps, "alphacutoff", m.alphaCutoff, loc_);
    }
    if (m.normalTexture.index < 0) return;
    auto it = prim.attributes.find("TANGENT");
    if (it == prim.attributes.end()) return;
    AccessorView v = View(it->second, "TANGENT");
    if (v.components != 4) Fail("TANGENT accessor must be VEC4");
    CheckAttributeType(v, AttributeKind::Direction, "TANGENT");
    if (v.count != vertices) Fail("TANGENT and POSITION accessors differ in count");
    std::vector<double> t(4 * v.count);
    for (size_t i = 0; i < v.count; ++i)
        for (int c = 0; c < 4; ++c) {
            t[4 * i + size_t(c)] = Component(v, i, c);
            if (!std::isfinite(t[4 * i + size_t(c)]))
                Fail("TANGENT accessor contains a value that is not a finite number");
        }
    if (skinFrames && skinFrames->size() == v.count) {
        // A tangent is a direction on the surface: the skinned frame's linear part moves it,
        // and a mirroring frame flips the bitangent's sign (w).
        for (size_t i = 0; i < v.count; ++i) {
            const Matrix4 &m = (*skinFrames)[i];
            double *ti = &t[4 * i];
            double o[3];
            for (int r = 0; r < 3; ++r)
                o[r] = m.m[r][0] * ti[0] + m.m[r][1] * ti[1] + m.m[r][2] * ti[2];
            const double len = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            if (len > 0)
                for (int r = 0; r < 3; ++r) ti[r] = o[r] / len;
            if (m.Determinant3x3() < 0) ti[3] = -ti[3];
        }
    }
    AddFloats(ps, "tangent", t, loc_);
}

}  // namespace prism::gltf_internal
