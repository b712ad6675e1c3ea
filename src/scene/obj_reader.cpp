// OBJ/MTL → SceneDescription. tinyobjloader does the parsing (negative indices, groups,
// triangulation); this file validates its output, regroups faces by material and maps MTL
// illumination models onto pbrt-v3 materials.
#include "scene/obj_reader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/file_io.h"
#include "core/memory.h"
#include "scene/param_builders.h"

namespace prism {

namespace {

using namespace reader;

bool NonZero(const tinyobj::real_t c[3]) { return c[0] > 0 || c[1] > 0 || c[2] > 0; }

// MTL texture paths are often written on Windows (".\tex.jpg"); they are relative to the OBJ's
// directory, which is the scene's baseDir.
std::string NormalizeTexturePath(std::string p) {
    std::replace(p.begin(), p.end(), '\\', '/');
    return p;
}

// Appends the "imagemap" texture "obj:<material>:<slot>" reading `file` and returns it, for
// the caller to add its other parameters (the reference lives until desc.textures grows).
TextureDesc &AddImageTexture(SceneDescription &desc, const tinyobj::material_t &m,
                             const std::string &slot, const std::string &file, bool isFloat,
                             const FileLoc &loc) {
    TextureDesc t;
    t.type = "imagemap";
    t.name = "obj:" + m.name + ":" + slot;
    t.loc = loc;
    t.isFloat = isFloat;
    AddString(t.params, "filename", NormalizeTexturePath(file), loc);
    desc.textures.push_back(std::move(t));
    return desc.textures.back();
}

// MTL illumination models → pbrt-v3 materials:
//   illum 4/6/7                       → "glass"  (index Ni, 1.5 when Ni <= 1; Kt = Tf if set)
//   illum 5, or illum 3 with Ks != 0  → "mirror" (Kr = Ks)
//   Ks != 0                           → "plastic" (Kd, Ks, alpha = sqrt(2 / (Ns + 2)), the
//                                        Blinn-Phong-to-Beckmann conversion; remaproughness false)
//   otherwise                         → "matte" (Kd)
// map_Kd becomes an "imagemap" texture that replaces Kd. Tf alone does not make glass:
// many exporters write "Tf 1 1 1" to mean "no filter". Neither does a dissolve d < 1 (or Tr):
// exporters write it for see-through surfaces (decals, leaves, windows drawn as blended
// polygons), so it is transparency (AddObjAlpha), not refraction; only the illumination
// models that ask for refraction (4, 6, 7) make glass. Ni alone says nothing (Blender writes
// Ni 1.45 for every material).
bool IsObjGlass(const tinyobj::material_t &m) {
    return m.illum == 4 || m.illum == 6 || m.illum == 7;
}

MaterialDesc ConvertMaterial(const tinyobj::material_t &m, const FileLoc &loc,
                             SceneDescription &desc) {
    MaterialDesc md;
    md.name = m.name;
    md.loc = loc;
    ParamSet &ps = md.params;
    const int illum = m.illum;
    auto Kd = [&] {
        if (!m.diffuse_texname.empty()) {
            AddTexture(ps, "Kd",
                       AddImageTexture(desc, m, "map_Kd", m.diffuse_texname, false, loc).name, loc);
        } else {
            AddRGB(ps, "Kd", m.diffuse[0], m.diffuse[1], m.diffuse[2], loc);
        }
    };
    if (IsObjGlass(m)) {
        md.type = "glass";
        AddFloat(ps, "index", m.ior > 1 ? m.ior : 1.5, loc);
        AddRGB(ps, "Kr", 1, 1, 1, loc);
        if (NonZero(m.transmittance))
            AddRGB(ps, "Kt", m.transmittance[0], m.transmittance[1], m.transmittance[2], loc);
        else
            AddRGB(ps, "Kt", 1, 1, 1, loc);
    } else if (illum == 5 || (illum == 3 && NonZero(m.specular))) {
        md.type = "mirror";
        AddRGB(ps, "Kr", m.specular[0], m.specular[1], m.specular[2], loc);
    } else if (NonZero(m.specular)) {
        md.type = "plastic";
        Kd();
        AddRGB(ps, "Ks", m.specular[0], m.specular[1], m.specular[2], loc);
        double ns = std::max(0.0, double(m.shininess));
        AddFloat(ps, "roughness", std::sqrt(2.0 / (ns + 2.0)), loc);
        AddBool(ps, "remaproughness", false, loc);
    } else {
        md.type = "matte";
        Kd();
    }
    // Surface detail on any material: "norm" is a tangent-space normal map (read linearly),
    // "bump"/"map_Bump" a height map (a float "bumpmap" texture scaled by -bm).
    if (!m.normal_texname.empty())
        AddString(ps, "normalmap", NormalizeTexturePath(m.normal_texname), loc);
    if (!m.bump_texname.empty()) {
        TextureDesc &t = AddImageTexture(desc, m, "bump", m.bump_texname, true, loc);
        AddString(t.params, "encoding", "linear", loc);
        AddFloat(t.params, "scale", m.bump_texopt.bump_multiplier, loc);
        AddTexture(ps, "bumpmap", t.name, loc);
    }
    return md;
}

// map_d: a cut-out from the image's alpha channel (its luminance when it has none), kept where
// it is at least 0.5 (as glTF's MASK); for every shape of the material. Without map_d, a
// dissolve d < 1 on a material that is not glass is stochastic transparency of alpha d (as
// glTF's BLEND: camera and shadow rays pass with probability 1 - d).
void AddObjAlpha(const tinyobj::material_t &m, const FileLoc &loc, SceneDescription &desc,
                 ParamSet &shapeParams) {
    if (m.alpha_texname.empty()) {
        if (m.dissolve < 1 && !IsObjGlass(m)) {
            AddFloat(shapeParams, "alpha", std::max(0.0, double(m.dissolve)), loc);
            AddString(shapeParams, "alphamode", "blend", loc);
        }
        return;
    }
    const std::string name = "obj:" + m.name + ":map_d";
    bool have = false;
    for (const TextureDesc &t : desc.textures) have = have || t.name == name;
    if (!have) {
        TextureDesc &t = AddImageTexture(desc, m, "map_d", m.alpha_texname, true, loc);
        AddString(t.params, "encoding", "linear", loc);
        AddString(t.params, "channel", "alphaorluminance", loc);
    }
    AddTexture(shapeParams, "alpha", name, loc);
    AddString(shapeParams, "alphamode", "mask", loc);
    AddFloat(shapeParams, "alphacutoff", 0.5, loc);
}

struct VertexKey {
    int v, n, t;
    bool operator==(const VertexKey &) const = default;
};
struct VertexKeyHash {
    size_t operator()(const VertexKey &k) const {
        uint64_t h = uint64_t(uint32_t(k.v)) * 0x9E3779B97F4A7C15ull;
        h ^= uint64_t(uint32_t(k.n)) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
        h ^= uint64_t(uint32_t(k.t)) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
        return size_t(h);
    }
};

// Accumulates one output mesh: OBJ's separate position/normal/uv indices are merged into
// single-index vertices.
struct MeshBuilder {
    std::vector<Vec3f> P, N;
    std::vector<Vec2f> uv;
    std::vector<int> indices;
    std::unordered_map<VertexKey, int, VertexKeyHash> map;
    bool allNormals = true, allUVs = true;

