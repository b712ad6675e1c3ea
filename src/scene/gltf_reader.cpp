// glTF 2.0 → SceneDescription. tinygltf (Debian's shared library) parses the JSON and loads
// buffers; image decoding is replaced by a callback that only keeps the encoded bytes. Every
// accessor is bounds-checked here because tinygltf does not validate them.
#include "scene/gltf_reader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/file_io.h"
#include "core/memory.h"
#include "core/pbrt_defaults.h"
#include "scene/gltf_converter.h"
#include "scene/param_builders.h"

namespace prism {

namespace gltf_internal {

using namespace reader;

double ExtNumber(const tinygltf::ExtensionMap &ext, const char *extName, const char *key,
                 double def) {
    auto it = ext.find(extName);
    if (it == ext.end() || !it->second.IsObject() || !it->second.Has(key)) return def;
    const tinygltf::Value &v = it->second.Get(key);
    return v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : def;
}

namespace {

// The memory budget seen from tinygltf's callbacks, which must not throw: a refused charge is
// kept here and rethrown once tinygltf returns.
struct ReadBudget {
    MemoryBudget &budget;
    std::string topFile;
    std::optional<MemoryBudgetError> refused;
    // A buffer or image the read confinement (--confine) refused, and why.
    std::string confinedPath, confinedReason;
    // The first buffer or image that could not be read otherwise (a FIFO, a device), and why.
    std::string failedPath, failedReason;
    // The glTF's JSON nests deeper than kMaxJsonDepth: refused before tinygltf parses it.
    std::optional<SceneError> tooDeep;
    // The model tinygltf is filling (its buffers and views are read before its images).
    const tinygltf::Model *model = nullptr;
};

// tinygltf's own FileExists probes every candidate path of a URI with fopen(path, "rb"): a
// FIFO blocks there forever, and a file outside the --confine folder is opened before
// ReadWholeFileWithinBudget could refuse it. This one opens nothing. A path the confinement
// refuses "exists", so that the read below reports the refusal at the URI.
bool FileExistsWithoutOpening(const std::string &path, void *) {
    if (!ReadConfinementRefusal(path).empty()) return true;
    struct stat st;
    return ::stat(path.c_str(), &st) == 0;
}

// No expansion (tinygltf's default does none either: no `~`, no environment variables).
std::string KeepFilePath(const std::string &path, void *) { return path; }

bool RefuseToWrite(std::string *err, const std::string &, const std::vector<unsigned char> &,
                   void *) {
    if (err) *err += "Prism does not write glTF files\n";
    return false;
}

// Replaces tinygltf's stb_image decoding: images without an external URI (data URIs and .glb
// bufferViews) keep their encoded bytes in Image::image; external files are referenced by
// path and decoded later by the renderer (which charges the decoded texture), so the bytes
// tinygltf read for them are given back to the budget.
bool KeepEncodedBytes(tinygltf::Image *image, const int index, std::string *err, std::string *, int,
                      int, const unsigned char *bytes, int size, void *user) {
    auto *b = static_cast<ReadBudget *>(user);
    // tinygltf 2.7 hands an image's buffer view over without checking it against its buffer
    // (found by fuzz_gltf_json: a view past the end was read out of bounds). Checked here,
    // before a byte is read.
    if (image->uri.empty() && image->bufferView >= 0 && b->model) {
        const auto &views = b->model->bufferViews;
        const auto &buffers = b->model->buffers;
        bool ok = size_t(image->bufferView) < views.size();
        if (ok) {
            const tinygltf::BufferView &v = views[size_t(image->bufferView)];
            ok = v.buffer >= 0 && size_t(v.buffer) < buffers.size() &&
                 v.byteOffset <= buffers[size_t(v.buffer)].data.size() &&
                 v.byteLength <= buffers[size_t(v.buffer)].data.size() - v.byteOffset;
        }
        if (!ok) {
            if (err)
                *err += "image " + std::to_string(index) + ": buffer view " +
                        std::to_string(image->bufferView) + " reaches past the end of its buffer\n";
            return false;
        }
    }
    if (!image->uri.empty() && image->uri.compare(0, 5, "data:") != 0 && size > 0)
        b->budget.Release(uint64_t(size));
    if (image->uri.empty() && bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// How deep JSON arrays and objects may nest in a glTF file. tinygltf turns JSON values (the
// "extras" of anything) into its own Value recursively, so 20,000 nested brackets in a 40 KB
// file overflowed the stack; real files nest about a dozen levels.
constexpr int kMaxJsonDepth = 512;

// The offset of the first '[' or '{' in `json` nested deeper than kMaxJsonDepth (brackets in
// strings do not count), or npos.
size_t TooDeepJson(std::string_view json) {
    int depth = 0;
    bool inString = false;
    for (size_t i = 0; i < json.size(); ++i) {
        char c = json[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) return i;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return std::string_view::npos;
}

// The JSON of a .gltf file (the whole file) or of a .glb (its first chunk, when it is JSON),
// and where that JSON starts in the file.
std::string_view JsonText(const std::vector<unsigned char> &file, bool glb, size_t *start) {
    std::string_view all(reinterpret_cast<const char *>(file.data()), file.size());
    *start = 0;
    if (!glb) return all;
    auto u32 = [&](size_t at) {
        return uint32_t(file[at]) | uint32_t(file[at + 1]) << 8 | uint32_t(file[at + 2]) << 16 |
               uint32_t(file[at + 3]) << 24;
    };
    if (file.size() < 20 || u32(16) != 0x4E4F534Au) return {};  // tinygltf reports it
    *start = 20;
    return all.substr(20, std::min<size_t>(u32(12), file.size() - 20));
}

// tinygltf reads the .gltf/.glb file, every external buffer and every external image whole.
// This replacement reads only regular files (not /dev/zero or a FIFO named by a hostile URI)
// and charges each to the memory budget, checked before anything is allocated.
bool ReadWholeFileWithinBudget(std::vector<unsigned char> *out, std::string *err,
                               const std::string &path, void *user) {
    auto *b = static_cast<ReadBudget *>(user);
    FileReadError error;
    const std::string what = path == b->topFile
                                 ? std::string("scene file")
                                 : "file " + Quote(std::filesystem::path(path).filename().string());
    try {
        if (!ReadFileContents(path, out, &error, b->budget.Remaining())) {
            if (error.tooLarge) b->budget.Check(error.size, what, FileLoc{b->topFile});
            if (error.refused && b->confinedPath.empty())
                b->confinedPath = path, b->confinedReason = error.reason;
            else if (!error.refused && !error.tooLarge && path != b->topFile &&
                     b->failedPath.empty())
                b->failedPath = path, b->failedReason = error.reason;
            if (err) *err += (error.tooLarge ? "file grew while read" : error.reason) + "\n";
            return false;
        }
        b->budget.Charge(out->size(), what, FileLoc{b->topFile});
        if (path == b->topFile) {
            const bool glb = LowerExtension(path) == ".glb";
            size_t start = 0;
            std::string_view json = JsonText(*out, glb, &start);
            size_t at = TooDeepJson(json);
            if (at != std::string_view::npos) {
                // A .gltf is text: line and column; a .glb's JSON chunk is one long line.
                FileLoc loc{path};
                if (!glb) {
                    loc.line = 1 + int(std::count(json.begin(), json.begin() + long(at), '\n'));
                    size_t lineStart = json.rfind('\n', at);
                    loc.column =
                        int(at - (lineStart == std::string_view::npos ? 0 : lineStart + 1)) + 1;
                }
                b->tooDeep = SceneError(
                    loc,
                    "JSON arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) +
                        " levels" +
                        (glb ? " (at byte " + std::to_string(start + at) + ")" : std::string()));
                if (err) *err += "JSON nested too deeply\n";
                out->clear();
                return false;
            }
        }
    } catch (const MemoryBudgetError &e) {
        if (!b->refused) b->refused = e;
        if (err) *err += e.Message() + "\n";
        out->clear();
        return false;
    }
    return true;
}

// Column-major glTF 4x4 → Matrix4 (row-major m[row][col]).
Matrix4 FromColumnMajor(const std::vector<double> &v) {
    Matrix4 m;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m.m[r][c] = v[size_t(c * 4 + r)];
    return m;
}

// T * R * S from a node's translation / rotation (unit quaternion x y z w) / scale.
Matrix4 NodeLocalMatrix(const tinygltf::Node &n, const FileLoc &loc) {
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16) throw SceneError(loc, "node matrix must have 16 numbers");
        return FromColumnMajor(n.matrix);
    }
    double t[3] = {0, 0, 0}, s[3] = {1, 1, 1}, q[4] = {0, 0, 0, 1};
    if (!n.translation.empty()) {
        if (n.translation.size() != 3)
            throw SceneError(loc, "node translation must have 3 numbers");
        for (int i = 0; i < 3; ++i) t[i] = n.translation[size_t(i)];
    }
    if (!n.scale.empty()) {
        if (n.scale.size() != 3) throw SceneError(loc, "node scale must have 3 numbers");
        for (int i = 0; i < 3; ++i) s[i] = n.scale[size_t(i)];
    }
    if (!n.rotation.empty()) {
        if (n.rotation.size() != 4) throw SceneError(loc, "node rotation must have 4 numbers");
        for (int i = 0; i < 4; ++i) q[i] = n.rotation[size_t(i)];
    }
    return TrsMatrix(t, q, s);
}

// Turns a primitive's vertex sequence v (*indices) into triangles, three each, for glTF's
// triangles (4: in place, a trailing partial triangle dropped), triangle strip (5: triangle i
// is v_i, v_{i+1+i%2}, v_{i+2-i%2}, so every triangle keeps the first one's winding) and
// triangle fan (6: v_{i+1}, v_{i+2}, v_0). Degenerate triangles of strips and fans (repeated
// indices, how strips restart) are dropped.
void ToTriangleList(int mode, std::vector<int> *indices) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        indices->resize(indices->size() / 3 * 3);
        return;
    }
    const std::vector<int> &v = *indices;
    std::vector<int> out;
    if (v.size() >= 3) out.reserve(3 * (v.size() - 2));
    for (size_t i = 0; i + 2 < v.size(); ++i) {
        int a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            a = v[i];
            b = v[i + 1 + i % 2];
            c = v[i + 2 - i % 2];
        } else {
            a = v[i + 1];
            b = v[i + 2];
            c = v[0];
        }
        if (a == b || b == c || a == c) continue;
        out.insert(out.end(), {a, b, c});
    }
    *indices = std::move(out);
}

}  // namespace

