// Structure-aware fuzz entries (fuzz_entry.h): the input bytes are not the file but the choices
// of a generator that writes a well-formed file, so that every run gets past the syntax and
// reaches what lies behind it: the glTF converter (node graphs, accessors, buffer views,
// materials, cameras, lights) and the texture graph (textures referring to textures, their
// mappings and parameters, evaluated by a tiny render). The bytes are read one choice at a
// time; when they run out every further choice is 0, so any input makes a complete file (and
// choice 0 is the ordinary one: the first entry of each table, the field present and valid).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "assembly/build_scene.h"
#include "core/error.h"
#include "core/memory.h"
#include "fuzz_entry.h"
#include "render/renderer.h"
#include "scene/gltf_reader.h"
#include "scene/pbrt_parser.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism::fuzz {

namespace {

using test::Base64;

class Choices {
  public:
    Choices(const uint8_t *data, size_t size) : data_(data), size_(size) {}
    uint32_t Byte() { return at_ < size_ ? data_[at_++] : 0u; }
    // A value in [0, n).
    uint32_t Below(uint32_t n) { return n ? Byte() % n : 0; }
    bool Flip() { return Byte() & 1u; }
    // A count in [0, n], usually small.
    int Count(int n) { return int(Below(uint32_t(n) + 1)); }
    // An index into n things: mostly valid, sometimes -1, n or far out.
    int Index(int n) {
        const uint32_t b = Byte();
        if (b < 200) return n > 0 ? int(b % uint32_t(n)) : 0;
        if (b < 220) return -1;
        if (b < 240) return n;
        return b < 250 ? 1000000 : 2147483647;
    }
    // A number from a table of ordinary and extreme values.
    std::string Number() {
        static const char *const kNumbers[] = {
            "1",     "0",     "-1",   "0.5",        "2",    "3",     "10",    "0.001",
            "-0.0",  "1e-30", "1e30", "-1e30",      "3e38", "1e300", "1e-45", "255",
            "65535", "0.25",  "100",  "4294967296", "-7.5", "0.75",  "1.5",   "1e9"};
        return kNumbers[Below(uint32_t(std::size(kNumbers)))];
    }
    // An integer from a table of ordinary and extreme values.
    std::string Integer() {
        static const char *const kIntegers[] = {"1",  "0",   "2",           "8",
                                                "-1", "100", "1000000",     "2147483647",
                                                "-5", "30",  "-2147483648", "3"};
        return kIntegers[Below(uint32_t(std::size(kIntegers)))];
    }
    std::string Numbers(int n) {
        std::string s;
        for (int i = 0; i < n; ++i) s += (i ? ", " : "") + Number();
        return s;
    }
    std::string Bytes(size_t n) {
        std::string s;
        for (size_t i = 0; i < n; ++i) s += char(Byte());
        return s;
    }