    void Add(const tinyobj::index_t &idx, const tinyobj::attrib_t &a) {
        VertexKey key{idx.vertex_index, idx.normal_index, idx.texcoord_index};
        auto [it, inserted] = map.try_emplace(key, int(P.size()));
        if (inserted) {
            size_t v = size_t(idx.vertex_index);
            P.emplace_back(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]);
            if (idx.normal_index >= 0) {
                size_t n = size_t(idx.normal_index);
                N.emplace_back(a.normals[3 * n], a.normals[3 * n + 1], a.normals[3 * n + 2]);
            } else {
                N.emplace_back();
                allNormals = false;
            }
            if (idx.texcoord_index >= 0) {
                size_t t = size_t(idx.texcoord_index);
                uv.emplace_back(a.texcoords[2 * t], a.texcoords[2 * t + 1]);
            } else {
                uv.emplace_back();
                allUVs = false;
            }
        }
        indices.push_back(it->second);
    }
};

void ValidateIndex(const tinyobj::index_t &idx, const tinyobj::attrib_t &a, const FileLoc &loc,
                   const std::string &shapeName) {
    auto Bad = [&](const char *what, int i, size_t n) {
        std::string who = shapeName.empty() ? "a face" : "a face of \"" + shapeName + "\"";
        // tinyobjloader has already resolved relative (negative) indices.
        if (i < 0) throw SceneError(loc, who + " refers to a " + what + " before the first one");
        throw SceneError(loc, who + " refers to " + what + " " + std::to_string(i + 1) +
                                  ", but there are " + std::to_string(n));
    };
    size_t nv = a.vertices.size() / 3, nn = a.normals.size() / 3, nt = a.texcoords.size() / 2;
    if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv) Bad("vertex", idx.vertex_index, nv);
    if (idx.normal_index < -1 || (idx.normal_index >= 0 && size_t(idx.normal_index) >= nn))
        Bad("normal", idx.normal_index, nn);
    if (idx.texcoord_index < -1 || (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt))
        Bad("texture coordinate", idx.texcoord_index, nt);
}