Matrix4 GltfConverter::NodeWorldMatrix(int nodeIndex) {
    if (parents_.empty()) {
        parents_.assign(model_.nodes.size(), -1);
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            for (int c : model_.nodes[i].children)
                if (c >= 0 && size_t(c) < parents_.size() && parents_[size_t(c)] < 0)
                    parents_[size_t(c)] = int(i);
    }
    Matrix4 world = Matrix4::Identity();
    int depth = 0;
    for (int i = nodeIndex; i >= 0; i = parents_[size_t(i)]) {
        if (size_t(i) >= model_.nodes.size())
            Fail("reference to node " + std::to_string(i) + ", which does not exist");
        if (++depth > 1000) Fail("node hierarchy is deeper than 1000 levels (or a cycle)");
        try {
            world = NodeLocalMatrix(model_.nodes[size_t(i)], loc_) * world;
        } catch (const SceneError &e) {
            Fail(e.Message());
        }
    }
    return world;
}

void GltfConverter::AddMesh(int meshIndex, const Transform &worldFromObject,
                            const std::vector<double> &nodeWeights, int skin) {
    if (meshIndex < 0 || size_t(meshIndex) >= model_.meshes.size()) {
        const Where where(*this, where_ + "/mesh");  // the node's
        Fail("node refers to mesh " + std::to_string(meshIndex) + ", which does not exist");
    }
    const tinygltf::Mesh &mesh = model_.meshes[size_t(meshIndex)];
    for (size_t primIndex = 0; primIndex < mesh.primitives.size(); ++primIndex) {
        const tinygltf::Primitive &prim = mesh.primitives[primIndex];
        const Where where(*this, "/meshes/" + std::to_string(meshIndex) + "/primitives/" +
                                     std::to_string(primIndex));
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            if (warnedModes_.insert(mode).second)
                diag_.Warn(loc_,
                           "primitive mode " + std::to_string(mode) +
                               (mode <= TINYGLTF_MODE_LINE_STRIP ? " (points or lines)" : "") +
                               " is not supported: only triangles, strips and fans are "
                               "rendered; such primitives are skipped");
            continue;
        }
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) {
            diag_.Warn(loc_,
                       "mesh \"" + mesh.name + "\" has a primitive without POSITION; skipped");
            continue;
        }
        std::vector<Vec3f> P = ReadVec3(pos->second, "POSITION", AttributeKind::Position);
        std::vector<Vec3f> N;
        std::vector<Vec2f> uv;
        if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
            N = ReadVec3(it->second, "NORMAL", AttributeKind::Direction);
            if (N.size() != P.size()) Fail("NORMAL and POSITION accessors differ in count");
        }
        if (!prim.targets.empty())
            ApplyMorphTargets(prim, nodeWeights.empty() ? mesh.weights : nodeWeights, P, N);
        std::vector<Matrix4> skinFrames;
        if (skin >= 0) ApplySkin(skin, prim, P, N, &skinFrames);
        if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
            uv = ReadTexcoords(it->second);
            if (uv.size() != P.size()) Fail("TEXCOORD_0 and POSITION accessors differ in count");
        }
        // TEXCOORD_1 only for materials with a texture on set 1 (textureInfo.texCoord).
        std::vector<Vec2f> uv1;
        if (materialsUsingTexCoord1_.count(prim.material)) {
            if (auto it = prim.attributes.find("TEXCOORD_1"); it != prim.attributes.end()) {
                uv1 = ReadTexcoords(it->second, "TEXCOORD_1");
                if (uv1.size() != P.size())
                    Fail("TEXCOORD_1 and POSITION accessors differ in count");
            } else if (!warnedMissingTexCoord1_) {
                warnedMissingTexCoord1_ = true;
                diag_.Warn(loc_, "mesh \"" + mesh.name + "\": material " +
                                     std::to_string(prim.material) +
                                     " reads TEXCOORD_1, which the primitive lacks; TEXCOORD_0 "
                                     "is read instead");
            }
        }
        std::vector<int> indices;
        if (prim.indices >= 0) {
            indices = ReadIndices(prim.indices, P.size());
        } else {
            indices.resize(P.size());
            for (size_t i = 0; i < P.size(); ++i) indices[i] = int(i);
        }
        ToTriangleList(mode, &indices);
        if (indices.empty() || P.empty()) continue;
        if (prim.material >= int(model_.materials.size()))
            Fail("primitive refers to material " + std::to_string(prim.material) +
                 ", which does not exist");
        ShapeDesc s;
        s.type = "trianglemesh";
        s.loc = loc_;
        s.name = mesh.name;
        s.worldFromObject = worldFromObject;
        // desc.materials mirrors model.materials, then glTF's default material.
        s.material = prim.material >= 0 ? prim.material : DefaultMaterial();
        s.areaLight = prim.material >= 0 ? areaLightOfMaterial_[size_t(prim.material)] : -1;
        s.directiveIndex = int(desc_.shapes.size());
        s.params = TriangleMeshParams(indices, P, N, uv, loc_);
        if (!uv1.empty()) AddPoint2s(s.params, "uv1", uv1, loc_);
        // Blended surfaces cast stochastic shadows of their alpha (AddSurfaceParams), except
        // blended emitters: a glowing shade or bulb such as shadows-spot's cone stands for the
        // lamp and surrounds its punctual light, so (as real-time viewers draw it) it casts
        // no shadow.
        if (prim.material >= 0 && model_.materials[size_t(prim.material)].alphaMode == "BLEND" &&
            areaLightOfMaterial_[size_t(prim.material)] >= 0)
            AddFloat(s.params, "shadowalpha", 0, loc_);
        AddSurfaceParams(prim, P.size(), s.params, skin >= 0 ? &skinFrames : nullptr);
        desc_.shapes.push_back(std::move(s));
    }
}