  private:
    const uint8_t *data_;
    size_t size_, at_ = 0;
};

const fs::path &Scratch() {
    static const fs::path dir = [] {
        fs::path p = fs::temp_directory_path() / ("prism-fuzz-s" + std::to_string(getpid()));
        fs::create_directories(p);
        return p;
    }();
    return dir;
}

// A JSON array of `n` items made by `item(i)`.
template <class F>
std::string Array(int n, F item) {
    std::string s = "[";
    for (int i = 0; i < n; ++i) s += (i ? ", " : "") + item(i);
    return s + "]";
}

// A glTF 2.0 file from the choices: its objects refer to each other by index (mostly valid).
std::string GltfFromChoices(Choices &c) {
    const int nBuffers = c.Count(2), nViews = c.Count(4), nAccessors = c.Count(8);
    const int nMeshes = c.Count(3), nMaterials = c.Count(3), nTextures = c.Count(2);
    const int nImages = c.Count(2), nCameras = c.Count(2), nLights = c.Count(2);
    const int nNodes = c.Count(8);
    std::string j = "{\"asset\": {\"version\": \"2.0\"}";
    j += ", \"buffers\": " + Array(nBuffers, [&](int) {
             const size_t n = size_t(1 + c.Below(4)) * 48;
             std::string data = c.Bytes(n);
             std::string length = c.Below(8) != 7 ? std::to_string(n) : c.Number();
             std::string uri = c.Below(16) == 15
                                   ? "missing.bin"
                                   : "data:application/octet-stream;base64," + Base64(data);
             return "{\"byteLength\": " + length + ", \"uri\": \"" + uri + "\"}";
         });
    j += ", \"bufferViews\": " + Array(nViews, [&](int) {
             std::string v = "{\"buffer\": " + std::to_string(c.Index(nBuffers)) +
                             ", \"byteLength\": " + std::to_string(c.Below(200));
             if (c.Flip()) v += ", \"byteOffset\": " + std::to_string(c.Below(64));
             if (c.Below(4) == 3)
                 v += ", \"byteStride\": " + std::to_string(4 * c.Below(10) + c.Below(4) / 3);
             return v + "}";
         });
    // Mostly what the reader takes (float VEC3 and VEC2, integer SCALAR indices), sometimes
    // what it must refuse.
    static const char *const kTypes[] = {"VEC3", "VEC3",   "VEC2", "SCALAR", "SCALAR", "VEC4",
                                         "MAT4", "VEC3",   "VEC2", "SCALAR", "VEC3",   "VEC2",
                                         "VEC3", "SCALAR", "VEC4", "BOGUS"};
    static const int kComponents[] = {5126, 5126, 5126, 5123, 5125, 5121, 5120, 5122,
                                      5126, 5126, 5123, 5125, 5126, 5126, 5121, 1};
    j += ", \"accessors\": " + Array(nAccessors, [&](int) {
             std::string a = "{\"componentType\": " +
                             std::to_string(kComponents[c.Below(std::size(kComponents))]) +
                             ", \"count\": " + std::to_string(c.Below(12)) + ", \"type\": \"" +
                             kTypes[c.Below(std::size(kTypes))] + "\"";
             if (c.Below(8) != 7) a += ", \"bufferView\": " + std::to_string(c.Index(nViews));
             if (c.Below(4) == 0) a += ", \"byteOffset\": " + std::to_string(c.Below(32));
             if (c.Below(4) == 0) a += ", \"normalized\": true";
             if (c.Below(6) == 0)
                 a += ", \"min\": [" + c.Numbers(3) + "], \"max\": [" + c.Numbers(3) + "]";
             if (c.Below(16) == 0)
                 a += ", \"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 0, "
                      "\"componentType\": 5123}, \"values\": {\"bufferView\": 0}}";
             return a + "}";
         });
    j += ", \"meshes\": " + Array(nMeshes, [&](int) {
             return "{\"primitives\": " +
                    Array(1 + c.Count(1),
                          [&](int) {
                              std::string p = "{\"attributes\": {\"POSITION\": " +
                                              std::to_string(c.Index(nAccessors));
                              for (const char *attr :
                                   {"NORMAL", "TEXCOORD_0", "TEXCOORD_1", "TANGENT"})
                                  if (c.Below(3) == 0)
                                      p += std::string(", \"") + attr +
                                           "\": " + std::to_string(c.Index(nAccessors));
                              p += "}";
                              if (c.Flip())
                                  p += ", \"indices\": " + std::to_string(c.Index(nAccessors));
                              if (c.Flip())
                                  p += ", \"material\": " + std::to_string(c.Index(nMaterials));
                              if (c.Below(6) == 0) p += ", \"mode\": " + std::to_string(c.Below(8));
                              return p + "}";
                          }) +
                    "}";
         });
    auto textureInfo = [&] {
        std::string t = "{\"index\": " + std::to_string(c.Index(nTextures));
        if (c.Below(4) == 0) t += ", \"texCoord\": " + std::to_string(c.Below(3));
        if (c.Below(6) == 0)
            t += ", \"extensions\": {\"KHR_texture_transform\": {\"offset\": [" + c.Numbers(2) +
                 "], \"rotation\": " + c.Number() + ", \"scale\": [" + c.Numbers(2) + "]}}";
        return t + "}";
    };
    static const char *const kAlpha[] = {"OPAQUE", "MASK", "BLEND", "bogus"};
    j +=
        ", \"materials\": " + Array(nMaterials, [&](int) {
            std::string m = "{\"pbrMetallicRoughness\": {\"baseColorFactor\": [" + c.Numbers(4) +
                            "], \"metallicFactor\": " + c.Number() +
                            ", \"roughnessFactor\": " + c.Number();
            if (c.Flip()) m += ", \"baseColorTexture\": " + textureInfo();
            if (c.Below(3) == 0) m += ", \"metallicRoughnessTexture\": " + textureInfo();
            m += "}";
            if (c.Below(3) == 0) m += ", \"normalTexture\": " + textureInfo();
            if (c.Below(3) == 0) m += ", \"emissiveFactor\": [" + c.Numbers(3) + "]";
            if (c.Below(3) == 0)
                m += std::string(", \"alphaMode\": \"") + kAlpha[c.Below(4)] +
                     "\", \"alphaCutoff\": " + c.Number();
            if (c.Below(4) == 0) m += ", \"doubleSided\": true";
            if (c.Below(3) == 0)
                m +=
                    ", \"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": " +
                    c.Number() + "}, \"KHR_materials_ior\": {\"ior\": " + c.Number() +
                    "}, \"KHR_materials_emissive_strength\": {\"emissiveStrength\": " + c.Number() +
                    "}}";
            return m + "}";
        });
    j += ", \"textures\": " + Array(nTextures, [&](int) {
             return "{\"source\": " + std::to_string(c.Index(nImages)) + "}";
         });
    j += ", \"images\": " + Array(nImages, [&](int) {
             if (c.Flip())
                 return "{\"bufferView\": " + std::to_string(c.Index(nViews)) +
                        ", \"mimeType\": \"image/png\"}";
             return "{\"uri\": \"data:image/png;base64," + Base64(c.Bytes((1 + c.Below(4)) * 16)) +
                    "\"}";
         });
    j += ", \"cameras\": " + Array(nCameras, [&](int) {
             if (!c.Flip())
                 return "{\"type\": \"perspective\", \"perspective\": {\"yfov\": " + c.Number() +
                        ", \"znear\": " + c.Number() + ", \"aspectRatio\": " + c.Number() + "}}";
             return "{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": " + c.Number() +
                    ", \"ymag\": " + c.Number() + ", \"znear\": " + c.Number() +
                    ", \"zfar\": " + c.Number() + "}}";
         });
    static const char *const kLights[] = {"point", "spot", "directional", "area"};
    j += ", \"extensions\": {\"KHR_lights_punctual\": {\"lights\": " +
         Array(nLights,
               [&](int) {
                   std::string l = std::string("{\"type\": \"") + kLights[c.Below(4)] +
                                   "\", \"color\": [" + c.Numbers(3) +
                                   "], \"intensity\": " + c.Number();
                   if (c.Flip()) l += ", \"range\": " + c.Number();
                   if (c.Flip())
                       l += ", \"spot\": {\"innerConeAngle\": " + c.Number() +
                            ", \"outerConeAngle\": " + c.Number() + "}";
                   return l + "}";
               }) +
         "}}";
    j += ", \"nodes\": " + Array(nNodes, [&](int) {
             std::string n = "{\"name\": \"n\"";
             if (c.Flip()) n += ", \"mesh\": " + std::to_string(c.Index(nMeshes));
             if (c.Below(4) == 0) n += ", \"camera\": " + std::to_string(c.Index(nCameras));
             if (c.Below(4) == 0)
                 n += ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": " +
                      std::to_string(c.Index(nLights)) + "}}";
             if (c.Flip())
                 n += ", \"children\": " +
                      Array(c.Count(3), [&](int) { return std::to_string(c.Index(nNodes)); });
             switch (c.Below(4)) {
                 case 1:
                     n += ", \"matrix\": [" + c.Numbers(16) + "]";
                     break;
                 case 2:
                     n += ", \"translation\": [" + c.Numbers(3) + "], \"rotation\": [" +
                          c.Numbers(4) + "], \"scale\": [" + c.Numbers(3) + "]";
                     break;
                 case 3:
                     n += ", \"scale\": [" + c.Numbers(c.Below(5)) + "]";
                     break;
                 default:
                     break;
             }
             return n + "}";
         });
    if (c.Below(8) != 7) {
        j += ", \"scenes\": " + Array(1 + c.Count(1), [&](int) {
                 return "{\"nodes\": " +
                        Array(c.Count(3), [&](int) { return std::to_string(c.Index(nNodes)); }) +
                        "}";
             });
        j += ", \"scene\": " + std::to_string(c.Index(2));
    }
    // An unsimulated extension used (a warning) and a simulated one required; an unsimulated
    // required one is refused at once (GltfReader tests), which would leave nothing to fuzz.
    if (c.Below(8) == 0)
        j += ", \"extensionsUsed\": [\"KHR_draco_mesh_compression\"], \"extensionsRequired\": "
             "[\"KHR_lights_punctual\"]";
    return j + "}\n";
}

// A pbrt scene from the choices: a graph of float and spectrum textures, each referring to
// earlier ones (sometimes to later, undefined or itself), under transforms, used by the
// materials of a sphere and a quad with uv.
std::string TexturesFromChoices(Choices &c) {
    static const char *const kTypes[] = {"constant", "scale", "mix",      "checkerboard", "bilerp",
                                         "uv",       "dots",  "fbm",      "wrinkled",     "windy",
                                         "marble",   "ptex",  "imagemap", "bogus"};
    static const char *const kTexParams[] = {"tex1",  "tex2",   "amount",  "tex",
                                             "scale", "inside", "outside", "value"};
    static const char *const kMappings[] = {"uv", "spherical", "cylindrical", "planar", "bogus"};
    const int n = 1 + c.Count(23);
    auto name = [&](int i) { return "t" + std::to_string(i); };
    std::string s =
        "LookAt 0 0 4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
        "Film \"image\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
        "Sampler \"random\" \"integer pixelsamples\" 1\nWorldBegin\n"
        "LightSource \"point\" \"rgb I\" [5 5 5] \"point from\" [0 2 4]\n";
    for (int i = 0; i < n; ++i) {
        switch (c.Below(8)) {
            case 1:
                s += "Scale " + c.Number() + " " + c.Number() + " " + c.Number() + "\n";
                break;
            case 2:
                s += "Rotate " + c.Number() + " 0 1 0\n";
                break;
            case 3:
                s += "Translate " + c.Number() + " 0 0\n";
                break;
            default:
                break;
        }
        const bool isFloat = c.Flip();
        const char *type = kTypes[c.Below(std::size(kTypes))];
        s += "Texture \"" + name(i) + "\" \"" + (isFloat ? "float" : "spectrum") + "\" \"" + type +
             "\"";
        for (int k = c.Count(4); k > 0; --k) {
            const char *param = kTexParams[c.Below(std::size(kTexParams))];
            if (c.Below(3) != 0) {  // a texture, mostly an earlier one
                const int to =
                    i > 0 && c.Below(6) != 0 ? int(c.Below(uint32_t(i))) : c.Index(n + 2);
                s += std::string(" \"texture ") + param + "\" \"" + name(to) + "\"";
            } else if (isFloat || c.Flip()) {
                s += std::string(" \"float ") + param + "\" " + c.Number();
            } else {
                s += std::string(" \"rgb ") + param + "\" [" + c.Number() + " " + c.Number() + " " +
                     c.Number() + "]";
            }
        }
        if (c.Flip()) s += " \"integer dimension\" " + std::to_string(int(c.Below(5)));
        if (c.Flip()) s += " \"integer octaves\" " + c.Integer();
        if (c.Flip()) s += " \"float roughness\" " + c.Number();
        if (c.Below(4) == 0) s += " \"float variation\" " + c.Number();
        if (c.Below(4) == 0)
            s += std::string(" \"string aamode\" \"") + (c.Flip() ? "none" : "closedform") + "\"";
        if (c.Below(3) == 0) {
            s += std::string(" \"string mapping\" \"") + kMappings[c.Below(5)] +
                 "\" \"float uscale\" " + c.Number() + " \"float vscale\" " + c.Number() +
                 " \"float udelta\" " + c.Number();
            if (c.Flip())
                s += " \"vector3 v1\" [" + c.Number() + " 0 0] \"vector3 v2\" [0 " + c.Number() +
                     " 0]";
        }
        if (c.Below(4) == 0)
            for (const char *v : {"v00", "v01", "v10", "v11"})
                s += std::string(" \"float ") + v + "\" " + c.Number();
        if (c.Below(6) == 0) s += " \"string filename\" \"missing.png\"";
        s += "\n";
    }
    auto tex = [&] { return name(c.Index(n)); };
    static const char *const kMaterials[] = {"matte", "plastic", "metal", "uber", "substrate"};
    for (int shape = 0; shape < 2; ++shape) {
        s += "AttributeBegin\nMaterial \"" + std::string(kMaterials[c.Below(5)]) +
             "\" \"texture Kd\" \"" + tex() + "\" \"texture Ks\" \"" + tex() +
             "\" \"texture roughness\" \"" + tex() + "\" \"texture sigma\" \"" + tex() + "\"";
        if (c.Flip()) s += " \"texture bumpmap\" \"" + tex() + "\"";
        s += "\n";
        s += shape == 0 ? "Shape \"sphere\" \"float radius\" 0.8\n"
                        : "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
                          "\"point3 P\" [-2 -2 -1  2 -2 -1  2 2 -1  -2 2 -1] "
                          "\"point2 uv\" [0 0 1 0 1 1 0 1]\n";
        s += "AttributeEnd\n";
    }
    return s;
}

}  // namespace

