// Format dispatch plus the defaults (camera framing, key/fill lights) that OBJ, glTF and PLY
// scenes need because those formats usually carry neither.
#include "scene/load_scene.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/file_io.h"
#include "core/memory.h"
#include "scene/gltf_reader.h"
#include "scene/obj_reader.h"
#include "scene/param_builders.h"
#include "scene/ply_reader.h"
#include "scene/stl_reader.h"
#include "scene/tokenizer.h"

namespace prism {

namespace {

using namespace reader;

// The largest world-space coordinate of an OBJ, glTF or PLY model Prism frames and renders.
constexpr double MaxModelCoordinate = 1e30;

void ExpandMesh(const ShapeDesc &s, const Transform &worldFromObject, Bounds3f &b) {
    if (s.type != "trianglemesh") return;
    const Param *p = s.params.Find("P");
    if (!p || p->type != ParamType::Point3) return;
    for (size_t i = 0; i + 2 < p->numbers.size(); i += 3) {
        Vec3d w = worldFromObject.Point(Vec3d(p->numbers[i], p->numbers[i + 1], p->numbers[i + 2]));
        // A transform (a glTF node scaled by 1e300, say) can take finite positions beyond what
        // a float holds, and no camera can frame or render them.
        if (!(std::abs(w.x) <= MaxModelCoordinate && std::abs(w.y) <= MaxModelCoordinate &&
              std::abs(w.z) <= MaxModelCoordinate))
            throw SceneError(s.loc, "the transform of this mesh puts vertex " +
                                        std::to_string(i / 3) +
                                        " beyond 1e30 (or at a non-finite position): it cannot "
                                        "be rendered");
        b.Expand(Vec3f(w));
    }
}

// The coordinate axis (with its sign) nearest to v among those orthogonal to `exclude` (any
// axis when `exclude` is zero).
Vec3d NearestAxis(const Vec3d &v, const Vec3d &exclude) {
    Vec3d best(0, 0, 0);
    double bestDot = -1;
    for (int i = 0; i < 3; ++i) {
        Vec3d axis(0, 0, 0);
        axis[i] = 1;
        if (std::abs(Dot(axis, exclude)) > 0.5) continue;
        double d = std::abs(v[i]);
        if (d > bestDot) {
            bestDot = d;
            best = axis * (v[i] < 0 ? -1.0 : 1.0);
        }
    }
    return best;
}

bool HasEmitters(const SceneDescription &desc) {
    if (!desc.lights.empty()) return true;
    // Emissive textures (glTF emissiveTexture: panels, screens, decals) light their
    // surroundings but do not light a model: only untextured emitters (a Cornell box's lamp)
    // count, so a model that has only emissive textures still gets the studio rig.
    for (const ShapeDesc &s : desc.shapes)
        if (s.areaLight >= 0 && size_t(s.areaLight) < desc.areaLights.size() &&
            !desc.areaLights[size_t(s.areaLight)].params.Has("emissionmap"))
            return true;
    return false;
}

SceneDescription LoadPlyScene(const std::string &path, Bounds3f *bounds, MemoryBudget &budget) {
    // Read once here for the bounds (and to report a broken file early, or one that does not
    // fit in the budget); the renderer reads it again through the "plymesh" shape and charges
    // it then, so this read's charge is given back. Warnings are left to that second read.
    Diagnostics scratch;
    uint64_t usedBefore = budget.Used();
    {
        PlyMesh mesh = ReadPlyFile(path, scratch, budget);
        for (const Vec3f &p : mesh.P) bounds->Expand(p);
    }
    budget.Release(budget.Used() - usedBefore);
    SceneDescription desc;
    desc.format = "ply";
    // A PLY file names no integrator: Prism's distribution integrator, as for OBJ and glTF.
    desc.integrator.type = "distribution";
    desc.sourceFile = path;
    desc.baseDir = DirectoryOf(path);
    ShapeDesc s;
    s.type = "plymesh";
    s.loc = FileLoc{path};
    AddString(s.params, "filename", std::filesystem::path(path).filename().string(), s.loc);
    desc.shapes.push_back(std::move(s));
    return desc;
}

}  // namespace

// Every format LoadScene reads, in the order messages list them.
constexpr const char *kSceneExtensions[] = {".pbrt", ".obj", ".gltf", ".glb", ".ply", ".stl"};

bool IsSceneExtension(const std::string &extension) {
    const std::string lower = ToLowerAscii(extension);
    for (const char *e : kSceneExtensions)
        if (lower == e) return true;
    return false;
}

std::string SceneExtensionList() {
    std::string list;
    const size_t n = std::size(kSceneExtensions);
    for (size_t i = 0; i < n; ++i)
        list += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + kSceneExtensions[i];
    return list;
}

std::vector<std::string> ReferencedFiles(const std::string &sceneFile) {
    std::vector<std::string> files;
    if (LowerExtension(sceneFile) != ".pbrt") return files;
    // Read in chunks and tokenized a line at a time (no pbrt token spans lines: strings end
    // before a newline, comments at it), so a scene file of any size takes a line's memory,
    // at most kMaxLine: a longer line is cut there (a token cut in two is lost).
    constexpr size_t kMaxLine = size_t(1) << 20;
    const int fd = ::open(sceneFile.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return files;
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {  // a FIFO or device never ends
        ::close(fd);
        return files;
    }
    const std::string dir = DirectoryOf(sceneFile);
    auto add = [&](const Token &t) {
        files.push_back(CanonicalPath(ResolveScenePath(dir, Tokenizer::StringValue(t))));
    };
    // What the tokens so far expect: Include/Import "FILE", "string filename" [ "FILE" ].
    enum class Expect { Nothing, IncludedFile, Filename, FilenameInBrackets };
    Expect expect = Expect::Nothing;
    auto scanLine = [&](std::string line) {
        try {
            Tokenizer tok(std::move(line), sceneFile);
            for (Token t = tok.Next(); t.kind != TokenKind::End; t = tok.Next()) {
                const Expect was = expect;
                expect = Expect::Nothing;
                if (t.kind == TokenKind::Word && (t.text == "Include" || t.text == "Import")) {
                    expect = Expect::IncludedFile;
                } else if (t.kind == TokenKind::LBracket && was == Expect::Filename) {
                    expect = Expect::FilenameInBrackets;
                } else if (t.kind == TokenKind::String) {
                    if (was != Expect::Nothing) {
                        add(t);
                        continue;
                    }
                    // "string filename" "x.ply" or "string filename" [ "x.ply" ]
                    std::string decl(t.text);
                    char type[16], name[16], extra;
                    if (decl.size() <= 40 &&
                        std::sscanf(decl.c_str(), " %15s %15s %c", type, name, &extra) == 2 &&
                        std::strcmp(type, "string") == 0 && std::strcmp(name, "filename") == 0)
                        expect = Expect::Filename;
                }
            }
        } catch (const SceneError &) {
            // Malformed: keep what was found; the render of this scene reports the error.
            expect = Expect::Nothing;
        }
    };
    std::string line;
    char chunk[1 << 16];
    while (true) {
        const ssize_t n = ::read(fd, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        for (ssize_t i = 0; i < n; ++i) {
            if (chunk[i] == '\n' || line.size() >= kMaxLine) {
                scanLine(std::move(line));
                line.clear();
                if (chunk[i] == '\n') continue;
            }
            line += chunk[i];
        }
    }
    ::close(fd);
    scanLine(std::move(line));
    return files;
}

Bounds3f SceneMeshBounds(const SceneDescription &desc) {
    Bounds3f b;
    for (const ShapeDesc &s : desc.shapes) ExpandMesh(s, s.worldFromObject, b);
    for (const InstanceDesc &inst : desc.instances)
        if (const ObjectDesc *obj = FindObject(desc, inst.object))
            for (const ShapeDesc &s : obj->shapes)
                ExpandMesh(s, inst.worldFromInstance * s.worldFromObject, b);
    return b;
}

void FrameDefaultCamera(SceneDescription &desc, const Bounds3f &bounds) {
    const double fovDeg = 40;
    Vec3d centre(0, 0, 0);
    double radius = 1;
    if (!bounds.IsEmpty()) {
        centre = Vec3d(bounds.Center());
        radius = 0.5 * Length(Vec3d(bounds.Diagonal()));
        if (!(radius > 0) || !std::isfinite(radius)) radius = 1;
    }
    // fov spans the shorter image axis, so the bounding sphere fits at this distance whatever
    // the aspect ratio.
    double dist = radius / std::sin(Radians(fovDeg / 2));
    Vec3d eye = centre + Normalize(Vec3d(0.3, 0.25, 1.0)) * dist;
    CameraDesc &cd = desc.camera;
    cd = CameraDesc{};
    cd.type = "perspective";
    cd.loc = FileLoc{desc.sourceFile};
    // OBJ, glTF and PLY data are right-handed with +y up. pbrt's LookAt builds a left-handed
    // camera frame, which would mirror the image; Scale(-1, 1, 1) in camera space (as pbrt
    // exporters do) restores "world +x appears to the right when looking down -z".
    cd.cameraFromWorld = Scale(-1, 1, 1) * LookAt(eye, centre, Vec3d(0, 1, 0));
    AddFloat(cd.params, "fov", fovDeg, cd.loc);
    cd.specified = true;
}

void AddStudioRig(SceneDescription &desc) {
    desc.studioRig = true;
    FileLoc loc{desc.sourceFile};
    // Camera space has +x to the image's right, +y up and +z ahead for every camera Prism
    // builds (see FrameDefaultCamera and the glTF reader).
    Transform worldFromCamera = desc.camera.cameraFromWorld.Inverse();
    auto AddDistant = [&](Vec3d towardLightCamera, double L) {
        Vec3d w = Normalize(worldFromCamera.Vector(towardLightCamera));
        LightDesc l;
        l.type = "distant";
        l.loc = loc;
        AddRGB(l.params, "L", L, L, L, loc);
        AddPoint3(l.params, "from", w, loc);
        AddPoint3(l.params, "to", Vec3d(0, 0, 0), loc);
        desc.lights.push_back(std::move(l));
    };
    // Key: a white Lambertian surface facing it reflects 2.5 / pi ≈ 0.8.
    AddDistant(Vec3d(-0.35, 1.0, -0.6), 2.5);
    // Fill: keeps the side away from the key from going black.
    AddDistant(Vec3d(1.0, 0.15, -0.3), 0.6);
    // Environment: ambient light in every crevice it reaches, and the background.
    LightDesc env;
    env.type = "infinite";
    env.loc = loc;
    AddRGB(env.params, "L", 0.15, 0.15, 0.15, loc);
    AddInts(env.params, "nsamples", {16}, loc);
    desc.lights.push_back(std::move(env));
}

Vec3d SceneUpAxis(const SceneDescription &desc) {
    if (desc.format != "pbrt") return Vec3d(0, 1, 0);
    Vec3d up = desc.camera.cameraFromWorld.Inverse().Vector(Vec3d(0, 1, 0));
    return NearestAxis(up, Vec3d(0, 0, 0));
}

Transform EnvironmentFrame(const SceneDescription &desc, double rotateDeg) {
    Vec3d up = SceneUpAxis(desc), forward(0, 0, -1), right(1, 0, 0);
    if (desc.format == "pbrt") {
        // pbrt worlds may be left- or right-handed: "right" is the side the camera shows on
        // the image's right, so the map is never seen mirrored.
        Transform worldFromCamera = desc.camera.cameraFromWorld.Inverse();
        forward = NearestAxis(worldFromCamera.Vector(Vec3d(0, 0, 1)), up);
        right = Cross(forward, up);
        if (Dot(right, worldFromCamera.Vector(Vec3d(1, 0, 0))) < 0) right = -right;
    }
    // Turning by rotateDeg counterclockwise seen from above: forward turns toward the left.
    double c = std::cos(Radians(rotateDeg)), s = std::sin(Radians(rotateDeg));
    Vec3d f = forward * c - right * s, r = right * c + forward * s;
    // Light space: z is the pole (up); pbrt's map u = atan2(y, x) / 2pi, so x = -forward and
    // y = -right put the map's centre (u = 1/2) ahead and u growing to the right. The columns
    // are orthonormal, so the inverse is the transpose (a reflection is fine: only directions
    // go through it).
    Matrix4 m = Matrix4::Identity();
    const Vec3d cols[3] = {-f, -r, up};
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) m.m[size_t(row)][size_t(col)] = cols[col][row];
    return Transform(m, m.Transposed());
}

void AddEnvironment(SceneDescription &desc, const EnvironmentSpec &spec) {
    if (spec.replace) desc.lights.clear();
    FileLoc loc{"--env"};
    LightDesc l;
    l.type = "infinite";
    l.loc = loc;
    l.worldFromLight = EnvironmentFrame(desc, spec.rotateDeg);
    AddRGB(l.params, "L", spec.L.r, spec.L.g, spec.L.b, loc);
    AddInts(l.params, "nsamples", {spec.nSamples}, loc);
    if (!spec.mapFile.empty())
        AddString(l.params, "mapname", std::filesystem::absolute(spec.mapFile).string(), loc);
    desc.lights.push_back(std::move(l));
}

SceneDescription LoadScene(const std::string &path, Diagnostics &diag, const LoadOptions &opts) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw SceneError(FileLoc{path}, "cannot open file \"" + path + "\"");
    const std::string ext = LowerExtension(path);
    if (!IsSceneExtension(ext))
        throw SceneError(FileLoc{path}, "unsupported scene format \"" + ext + "\" (expected " +
                                            SceneExtensionList() + ")");
    if (!opts.camera.empty() && ext != ".gltf" && ext != ".glb")
        throw SceneError(FileLoc{path}, "--camera " + Quote(opts.camera) +
                                            " picks among a glTF file's cameras; a " + ext +
                                            " scene has one camera at most");

    // Every reader holds the whole file in memory (tinyobjloader, tinygltf, PLY, pbrt) and
    // charges it, and what it builds from it, to the budget.
    MemoryBudget ownBudget(opts.budget ? 1 : opts.maxMemory);
    MemoryBudget &budget = opts.budget ? *opts.budget : ownBudget;

    if (ext == ".pbrt") {
        PbrtParseOptions pbrtOpts = opts.pbrt;
        pbrtOpts.budget = &budget;
        return ParsePbrtFile(path, diag, pbrtOpts);
    }

    SceneDescription desc;
    Bounds3f bounds;
    if (ext == ".obj") {
        desc = ReadObjFile(path, diag, &budget);
        bounds = SceneMeshBounds(desc);
    } else if (ext == ".gltf" || ext == ".glb") {
        desc = ReadGltfFile(path, diag, budget, opts.camera);
        bounds = SceneMeshBounds(desc);
    } else if (ext == ".stl") {
        desc = ReadStlFile(path, diag, &budget);
        bounds = SceneMeshBounds(desc);
    } else {
        desc = LoadPlyScene(path, &bounds, budget);
    }
    if (bounds.IsEmpty()) desc.notes.push_back("the scene contains no triangles");
    if (opts.defaultCamera && !desc.camera.specified) {
        FrameDefaultCamera(desc, bounds);
        desc.notes.push_back("no camera in file: framed the bounding box");
    }
    if (opts.defaultLights && !HasEmitters(desc)) {
        AddStudioRig(desc);
        desc.notes.push_back("no lights in file: added the studio rig (key, fill, environment)");
    }
    return desc;
}

}  // namespace prism