// Keeps only the rigid part of a camera node's transform (glTF asks for unscaled camera nodes;
// a scaled parent such as Duck's 0.01 root must not shrink the view).
Matrix4 RigidPart(const Matrix4 &m) {
    Vec3d c[3];
    for (int j = 0; j < 3; ++j) c[j] = Vec3d(m.m[0][j], m.m[1][j], m.m[2][j]);
    c[0] = Normalize(c[0]);
    c[1] = Normalize(c[1] - c[0] * Dot(c[0], c[1]));
    c[2] = Cross(c[0], c[1]);  // right-handed, like the glTF camera frame
    Matrix4 r = Matrix4::Identity();
    for (int j = 0; j < 3; ++j) {
        r.m[0][j] = c[j].x;
        r.m[1][j] = c[j].y;
        r.m[2][j] = c[j].z;
    }
    for (int i = 0; i < 3; ++i) r.m[i][3] = m.m[i][3];
    return r;
}

void GltfConverter::AddCamera(const tinygltf::Node &node, const Matrix4 &world) {
    if (node.camera < 0 || size_t(node.camera) >= model_.cameras.size()) {
        const Where where(*this, where_ + "/camera");  // the node's
        Fail("node refers to camera " + std::to_string(node.camera) + ", which does not exist");
    }
    const Where where(*this, "/cameras/" + std::to_string(node.camera));
    const tinygltf::Camera &cam = model_.cameras[size_t(node.camera)];
    Matrix4 rigid = RigidPart(world);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(rigid.m[r][c])) {
                diag_.Warn(loc_, "camera node has a degenerate transform; camera ignored");
                return;
            }
    // A rigid part that is finite but singular (found by fuzz_gltf_json: std::invalid_argument
    // escaped) frames no camera either.
    Transform worldFromCamera;
    try {
        worldFromCamera = Transform(rigid);
    } catch (const std::invalid_argument &) {
        diag_.Warn(loc_, "camera node has a degenerate transform; camera ignored");
        return;
    }
    CameraDesc &cd = desc_.camera;
    cd.loc = loc_;
    // glTF cameras look down -z with +y up (right-handed); pbrt's look down +z with +y up and
    // +x to the right of the image (left-handed). Flipping z maps glTF-camera right to pbrt
    // right and "in front" to z > 0 without mirroring the image.
    cd.cameraFromWorld = Scale(1, 1, -1) * worldFromCamera.Inverse();
    if (cam.type == "orthographic") {
        const auto &o = cam.orthographic;
        if (!(o.xmag != 0 && o.ymag != 0)) Fail("orthographic camera needs non-zero xmag and ymag");
        cd.type = "orthographic";
        Param p = MakeParam(ParamType::Float, "screenwindow", loc_);
        double x = std::abs(o.xmag), y = std::abs(o.ymag);
        p.numbers = {-x, x, -y, y};
        cd.params.Add(std::move(p));
    } else {
        const auto &p = cam.perspective;
        if (!(p.yfov > 0 && p.yfov < Pi)) Fail("perspective camera yfov must be in (0, pi)");
        cd.type = "perspective";
        // pbrt's fov spans the shorter image axis; glTF's yfov always spans the vertical one.
        // Without an aspect ratio the film keeps pbrt's default resolution; with one, its
        // longer side keeps pbrt's default width.
        const int longSide = PbrtDefaultXResolution;
        double aspect = p.aspectRatio > 0 ? p.aspectRatio
                                          : double(PbrtDefaultXResolution) / PbrtDefaultYResolution;
        if (p.aspectRatio > 0) {
            ParamSet &film = desc_.film.params;
            int xres = aspect >= 1 ? longSide : std::max(1, int(std::lround(longSide * aspect)));
            int yres = aspect >= 1 ? std::max(1, int(std::lround(longSide / aspect))) : longSide;
            AddInts(film, "xresolution", {xres}, loc_);
            AddInts(film, "yresolution", {yres}, loc_);
        }
        double fov = aspect >= 1 ? p.yfov : 2 * std::atan(std::tan(p.yfov / 2) * aspect);
        AddFloat(cd.params, "fov", Degrees(fov), loc_);
    }
    cd.specified = true;
    haveCamera_ = true;
}