// A material library that is a device or FIFO (a hostile "mtllib ../../dev/zero") would make
// tinyobjloader read forever; only regular files (or missing ones: a warning later) pass.
void CheckMaterialLibraries(const std::string &path, const std::string &line, int lineNo) {
    namespace fs = std::filesystem;
    std::istringstream names(line.substr(6));
    std::string name;
    while (names >> name) {
        // tinyobjloader joins the OBJ's directory and the name as strings.
        std::string dir = fs::path(path).parent_path().string();
        std::string joined = dir.empty() ? name : dir + "/" + name;
        std::error_code ec;
        fs::file_status st = fs::status(joined, ec);
        if (!ec && fs::exists(st) && st.type() != fs::file_type::regular)
            throw SceneError(FileLoc{path, lineNo, 1},
                             "material library \"" + name + "\" is not a regular file");
    }
}

// tinyobjloader reads a malformed number as 0 without complaint; check the numeric lines
// first so such files fail with a location instead of rendering wrongly.
void CheckNumbers(const std::string &path, const std::string &text) {
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        size_t i = line.find_first_not_of(" \t");
        if (i != std::string::npos && line.compare(i, 7, "mtllib ") == 0)
            CheckMaterialLibraries(path, line.substr(i), lineNo);
        if (i == std::string::npos || line[i] != 'v') continue;
        size_t kwEnd = line.find_first_of(" \t", i);
        if (kwEnd == std::string::npos) continue;
        std::string kw = line.substr(i, kwEnd - i);
        if (kw != "v" && kw != "vn" && kw != "vt") continue;
        size_t p = kwEnd;
        while (true) {
            p = line.find_first_not_of(" \t\r", p);
            if (p == std::string::npos || line[p] == '#') break;
            size_t end = line.find_first_of(" \t\r", p);
            if (end == std::string::npos) end = line.size();
            const char *b = line.data() + p, *e = line.data() + end;
            if (*b == '+') ++b;
            double v;
            auto r = std::from_chars(b, e, v);
            if (r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
                throw SceneError(
                    FileLoc{path, lineNo, int(p) + 1},
                    "bad number \"" + line.substr(p, end - p) + "\" in \"" + kw + "\" line");
            p = end;
        }
    }
}

// The lines of `text` whose first word is `keyword`, with their line numbers (mtllib and
// map_Kd lines, to locate confinement errors).
std::vector<std::pair<int, std::string>> KeywordLines(const std::string &text,
                                                      std::string_view keyword) {
    std::vector<std::pair<int, std::string>> lines;
    int lineNo = 1;
    for (size_t start = 0; start < text.size(); ++lineNo) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + start, end - start);
        size_t k = line.find_first_not_of(" \t");
        if (k != std::string_view::npos && line.substr(k, keyword.size()) == keyword &&
            k + keyword.size() < line.size() &&
            std::isspace(static_cast<unsigned char>(line[k + keyword.size()])))
            lines.emplace_back(lineNo, std::string(line));
        start = end + 1;
    }
    return lines;
}

