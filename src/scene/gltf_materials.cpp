// glTF materials, textures and images → pbrt-v3 materials and "imagemap" textures.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string_view>

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
FileLoc LocateUri(const std::string &gltfPath, const std::string &path, std::string *written) {
    // Not found: the file's name alone, never the folders it was resolved in.
    if (written) *written = std::filesystem::path(path).filename().string();
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
            if (written) *written = text.substr(open + 1, close - open - 1);
            return FileLoc{gltfPath, line, col};
        }
    }
    return FileLoc{gltfPath};
}

namespace {

size_t SkipSpace(std::string_view j, size_t i) {
    while (i < j.size() && (j[i] == ' ' || j[i] == '\t' || j[i] == '\n' || j[i] == '\r')) ++i;
    return i;
}

// The end of the string starting at the quote j[i] (one past its closing quote).
size_t SkipString(std::string_view j, size_t i) {
    for (++i; i < j.size(); ++i) {
        if (j[i] == '\\')
            ++i;
        else if (j[i] == '"')
            return i + 1;
    }
    return j.size();
}

// One past the JSON value starting at j[i]; brackets are counted, not recursed into.
size_t SkipValue(std::string_view j, size_t i) {
    if (i >= j.size()) return i;
    if (j[i] == '"') return SkipString(j, i);
    if (j[i] != '[' && j[i] != '{') {
        while (i < j.size() && j[i] != ',' && j[i] != '}' && j[i] != ']') ++i;
        return i;
    }
    int depth = 0;
    while (i < j.size()) {
        const char c = j[i];
        if (c == '"') {
            i = SkipString(j, i);
            continue;
        }
        if (c == '[' || c == '{') ++depth;
        if ((c == ']' || c == '}') && --depth == 0) return i + 1;
        ++i;
    }
    return i;
}

// The offset in `json` of the value the JSON pointer `pointer` ("/nodes/3/mesh") names, or
// npos. Object keys are compared as written (glTF's keys need no escapes).
size_t FindJsonPointer(std::string_view json, const std::string &pointer) {
    size_t i = SkipSpace(json, 0);
    size_t from = 1;
    while (from <= pointer.size() && pointer.size() > 0) {
        size_t to = pointer.find('/', from);
        if (to == std::string::npos) to = pointer.size();
        const std::string_view token = std::string_view(pointer).substr(from, to - from);
        from = to + 1;
        if (i >= json.size()) return std::string_view::npos;
        if (json[i] == '{') {
            i = SkipSpace(json, i + 1);
            while (true) {
                if (i >= json.size() || json[i] != '"') return std::string_view::npos;
                const size_t keyEnd = SkipString(json, i);
                const std::string_view key = json.substr(i + 1, keyEnd - i - 2);
                i = SkipSpace(json, keyEnd);
                if (i >= json.size() || json[i] != ':') return std::string_view::npos;
                i = SkipSpace(json, i + 1);
                if (key == token) break;
                i = SkipSpace(json, SkipValue(json, i));
                if (i >= json.size() || json[i] != ',') return std::string_view::npos;
                i = SkipSpace(json, i + 1);
            }
        } else if (json[i] == '[') {
            if (token.empty() || token.size() > 9 ||
                !std::all_of(token.begin(), token.end(),
                             [](char c) { return c >= '0' && c <= '9'; }))
                return std::string_view::npos;
            const long index = std::stol(std::string(token));
            i = SkipSpace(json, i + 1);
            for (long k = 0; k < index; ++k) {
                if (i >= json.size() || json[i] == ']') return std::string_view::npos;
                i = SkipSpace(json, SkipValue(json, i));
                if (i >= json.size() || json[i] != ',') return std::string_view::npos;
                i = SkipSpace(json, i + 1);
            }
            if (i >= json.size() || json[i] == ']') return std::string_view::npos;
        } else {
            return std::string_view::npos;
        }
    }
    return i;
}

}  // namespace