// KHR_lights_punctual. Units: glTF gives candela (point/spot) and lux (directional); Prism is
// radiometric RGB, and we take 1 cd as I = 1 and 1 lx as L = 1 (no 683 lm/W factor), so
// I = color * intensity and L = color * intensity. "range" is ignored (pbrt lights have none).
void GltfConverter::AddLight(const tinygltf::Node &node, const Matrix4 &world) {
    auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return;
    const tinygltf::Value &li = it->second.Get("light");
    if (!li.IsInt() && !li.IsNumber()) Fail("KHR_lights_punctual light index must be a number");
    int index = li.GetNumberAsInt();
    if (index < 0 || size_t(index) >= model_.lights.size())
        Fail("node refers to light " + std::to_string(index) + ", which does not exist");
    const tinygltf::Light &l = model_.lights[size_t(index)];
    double col[3] = {1, 1, 1};
    if (l.color.size() == 3)
        for (int i = 0; i < 3; ++i) col[i] = l.color[size_t(i)];
    double k = l.intensity;
    LightDesc ld;
    ld.loc = loc_;
    try {
        ld.worldFromLight = Transform(world);
    } catch (const std::invalid_argument &) {
        diag_.Warn(loc_, "light node has a singular transform; light ignored");
        return;
    }
    Vec3d origin(0, 0, 0), forward(0, 0, -1);  // glTF lights shine down -z
    if (l.type == "point") {
        ld.type = "point";
        AddRGB(ld.params, "I", col[0] * k, col[1] * k, col[2] * k, loc_);
        AddPoint3(ld.params, "from", origin, loc_);
    } else if (l.type == "spot") {
        ld.type = "spot";
        AddRGB(ld.params, "I", col[0] * k, col[1] * k, col[2] * k, loc_);
        AddPoint3(ld.params, "from", origin, loc_);
        AddPoint3(ld.params, "to", forward, loc_);
        double outer = Clamp(l.spot.outerConeAngle, 0.0, Pi / 2);
        double inner = Clamp(l.spot.innerConeAngle, 0.0, outer);
        AddFloat(ld.params, "coneangle", Degrees(outer), loc_);
        AddFloat(ld.params, "conedeltaangle", Degrees(outer - inner), loc_);
    } else if (l.type == "directional") {
        ld.type = "distant";
        AddRGB(ld.params, "L", col[0] * k, col[1] * k, col[2] * k, loc_);
        AddPoint3(ld.params, "from", origin, loc_);
        AddPoint3(ld.params, "to", forward, loc_);
    } else {
        diag_.Warn(loc_, "unknown KHR_lights_punctual type \"" + l.type + "\"; light ignored");
        return;
    }
    desc_.lights.push_back(std::move(ld));
}