// The location in `file` of the first of `lines` that names `name` (at the name's column), or
// the whole file.
FileLoc LocateName(const std::string &file, const std::vector<std::pair<int, std::string>> &lines,
                   const std::string &name) {
    for (const auto &[lineNo, line] : lines) {
        size_t at = line.find(name);
        if (at != std::string::npos) return FileLoc{file, lineNo, int(at) + 1};
    }
    return FileLoc{file};
}

// tinyobjloader's MaterialFileReader, reading through the shared file reader: MTL files are
// looked up in the OBJ's directory; one that cannot be read is a warning, as in tinyobjloader,
// except one that the read confinement (--confine) refuses: an error at its mtllib line.
class MtlReader : public tinyobj::MaterialReader {
  public:
    MtlReader(std::string dir, MemoryBudget *budget, FileLoc loc, const std::string &objText)
        : dir_(std::move(dir)),
          budget_(budget),
          loc_(std::move(loc)),
          mtllibLines_(KeywordLines(objText, "mtllib")) {}
    bool operator()(const std::string &name, std::vector<tinyobj::material_t> *materials,
                    std::map<std::string, int> *matMap, std::string *warn,
                    std::string *err) override {
        std::string text;
        FileReadError error;
        const std::string what = "material library " + Quote(name);
        const std::string path = dir_.empty() ? name : dir_ + "/" + name;
        if (!ReadFileContents(path, &text, &error, budget_ ? budget_->Remaining() : UINT64_MAX)) {
            if (error.tooLarge && budget_) budget_->Check(error.size, what, loc_);  // throws
            if (error.refused)
                throw SceneError(LocateName(loc_.file, mtllibLines_, name),
                                 what + ": " + error.reason);
            if (warn)
                *warn += "Material file [ " + name + " ] not found in a path : " + dir_ + "\n";
            return false;
        }
        if (budget_) budget_->Charge(text.size(), what, loc_);
        std::istringstream in(text);
        tinyobj::LoadMtl(matMap, materials, &in, warn, err);
        if (!ReadConfinementFolder().empty())
            mapKdLines_.emplace_back(path, KeywordLines(text, "map_Kd"));
        return true;
    }
    // Under --confine: every map_Kd texture must be readable, checked here so that a refusal
    // points at its map_Kd line.
    void CheckTextures(const std::vector<tinyobj::material_t> &materials) const {
        for (const tinyobj::material_t &m : materials) {
            if (m.diffuse_texname.empty()) continue;
            std::string file = NormalizeTexturePath(m.diffuse_texname);
            FileLoc loc = loc_;
            for (const auto &[mtlPath, lines] : mapKdLines_) {
                FileLoc l = LocateName(mtlPath, lines, m.diffuse_texname);
                if (l.line > 0) {
                    loc = l;
                    break;
                }
            }
            CheckReadConfinement(ResolveScenePath(dir_, file), loc, "texture file",
                                 m.diffuse_texname);
        }
    }

  private:
    std::string dir_;
    MemoryBudget *budget_;
    FileLoc loc_;
    std::vector<std::pair<int, std::string>> mtllibLines_;
    // Under --confine: each MTL file read and its map_Kd lines.
    std::vector<std::pair<std::string, std::vector<std::pair<int, std::string>>>> mapKdLines_;
};

}  // namespace

