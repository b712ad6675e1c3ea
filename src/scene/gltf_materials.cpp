// glTF materials, textures and images → pbrt-v3 materials and "imagemap" textures.
#include <algorithm>
#include <cmath>

#include "core/file_io.h"
#include "scene/gltf_converter.h"
#include "scene/param_builders.h"

namespace prism::gltf_internal {

using namespace reader;

namespace {

// glTF URIs are percent-encoded ("my%20texture.png").
std::string DecodeUri(const std::string &uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
            std::isxdigit((unsigned char)uri[i + 2])) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace

// The location of the "uri" in the glTF file `gltfPath` whose file is `path` (as tinygltf
// resolved it against the glTF's folder), or the whole file: for confinement errors.
FileLoc LocateUri(const std::string &gltfPath, const std::string &path) {
    std::string text;
    FileReadError error;
    if (!ReadFileContents(gltfPath, &text, &error, 64u << 20)) return FileLoc{gltfPath};
    const std::string dir = DirectoryOf(gltfPath);
    for (size_t at = text.find("\"uri\""); at != std::string::npos;
         at = text.find("\"uri\"", at + 5)) {
        size_t open = text.find('"', text.find(':', at + 5));
        if (open == std::string::npos) break;
        size_t close = text.find('"', open + 1);
        if (close == std::string::npos) break;
        std::string uri = DecodeUri(text.substr(open + 1, close - open - 1));
        if (uri == path || (dir.empty() ? uri : dir + "/" + uri) == path ||
            CanonicalPath(ResolveScenePath(dir, uri)) == CanonicalPath(path)) {
            int line = 1 + int(std::count(text.begin(), text.begin() + long(open), '\n'));
            size_t lineStart = text.rfind('\n', open);
            int col = int(open - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
            return FileLoc{gltfPath, line, col};
        }
    }
    return FileLoc{gltfPath};
}

std::string GltfConverter::ImageFilename(int imageIndex) {
    auto it = imageFilenames_.find(imageIndex);
    if (it != imageFilenames_.end()) return it->second;
    const tinygltf::Image &img = model_.images[size_t(imageIndex)];
    std::string filename;
    if (!img.uri.empty() && img.uri.compare(0, 5, "data:") != 0) {
        filename = DecodeUri(img.uri);
    } else if (!img.image.empty()) {
        EmbeddedImage e;
        e.name = img.name.empty() ? "image " + std::to_string(imageIndex) : img.name;
        e.mimeType = img.mimeType;
        e.bytes = img.image;
        filename = "embedded:" + std::to_string(desc_.embeddedImages.size());
        desc_.embeddedImages.push_back(std::move(e));
    }
    imageFilenames_[imageIndex] = filename;
    return filename;
}

// An "imagemap" texture for a glTF texture, shared by every material that uses it; "" if the
// texture has no usable image.
std::string GltfConverter::TextureFor(int textureIndex) {
    auto it = textureNames_.find(textureIndex);
    if (it != textureNames_.end()) return it->second;
    std::string name;
    if (textureIndex >= 0 && size_t(textureIndex) < model_.textures.size()) {
        const tinygltf::Texture &tex = model_.textures[size_t(textureIndex)];
        if (tex.source >= 0 && size_t(tex.source) < model_.images.size()) {
            std::string file = ImageFilename(tex.source);
            if (!file.empty()) {
                TextureDesc t;
                t.type = "imagemap";
                t.name = "gltf:texture" + std::to_string(textureIndex);
                t.loc = loc_;
                AddString(t.params, "filename", file, loc_);
                if (tex.sampler >= 0 && size_t(tex.sampler) < model_.samplers.size() &&
                    model_.samplers[size_t(tex.sampler)].wrapS ==
                        TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE)
                    AddString(t.params, "wrap", "clamp", loc_);
                name = t.name;
                desc_.textures.push_back(std::move(t));
            }
        }
    }
    if (name.empty())
        diag_.Warn(loc_,
                   "texture " + std::to_string(textureIndex) + " has no usable image; ignored");
    textureNames_[textureIndex] = name;
    return name;
}

// Metallic-roughness → pbrt-v3 materials (Whitted approximations):
//  - KHR_materials_transmission > 0 → "glass" (index = KHR_materials_ior, default 1.5;
//    Kt = base colour factor; roughness = glTF roughness² (alpha), remaproughness false: rough
//    glass for the distribution integrator, smooth for Whitted).
//  - metallic >= 0.5 → "metal" with eta = 1 and k = 2 sqrt(F0) / sqrt(1 - F0) per channel,
//    F0 = base colour factor clamped below 0.999: for eta = 1 the conductor Fresnel at normal
//    incidence is k² / (4 + k²), which this choice makes equal to F0. roughness = glTF
//    roughness² (alpha), remaproughness false. Base colour textures are not used for metals.
//    A metal whose metalness comes from a metallicRoughnessTexture and whose colour comes
//    from a baseColorTexture (e.g. DamagedHelmet) is treated as plastic instead: per-texel
//    metalness cannot be expressed, and an untextured tinted metal would hide the texture.
//  - otherwise → "plastic": Kd = base colour (texture × factor), Ks = 1, roughness = glTF
//    roughness², remaproughness false. Ks is 1, not 0.04, because pbrt's plastic already
//    multiplies Ks by a dielectric Fresnel term with eta 1.5, which is 0.04 at normal incidence.
//  - emissiveFactor × KHR_materials_emissive_strength → a "diffuse" area light on every shape
//    with the material, unless an emissiveTexture modulates it (not supported: a full-strength
//    emitter would be far brighter than intended, so emission is dropped with a warning).
void GltfConverter::ConvertMaterials() {
    for (size_t mi = 0; mi < model_.materials.size(); ++mi) {
        const tinygltf::Material &m = model_.materials[mi];
        const auto &pbr = m.pbrMetallicRoughness;
        MaterialDesc md;
        md.name = m.name.empty() ? "material " + std::to_string(mi) : m.name;
        md.loc = loc_;
        ParamSet &ps = md.params;
        double base[3] = {1, 1, 1};
        if (pbr.baseColorFactor.size() >= 3)
            for (int i = 0; i < 3; ++i) base[i] = Clamp(pbr.baseColorFactor[size_t(i)], 0.0, 1.0);
        double rough = Clamp(pbr.roughnessFactor, 0.0, 1.0);
        double alpha = rough * rough;
        double metallic = Clamp(pbr.metallicFactor, 0.0, 1.0);
        double transmission =
            ExtNumber(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0);
        if (transmission > 0) {
            md.type = "glass";
            AddFloat(ps, "index", ExtNumber(m.extensions, "KHR_materials_ior", "ior", 1.5), loc_);
            AddRGB(ps, "Kr", 1, 1, 1, loc_);
            AddRGB(ps, "Kt", base[0], base[1], base[2], loc_);
            if (alpha > 0) {
                AddFloat(ps, "roughness", alpha, loc_);
                AddBool(ps, "remaproughness", false, loc_);
            }
        } else if (metallic >= 0.5 &&
                   !(pbr.metallicRoughnessTexture.index >= 0 && pbr.baseColorTexture.index >= 0)) {
            md.type = "metal";
            double k[3];
            for (int i = 0; i < 3; ++i) {
                double f0 = std::min(base[i], 0.999);
                k[i] = 2 * std::sqrt(f0) / std::sqrt(1 - f0);
            }
            AddRGB(ps, "eta", 1, 1, 1, loc_);
            AddRGB(ps, "k", k[0], k[1], k[2], loc_);
            AddFloat(ps, "roughness", alpha, loc_);
            AddBool(ps, "remaproughness", false, loc_);
        } else {
            md.type = "plastic";
            std::string tex;
            if (pbr.baseColorTexture.index >= 0) tex = TextureFor(pbr.baseColorTexture.index);
            if (tex.empty()) {
                AddRGB(ps, "Kd", base[0], base[1], base[2], loc_);
            } else if (base[0] == 1 && base[1] == 1 && base[2] == 1) {
                AddTexture(ps, "Kd", tex, loc_);
            } else {
                // pbrt's imagemap has no tint: multiply with a "scale" texture.
                TextureDesc sc;
                sc.type = "scale";
                sc.name = "gltf:material" + std::to_string(mi) + ":baseColor";
                sc.loc = loc_;
                AddTexture(sc.params, "tex1", tex, loc_);
                AddRGB(sc.params, "tex2", base[0], base[1], base[2], loc_);
                AddTexture(ps, "Kd", sc.name, loc_);
                desc_.textures.push_back(std::move(sc));
            }
            AddRGB(ps, "Ks", 1, 1, 1, loc_);
            AddFloat(ps, "roughness", alpha, loc_);
            AddBool(ps, "remaproughness", false, loc_);
        }
        AddNormalMap(m, md.params);
        desc_.materials.push_back(std::move(md));

        int light = -1;
        double e[3] = {0, 0, 0};
        if (m.emissiveFactor.size() >= 3)
            for (int i = 0; i < 3; ++i) e[i] = std::max(0.0, m.emissiveFactor[size_t(i)]);
        double strength =
            ExtNumber(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1);
        if (e[0] > 0 || e[1] > 0 || e[2] > 0) {
            if (m.emissiveTexture.index >= 0) {
                diag_.Warn(loc_, "material \"" + desc_.materials.back().name +
                                     "\": emissive textures are not supported; emission ignored");
            } else {
                AreaLightDesc al;
                al.type = "diffuse";
                al.loc = loc_;
                AddRGB(al.params, "L", e[0] * strength, e[1] * strength, e[2] * strength, loc_);
                // OBJ/glTF carry no sample count: 16 stratified shadow rays give clean soft
                // shadows.
                AddInts(al.params, "nsamples", {16}, loc_);
                light = int(desc_.areaLights.size());
                desc_.areaLights.push_back(std::move(al));
            }
        }
        areaLightOfMaterial_.push_back(light);
    }
}

}  // namespace prism::gltf_internal