void GltfConverter::Traverse(int nodeIndex, const Matrix4 &parent, std::vector<int> &path) {
    if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size())
        Fail("reference to node " + std::to_string(nodeIndex) + ", which does not exist");
    for (int p : path)
        if (p == nodeIndex) Fail("node " + std::to_string(nodeIndex) + " is its own ancestor");
    if (path.size() > 1000) Fail("node hierarchy is deeper than 1000 levels");
    const Where where(*this, "/nodes/" + std::to_string(nodeIndex));
    const tinygltf::Node &node = model_.nodes[size_t(nodeIndex)];
    Matrix4 local;
    try {
        local = NodeLocalMatrix(node, loc_);
    } catch (const SceneError &e) {
        Fail(e.Message());
    }
    Matrix4 world = parent * local;
    if (node.mesh >= 0 && node.skin >= 0) {
        // Skinned: the joints place the vertices in the world; the node's transform is not
        // applied (glTF 2.0 §3.7.3).
        AddMesh(node.mesh, Transform(), node.weights, node.skin);
    } else if (node.mesh >= 0 && node.extensions.count("EXT_mesh_gpu_instancing")) {
        AddMeshInstances(node, world);
    } else if (node.mesh >= 0) {
        Transform t;
        bool ok = true;
        try {
            t = Transform(world);
        } catch (const std::invalid_argument &) {
            ok = false;  // zero scale hides a node; nothing to render
        }
        if (ok) AddMesh(node.mesh, t, node.weights);
    }
    if (node.camera >= 0 && !haveCamera_ && (wantedCamera_ < 0 || node.camera == wantedCamera_))
        AddCamera(node, world);
    AddLight(node, world);
    path.push_back(nodeIndex);
    for (int c : node.children) Traverse(c, world, path);
    path.pop_back();
}