SceneDescription ReadObjFile(const std::string &path, Diagnostics &diag, MemoryBudget *budget) {
    FileLoc fileLoc{path};
    std::string text = budget ? ReadFileOrThrow(path, fileLoc, *budget, "scene file")
                              : ReadFileOrThrow(path, fileLoc);
    CheckNumbers(path, text);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    MtlReader mtlReader(DirectoryOf(path), budget, fileLoc, text);
    std::istringstream in(std::move(text));
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtlReader,
                               /*triangulate=*/true, /*default_vcols_fallback=*/false);
    if (!ReadConfinementFolder().empty()) mtlReader.CheckTextures(materials);
    for (const std::string &w : MessageLines(warn)) diag.Warn(fileLoc, w);
    std::vector<std::string> errors = MessageLines(err);
    if (!ok || !errors.empty())
        throw SceneError(fileLoc, errors.empty() ? std::string("cannot parse OBJ file")
                                                 : "cannot parse OBJ file: " + errors.front());

    for (tinyobj::real_t x : attrib.vertices)
        if (!std::isfinite(x)) throw SceneError(fileLoc, "vertex position is not a finite number");

    SceneDescription desc;
    desc.format = "obj";
    // OBJ names no integrator: Prism's distribution integrator (glossy materials reflect).
    desc.integrator.type = "distribution";
    desc.sourceFile = path;
    desc.baseDir = DirectoryOf(path);

    // Materials map 1:1 onto desc.materials; emissive ones get an area light.
    std::vector<int> areaLightOf;
    for (const tinyobj::material_t &m : materials) {
        desc.materials.push_back(ConvertMaterial(m, fileLoc, desc));
        // A coloured Tf beside d < 1 reads like a filter for glass; say what is made instead.
        const bool colouredTf =
            NonZero(m.transmittance) &&
            !(m.transmittance[0] == 1 && m.transmittance[1] == 1 && m.transmittance[2] == 1);
        if (m.dissolve < 1 && !IsObjGlass(m) && m.alpha_texname.empty() && colouredTf)
            diag.Warn(fileLoc, "material " + Quote(m.name) + ": \"d " +
                                   (std::ostringstream() << m.dissolve).str() +
                                   "\" is read as transparency (a see-through surface), not "
                                   "refraction, so its Tf filter colour is ignored; illum 4, 6 "
                                   "or 7 makes it glass with Kt = Tf");
        int light = -1;
        if (NonZero(m.emission)) {
            AreaLightDesc al;
            al.type = "diffuse";
            al.loc = fileLoc;
            AddRGB(al.params, "L", m.emission[0], m.emission[1], m.emission[2], fileLoc);
            // OBJ/glTF carry no sample count: 16 stratified shadow rays give clean soft shadows.
            AddInts(al.params, "nsamples", {16}, fileLoc);
            light = int(desc.areaLights.size());
            desc.areaLights.push_back(std::move(al));
        }
        areaLightOf.push_back(light);
    }
    const int nMaterials = int(desc.materials.size());

    for (const tinyobj::shape_t &shape : shapes) {
        const tinyobj::mesh_t &mesh = shape.mesh;
        std::map<int, MeshBuilder> byMaterial;  // ordered: deterministic output
        size_t offset = 0;
        for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            size_t n = mesh.num_face_vertices[f];
            if (offset + n > mesh.indices.size())
                throw SceneError(fileLoc, "inconsistent face data in shape \"" + shape.name + "\"");
            int mat = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            if (mat < -1 || mat >= nMaterials) mat = -1;
            for (size_t k = 0; k < n; ++k)
                ValidateIndex(mesh.indices[offset + k], attrib, fileLoc, shape.name);
            MeshBuilder &b = byMaterial[mat];
            // tinyobjloader already triangulated; fan anything else defensively.
            for (size_t k = 1; k + 1 < n; ++k) {
                b.Add(mesh.indices[offset], attrib);
                b.Add(mesh.indices[offset + k], attrib);
                b.Add(mesh.indices[offset + k + 1], attrib);
            }
            offset += n;
        }
        for (auto &[mat, b] : byMaterial) {
            if (b.indices.empty()) continue;
            // A face without normals gets flat shading: drop N for the whole mesh.
            if (!b.allNormals) b.N.clear();
            if (!b.allUVs) b.uv.clear();
            ShapeDesc s;
            s.type = "trianglemesh";
            s.loc = fileLoc;
            s.name = shape.name;
            s.material = mat;
            s.areaLight = mat >= 0 ? areaLightOf[size_t(mat)] : -1;
            s.directiveIndex = int(desc.shapes.size());
            s.params = TriangleMeshParams(b.indices, b.P, b.N, b.uv, fileLoc);
            if (mat >= 0) AddObjAlpha(materials[size_t(mat)], fileLoc, desc, s.params);
            if (budget) budget->Charge(ParamStorageBytes(s.params), "mesh", fileLoc);
            desc.shapes.push_back(std::move(s));
        }
    }
    return desc;
}

}  // namespace prism