std::string GltfJsonScene(const uint8_t *data, size_t size) {
    Choices c(data, size);
    return GltfFromChoices(c);
}

std::string TextureGraphScene(const uint8_t *data, size_t size) {
    Choices c(data, size);
    return TexturesFromChoices(c);
}

void FuzzGltfJson(const uint8_t *data, size_t size, std::string *rejected) {
    const std::string json = GltfJsonScene(data, size);
    const fs::path path = Scratch() / "structured.gltf";
    {
        FILE *f = std::fopen(path.c_str(), "wb");
        if (!f) throw std::logic_error("fuzz: cannot write " + path.string());
        std::fwrite(json.data(), 1, json.size(), f);
        std::fclose(f);
    }
    Diagnostics diag(false);
    MemoryBudget budget(uint64_t(256) << 20);
    try {
        ReadGltfFile(path.string(), diag, budget);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

void FuzzTextureGraph(const uint8_t *data, size_t size, std::string *rejected) {
    const std::string text = TextureGraphScene(data, size);
    Diagnostics diag(false);
    MemoryBudget budget(uint64_t(256) << 20);
    try {
        PbrtParseOptions opts;
        opts.confineIncludes = true;
        opts.budget = &budget;
        SceneDescription desc =
            ParsePbrtString(text, (Scratch() / "textures.pbrt").string(), diag, opts);
        BuildSettings settings;
        settings.budget = &budget;
        RenderScene scene = BuildRenderScene(desc, settings, diag);
        // Every texture the materials reach is evaluated at the hits of 16 camera rays (with
        // their footprints where a texture filters) and at their specular bounces.
        RenderStats stats;
        Render(scene, &stats);
    } catch (const SceneError &e) {
        if (rejected) *rejected = e.what();
    }
}

}  // namespace prism::fuzz