void GltfConverter::CheckExpansion(const std::vector<int> &roots) const {
    if (!budget_) return;
    static constexpr uint64_t kSaturated = uint64_t(1) << 62;
    auto add = [](uint64_t a, uint64_t b) { return std::min(kSaturated, a + b); };
    const size_t n = model_.nodes.size();
    // Per node: the node instances and mesh instances below it (itself included); 0 = not yet
    // counted. A cycle or a missing node counts nothing here (Traverse reports it).
    std::vector<uint64_t> nodes(n, 0), meshes(n, 0);
    std::vector<char> state(n, 0);  // 1: being counted, 2: done
    auto count = [&](auto &self, int i, int depth) -> void {
        if (i < 0 || size_t(i) >= n || state[size_t(i)] != 0 || depth > 1001) return;
        state[size_t(i)] = 1;
        const tinygltf::Node &node = model_.nodes[size_t(i)];
        uint64_t total = 1, withMesh = node.mesh >= 0 ? 1 : 0;
        for (int c : node.children) {
            self(self, c, depth + 1);
            if (c >= 0 && size_t(c) < n && state[size_t(c)] == 2) {
                total = add(total, nodes[size_t(c)]);
                withMesh = add(withMesh, meshes[size_t(c)]);
            }
        }
        nodes[size_t(i)] = total;
        meshes[size_t(i)] = withMesh;
        state[size_t(i)] = 2;
    };
    uint64_t total = 0, withMesh = 0;
    for (int r : roots) {
        count(count, r, 0);
        if (r >= 0 && size_t(r) < n && state[size_t(r)] == 2) {
            total = add(total, nodes[size_t(r)]);
            withMesh = add(withMesh, meshes[size_t(r)]);
        }
    }
    auto mul = [&](uint64_t a, uint64_t b) { return a > kSaturated / b ? kSaturated : a * b; };
    const uint64_t bytes = std::min(
        kSaturated, mul(total, kBytesPerNodeInstance) + mul(withMesh, kBytesPerMeshInstance));
    auto shown = [&](uint64_t v) {
        return v >= kSaturated ? std::string("more than 2^62") : std::to_string(v);
    };
    budget_->Check(bytes,
                   "the node graph (" + shown(total) + " node instances, " + shown(withMesh) +
                       " of them meshes: nodes share children)",
                   loc_);
}