FileLoc LocateJsonPointer(const std::string &gltfPath, const std::string &pointer) {
    FileLoc loc{gltfPath};
    // A .glb's JSON is one line inside a binary file: the pointer in the message says where.
    if (pointer.empty() || LowerExtension(gltfPath) == ".glb") return loc;
    std::string text;
    FileReadError error;
    if (!ReadFileContents(gltfPath, &text, &error, 64u << 20)) return loc;
    const size_t at = FindJsonPointer(text, pointer);
    if (at == std::string_view::npos || at >= text.size()) return loc;
    loc.line = 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
    const size_t lineStart = text.rfind('\n', at);
    loc.column = int(at - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
    return loc;
}

void GltfConverter::Fail(const std::string &msg) const {
    if (where_.empty()) throw SceneError(loc_, msg);
    throw SceneError(LocateJsonPointer(loc_.file, where_), msg + " (at " + where_ + ")");
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

void GltfConverter::AddSamplerWrap(ParamSet &ps, int sampler) {
    if (sampler < 0 || size_t(sampler) >= model_.samplers.size()) return;
    const tinygltf::Sampler &smp = model_.samplers[size_t(sampler)];
    auto add = [&](const char *param, int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE)
            AddString(ps, param, "clamp", loc_);
        else if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
            AddString(ps, param, "mirror", loc_);
    };
    add("wraps", smp.wrapS);
    add("wrapt", smp.wrapT);
}

// An "imagemap" texture for a glTF texture, shared by every material that uses it; "" if the
// texture has no usable image. `linear`: the image holds data (metallicRoughness, occlusion),
// not sRGB colours.
std::string GltfConverter::TextureFor(int textureIndex, bool linear) {
    // In 64 bits: the index is the file's (2^31 - 1 would overflow an int's -2 - index).
    const int64_t key = linear ? -2 - int64_t(textureIndex) : int64_t(textureIndex);
    auto it = textureNames_.find(key);
    if (it != textureNames_.end()) return it->second;
    std::string name;
    if (textureIndex >= 0 && size_t(textureIndex) < model_.textures.size()) {
        const tinygltf::Texture &tex = model_.textures[size_t(textureIndex)];
        if (tex.source >= 0 && size_t(tex.source) < model_.images.size()) {
            std::string file = ImageFilename(tex.source);
            if (!file.empty()) {
                TextureDesc t;
                t.type = "imagemap";
                t.name = "gltf:texture" + std::to_string(textureIndex) + (linear ? ":linear" : "");
                t.loc = loc_;
                AddString(t.params, "filename", file, loc_);
                if (linear) AddBool(t.params, "gamma", false, loc_);
                AddSamplerWrap(t.params, tex.sampler);
                // Pixel-art samplers (magFilter and minFilter NEAREST) look texels up
                // unfiltered; every other texture is EWA-filtered (docs/MATERIALS.md).
                if (tex.sampler >= 0 && size_t(tex.sampler) < model_.samplers.size() &&
                    model_.samplers[size_t(tex.sampler)].magFilter ==
                        TINYGLTF_TEXTURE_FILTER_NEAREST &&
                    model_.samplers[size_t(tex.sampler)].minFilter ==
                        TINYGLTF_TEXTURE_FILTER_NEAREST)
                    AddString(t.params, "filter", "point", loc_);
                name = t.name;
                desc_.textures.push_back(std::move(t));
            }
        }
    }
    if (name.empty())
        diag_.Warn(loc_,
                   "texture " + std::to_string(textureIndex) + " has no usable image; ignored");
    textureNames_[key] = name;
    return name;
}

namespace {

// A number array in a glTF extension object, or `def`.
std::vector<double> ExtNumbers(const tinygltf::ExtensionMap &ext, const char *extName,
                               const char *key, std::vector<double> def) {
    auto it = ext.find(extName);
    if (it == ext.end() || !it->second.IsObject() || !it->second.Has(key)) return def;
    const tinygltf::Value &v = it->second.Get(key);
    if (!v.IsArray() || v.ArrayLen() != def.size()) return def;
    std::vector<double> out(def.size());
    for (size_t i = 0; i < def.size(); ++i) {
        const tinygltf::Value &e = v.Get(int(i));
        out[i] = e.IsNumber() || e.IsInt() ? e.GetNumberAsDouble() : def[i];
    }
    return out;
}

}  // namespace

int GltfConverter::TexCoordOf(int texCoord, const tinygltf::ExtensionMap &ext, int material) {
    texCoord = int(ExtNumber(ext, "KHR_texture_transform", "texCoord", texCoord));
    if (texCoord != 0 && texCoord != 1) {
        if (warnedTexCoord_++ == 0)
            diag_.Warn(loc_, "texture coordinate set " + std::to_string(texCoord) +
                                 " is read as TEXCOORD_0 (Prism reads sets 0 and 1)");
        return 0;
    }
    if (texCoord == 1 && material >= 0) materialsUsingTexCoord1_.insert(material);
    return texCoord;
}

void GltfConverter::AddTexCoordParams(ParamSet &ps, const std::string &param, int texCoord,
                                      const tinygltf::ExtensionMap &ext, int material) {
    const char *tt = "KHR_texture_transform";
    if (TexCoordOf(texCoord, ext, material) == 1) AddInts(ps, param + "texcoord", {1}, loc_);
    if (ext.count(tt)) {
        std::vector<double> off = ExtNumbers(ext, tt, "offset", {0, 0});
        std::vector<double> sc = ExtNumbers(ext, tt, "scale", {1, 1});
        double rot = ExtNumber(ext, tt, "rotation", 0);
        Param p = MakeParam(ParamType::Float, param + "transform", loc_);
        p.numbers = {off[0], off[1], rot, sc[0], sc[1]};
        ps.Add(std::move(p));
    }
}

// A texture map of a "gltf" material: "<param>" names the imagemap, "<param>texcoord" 1 reads
// TEXCOORD_1, "<param>transform" holds KHR_texture_transform. False when the texture has no
// usable image.
bool GltfConverter::AddMap(ParamSet &ps, const std::string &param, int textureIndex, int texCoord,
                           const tinygltf::ExtensionMap &ext, bool linear) {
    if (textureIndex < 0) return false;
    std::string tex = TextureFor(textureIndex, linear);
    if (tex.empty()) return false;
    AddTexture(ps, param, tex, loc_);
    AddTexCoordParams(ps, param, texCoord, ext, currentMaterial_);
    return true;
}

// Metallic-roughness → Prism's "gltf" material (render/gltf_material.h), which evaluates the
// specification's BRDF with KHR_materials_ior, _specular, _transmission, _clearcoat; the
// texture maps (baseColor sRGB, metallicRoughness and occlusion linear) with their texture
// coordinate set and KHR_texture_transform. Emission (emissiveFactor × emissiveTexture ×
// KHR_materials_emissive_strength) becomes a "diffuse" area light on every shape with the
// material, textured ("emissionmap") when there is an emissiveTexture: light samples reach it
// and every ray that hits it sees it (docs/MATERIALS.md).
void GltfConverter::ConvertMaterials() {
    for (size_t mi = 0; mi < model_.materials.size(); ++mi) {
        const Where where(*this, "/materials/" + std::to_string(mi));
        const tinygltf::Material &m = model_.materials[mi];
        const auto &pbr = m.pbrMetallicRoughness;
        currentMaterial_ = int(mi);
        MaterialDesc md;
        md.name = m.name.empty() ? "material " + std::to_string(mi) : m.name;
        md.loc = loc_;
        md.type = "gltf";
        ParamSet &ps = md.params;
        double base[3] = {1, 1, 1};
        if (pbr.baseColorFactor.size() >= 3)
            for (int i = 0; i < 3; ++i) base[i] = Clamp(pbr.baseColorFactor[size_t(i)], 0.0, 1.0);
        AddRGB(ps, "basecolor", base[0], base[1], base[2], loc_);
        AddMap(ps, "basecolormap", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
               pbr.baseColorTexture.extensions, false);
        AddFloat(ps, "metallic", Clamp(pbr.metallicFactor, 0.0, 1.0), loc_);
        AddFloat(ps, "roughness", Clamp(pbr.roughnessFactor, 0.0, 1.0), loc_);
        AddMap(ps, "metallicroughnessmap", pbr.metallicRoughnessTexture.index,
               pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions,
               true);
        if (AddMap(ps, "occlusionmap", m.occlusionTexture.index, m.occlusionTexture.texCoord,
                   m.occlusionTexture.extensions, true))
            AddFloat(ps, "occlusionstrength", m.occlusionTexture.strength, loc_);
        const auto &ext = m.extensions;
        AddFloat(ps, "ior", ExtNumber(ext, "KHR_materials_ior", "ior", 1.5), loc_);
        AddFloat(ps, "transmission",
                 ExtNumber(ext, "KHR_materials_transmission", "transmissionFactor", 0), loc_);
        AddFloat(ps, "specular", ExtNumber(ext, "KHR_materials_specular", "specularFactor", 1),
                 loc_);
        std::vector<double> sc =
            ExtNumbers(ext, "KHR_materials_specular", "specularColorFactor", {1, 1, 1});
        AddRGB(ps, "specularcolor", sc[0], sc[1], sc[2], loc_);
        AddFloat(ps, "clearcoat", ExtNumber(ext, "KHR_materials_clearcoat", "clearcoatFactor", 0),
                 loc_);
        AddFloat(ps, "clearcoatroughness",
                 ExtNumber(ext, "KHR_materials_clearcoat", "clearcoatRoughnessFactor", 0), loc_);

        int light = -1;
        double e[3] = {0, 0, 0};
        if (m.emissiveFactor.size() >= 3)
            for (int i = 0; i < 3; ++i) e[i] = std::max(0.0, m.emissiveFactor[size_t(i)]);
        double strength =
            ExtNumber(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1);
        if (e[0] > 0 || e[1] > 0 || e[2] > 0) {
            // An area light on every shape with the material: L = factor × strength, times the
            // emissive texture ("emissionmap", with its texture coordinate set and transform)
            // when there is one. Light samples reach it; camera and recursive rays see it.
            AreaLightDesc al;
            al.type = "diffuse";
            al.loc = loc_;
            AddRGB(al.params, "L", e[0] * strength, e[1] * strength, e[2] * strength, loc_);
            AddMap(al.params, "emissionmap", m.emissiveTexture.index, m.emissiveTexture.texCoord,
                   m.emissiveTexture.extensions, false);
            // OBJ/glTF carry no sample count: 16 stratified shadow rays give clean soft
            // shadows.
            AddInts(al.params, "nsamples", {16}, loc_);
            light = int(desc_.areaLights.size());
            desc_.areaLights.push_back(std::move(al));
        }
        AddNormalMap(m, md.params);
        desc_.materials.push_back(std::move(md));
        areaLightOfMaterial_.push_back(light);
    }
}

int GltfConverter::DefaultMaterial() {
    if (defaultMaterial_ < 0) {
        // The "gltf" material's defaults are glTF's: no parameters needed.
        MaterialDesc md;
        md.name = "glTF default material";
        md.loc = loc_;
        md.type = "gltf";
        defaultMaterial_ = int(desc_.materials.size());
        desc_.materials.push_back(std::move(md));
        areaLightOfMaterial_.push_back(-1);
    }
    return defaultMaterial_;
}

}  // namespace prism::gltf_internal