namespace {

// The glTF extensions Prism simulates: wholly, or without the textures listed (each with
// what is used instead).
struct IgnoredTexture {
    const char *name, *instead;
};
struct SimulatedExtension {
    const char *name;
    std::vector<IgnoredTexture> ignoredTextures;
};
const SimulatedExtension kSimulated[] = {
    {"KHR_lights_punctual", {}},
    {"KHR_materials_ior", {}},
    {"KHR_materials_emissive_strength", {}},
    {"KHR_texture_transform", {}},
    {"KHR_mesh_quantization", {}},
    {"EXT_mesh_gpu_instancing", {}},
    {"KHR_materials_transmission", {{"transmissionTexture", "transmissionFactor alone"}}},
    {"KHR_materials_specular",
     {{"specularTexture", "specularFactor alone"},
      {"specularColorTexture", "specularColorFactor alone"}}},
    {"KHR_materials_clearcoat",
     {{"clearcoatTexture", "clearcoatFactor alone"},
      {"clearcoatRoughnessTexture", "clearcoatRoughnessFactor alone"},
      {"clearcoatNormalTexture", "the base's shading normal"}}},
};

const SimulatedExtension *FindSimulated(const std::string &name) {
    for (const SimulatedExtension &e : kSimulated)
        if (name == e.name) return &e;
    return nullptr;
}

// What a file loses when Prism ignores an extension it uses, for the ones whose loss is not
// obvious from the name.
std::string IgnoredBecause(const std::string &name) {
    static const std::map<std::string, std::string> why = {
        {"KHR_materials_volume",
         "transmissive surfaces are thin: no refraction through the "
         "volume and no attenuation tint"},
        {"KHR_materials_sheen", "no sheen lobe"},
        {"KHR_materials_iridescence", "no thin-film colours"},
        {"KHR_materials_anisotropy", "highlights are isotropic"},
        {"KHR_materials_unlit", "unlit materials are shaded as lit ones"},
        {"KHR_materials_dispersion", "one index of refraction for every colour"},
        {"KHR_materials_variants", "the materials the file names by default are used"},
    };
    auto it = why.find(name);
    return it == why.end() ? "" : " (" + it->second + ")";
}

}  // namespace

// Every extension the file uses that Prism does not simulate is named once, with what it
// costs where that is known; so are the extension textures that are read as factors only.
// An extension the file requires but Prism does not simulate is an error: the file says it
// cannot be rendered without it.
void GltfConverter::CheckExtensions() {
    for (const std::string &e : model_.extensionsUsed)
        quantization_ = quantization_ || e == "KHR_mesh_quantization";
    for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
        const std::string &e = model_.extensionsRequired[i];
        if (FindSimulated(e)) continue;
        const Where where(*this, "/extensionsRequired/" + std::to_string(i));
        Fail("the file requires glTF extension " + e + ", which Prism does not support" +
             IgnoredBecause(e));
    }
    for (const std::string &e : model_.extensionsUsed)
        if (!FindSimulated(e))
            diag_.Warn(loc_, "glTF extension " + e + " is not supported and is ignored" +
                                 IgnoredBecause(e));
    // The partly simulated ones: each ignored texture once, with the first material using it
    // and how many do.
    for (const SimulatedExtension &e : kSimulated)
        for (const IgnoredTexture &texture : e.ignoredTextures) {
            int count = 0;
            std::string first;
            for (size_t mi = 0; mi < model_.materials.size(); ++mi) {
                const tinygltf::Material &m = model_.materials[mi];
                auto it = m.extensions.find(e.name);
                if (it == m.extensions.end() || !it->second.IsObject() ||
                    !it->second.Has(texture.name))
                    continue;
                if (count++ == 0)
                    first = m.name.empty() ? "material " + std::to_string(mi)
                                           : "material \"" + m.name + "\"";
            }
            if (count == 0) continue;
            diag_.Warn(loc_, std::string(e.name) + " " + texture.name + " is ignored (" +
                                 texture.instead + " is used), in " + first +
                                 (count > 1 ? " and " + std::to_string(count - 1) + " more"
                                            : std::string()));
        }
}

void GltfConverter::ResolveCamera() {
    if (cameraName_.empty()) return;
    for (size_t i = 0; i < model_.cameras.size(); ++i)
        if (model_.cameras[i].name == cameraName_) {
            wantedCamera_ = int(i);
            return;
        }
    const bool digits = cameraName_.find_first_not_of("0123456789") == std::string::npos;
    if (digits && cameraName_.size() < 10 &&
        size_t(std::stoi(cameraName_)) < model_.cameras.size()) {
        wantedCamera_ = std::stoi(cameraName_);
        return;
    }
    std::string names;
    for (size_t i = 0; i < model_.cameras.size(); ++i)
        names += (i ? ", " : "") + std::to_string(i) +
                 (model_.cameras[i].name.empty() ? "" : " \"" + model_.cameras[i].name + "\"");
    Fail("--camera " + Quote(cameraName_) + ": the file has no such camera (" +
         (names.empty() ? std::string("it has none") : "its cameras: " + names) + ")");
}

void GltfConverter::CheckCameraFound() const {
    if (wantedCamera_ >= 0 && !haveCamera_)
        Fail("--camera " + Quote(cameraName_) + ": no node of the scene uses camera " +
             std::to_string(wantedCamera_));
}

void GltfConverter::Read() {
    CheckExtensions();
    ConvertMaterials();
    ResolveCamera();
    if (model_.scenes.empty()) {
        // No scene: glTF allows this for libraries of assets; render every root node.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node &n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
        std::vector<int> roots;
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
        CheckExpansion(roots);
        std::vector<int> path;
        for (int r : roots) Traverse(r, Matrix4::Identity(), path);
        CheckCameraFound();
        return;
    }
    int sceneIndex = model_.defaultScene;
    if (sceneIndex < 0 || size_t(sceneIndex) >= model_.scenes.size()) sceneIndex = 0;
    CheckExpansion(model_.scenes[size_t(sceneIndex)].nodes);
    const Where where(*this, "/scenes/" + std::to_string(sceneIndex) + "/nodes");
    std::vector<int> path;
    for (int n : model_.scenes[size_t(sceneIndex)].nodes) Traverse(n, Matrix4::Identity(), path);
    CheckCameraFound();
}

}  // namespace gltf_internal

SceneDescription ReadGltfFile(const std::string &path, Diagnostics &diag, uint64_t maxMemory) {
    MemoryBudget budget(maxMemory);
    return ReadGltfFile(path, diag, budget);
}

SceneDescription ReadGltfFile(const std::string &path, Diagnostics &diag, MemoryBudget &memory,
                              const std::string &camera) {
    using namespace gltf_internal;
    FileLoc loc{path};
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw SceneError(loc, "cannot open file \"" + path + "\"");

    tinygltf::Model model;
    tinygltf::TinyGLTF ctx;
    ReadBudget budget{memory, path, std::nullopt};
    budget.model = &model;
    ctx.SetImageLoader(&KeepEncodedBytes, &budget);
    // Every file tinygltf touches goes through Prism's reader (core/file_io.h): no FIFO or
    // device is opened, and --confine holds before anything is opened.
    ctx.SetFsCallbacks({&FileExistsWithoutOpening, &KeepFilePath, &ReadWholeFileWithinBudget,
                        &RefuseToWrite, &budget});
    std::string err, warn;
    bool ok;
    try {
        ok = LowerExtension(path) == ".glb" ? ctx.LoadBinaryFromFile(&model, &err, &warn, path)
                                            : ctx.LoadASCIIFromFile(&model, &err, &warn, path);
    } catch (const std::exception &e) {
        throw SceneError(loc, std::string("cannot parse glTF file: ") + e.what());
    }
    if (budget.refused) throw *budget.refused;
    if (budget.tooDeep) throw *budget.tooDeep;
    // A buffer or image that could not be read, named by its URI as the file writes it.
    for (auto [failed, reason] : {std::pair{&budget.confinedPath, &budget.confinedReason},
                                  std::pair{&budget.failedPath, &budget.failedReason}}) {
        if (failed->empty()) continue;
        std::string uri;
        const FileLoc at = gltf_internal::LocateUri(path, *failed, &uri);
        throw SceneError(at, "cannot read file " + Quote(uri) + ": " + *reason);
    }
    for (const std::string &w : MessageLines(warn)) diag.Warn(loc, w);
    if (!ok) {
        std::vector<std::string> errs = MessageLines(err);
        throw SceneError(loc, errs.empty() ? std::string("cannot parse glTF file")
                                           : "cannot parse glTF file: " + errs.front());
    }

    SceneDescription desc;
    desc.format = "gltf";
    // glTF names no integrator: Prism's distribution integrator (rough metals reflect).
    desc.integrator.type = "distribution";
    desc.sourceFile = path;
    desc.baseDir = DirectoryOf(path);
    GltfConverter converter(model, path, diag, desc);
    converter.SetBudget(&memory);
    converter.SetCamera(camera);
    converter.Read();
    // What the description keeps after the model is freed: mesh parameters and embedded images.
    uint64_t geometry = 0, images = 0;
    for (const ShapeDesc &s : desc.shapes) geometry += ParamStorageBytes(s.params);
    for (const ObjectDesc &o : desc.objects)
        for (const ShapeDesc &s : o.shapes) geometry += ParamStorageBytes(s.params);
    for (const EmbeddedImage &e : desc.embeddedImages) images += e.bytes.size();
    memory.Charge(geometry, "glTF geometry", loc);
    memory.Charge(images, "embedded images", loc);
    return desc;
}

}  // namespace prism
