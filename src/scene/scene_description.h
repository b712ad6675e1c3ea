// Plain-data scene description between the scene readers (pbrt, OBJ, glTF) and the renderer.
// Nothing here knows about Embree; every entity keeps the location it came from so later
// stages can report errors against the scene file.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/transform.h"
#include "scene/paramset.h"
#include "scene/pbrt_version.h"

namespace prism {

// A directive with a type name ("sphere", "matte", ...), its parameters and its location.
struct SceneEntity {
    std::string type;
    ParamSet params;
    FileLoc loc;
    // pbrt-v4's ColorSpace in effect at the directive: its RGB parameters were written in it
    // (MakeParamSet has mapped them to sRGB), and a light's default white is its white.
    ColorSpaceId colorSpace = ColorSpaceId::SRGB;
};

// pbrt-v3 ActiveTransform/TransformTimes: a directive's CTM at the end time, when it differs
// from the start-time CTM (the entity's own transform), and the keyframes' times (the last
// TransformTimes, default 0 1). `loc` is the ActiveTransform directive that made the two
// differ (the reason motion blur is on).
struct TransformMotion {
    Transform end;
    double startTime = 0, endTime = 1;
    FileLoc loc;
};

struct CameraDesc : SceneEntity {
    Transform cameraFromWorld;              // CTM at the Camera directive (start time)
    std::optional<TransformMotion> motion;  // cameraFromWorld at the end time, if it moves
    bool specified = false;                 // false → reader default (perspective, identity)
    // The camera's medium (pbrt-v3 CameraMedium: the outside medium of the MediumInterface
    // current at Camera; index into SceneDescription::media, -1: none) and that directive.
    int medium = -1;
    FileLoc mediumLoc;
};

struct TextureDesc : SceneEntity {
    std::string name;
    bool isFloat = false;  // "float" vs "spectrum"/"color"
    Transform worldFromTexture;
};

struct MaterialDesc : SceneEntity {
    std::string name;  // for named materials; "" for anonymous Material directives
};

// MakeNamedMedium: type "homogeneous" or "heterogeneous" (the "type" parameter), with the CTM
// at the directive (a grid's placement).
struct MediumDesc : SceneEntity {
    std::string name;
    Transform worldFromMedium;
};

struct LightDesc : SceneEntity {
    Transform worldFromLight;
    // The outside medium of the MediumInterface current at LightSource (pbrt-v3: the medium
    // its emitted rays begin in; index into SceneDescription::media, -1: vacuum).
    int medium = -1;
};

struct AreaLightDesc : SceneEntity {
    // type "diffuse"; params L, scale, twosided, nsamples
};

struct ShapeDesc : SceneEntity {
    Transform worldFromObject;              // at the start time
    std::optional<TransformMotion> motion;  // worldFromObject at the end time, if it moves
    bool reverseOrientation = false;
    int material = -1;       // index into SceneDescription::materials; -1 = the default matte
    int areaLight = -1;      // index into SceneDescription::areaLights; -1 = not emissive
    int directiveIndex = 0;  // 0-based Shape directive order in the top-level file
    std::string name;        // OBJ object/group name, glTF mesh name ("" for pbrt shapes)
    // MediumInterface (indices into SceneDescription::media; -1: vacuum) and its directive.
    int mediumInside = -1, mediumOutside = -1;
    FileLoc mediumLoc;
};

// What a ShapeDesc holds in memory, for the memory budget: the struct, its strings and its
// parameters (ParamStorageBytes).
uint64_t ShapeDescBytes(const ShapeDesc &s);

// ObjectBegin/ObjectEnd: shapes recorded with the CTM at their declaration.
struct ObjectDesc {
    std::string name;
    FileLoc loc;
    std::vector<ShapeDesc> shapes;
};

// CSGBegin "union"|"intersection"|"difference" ... CSGEnd (a Prism extension, docs/FORMAT.md):
// a boolean operation over operand shapes (each with the CTM, material and orientation of its
// Shape directive) and nested nodes, in directive order.
struct CsgDesc {
    std::string op;  // "union", "intersection" or "difference" (checked by the scene builder)
    FileLoc loc;     // the CSGBegin directive
    struct Operand {
        bool shape = true;  // a Shape (index into shapes) or a nested node (into children)
        int index = 0;
    };
    std::vector<ShapeDesc> shapes;
    std::vector<CsgDesc> children;
    std::vector<Operand> operands;
};

struct InstanceDesc {
    std::string object;
    Transform worldFromInstance;            // at the start time
    std::optional<TransformMotion> motion;  // worldFromInstance at the end time, if it moves
    FileLoc loc;
};

// An image stored inside a scene file (glTF data URI or .glb bufferView). Textures refer to
// it with the filename "embedded:<index into SceneDescription::embeddedImages>".
struct EmbeddedImage {
    std::string name;
    std::string mimeType;  // "image/png", "image/jpeg", ... ("" if the file did not say)
    std::vector<unsigned char> bytes;  // the encoded file, not decoded pixels
};

// Index named by an "embedded:<i>" texture filename, or -1 for an ordinary path.
inline int EmbeddedImageIndex(const std::string &filename) {
    const std::string prefix = "embedded:";
    if (filename.compare(0, prefix.size(), prefix) != 0 || filename.size() == prefix.size())
        return -1;
    int v = 0;
    for (size_t i = prefix.size(); i < filename.size(); ++i) {
        if (filename[i] < '0' || filename[i] > '9' || v > 100000000) return -1;
        v = v * 10 + (filename[i] - '0');
    }
    return v;
}

struct SceneDescription {
    CameraDesc camera;
    SceneEntity film{"image", {}, {}};
    SceneEntity sampler{"halton", {}, {}};
    // pbrt-v4's Option directives, merged (a later value of a name wins): what the assembly
    // reads of them, assembly/scene_options.h.
    ParamSet options;
    SceneEntity filter{"box", {}, {}};
    SceneEntity integrator{"path", {}, {}};
    std::vector<ShapeDesc> shapes;
    std::vector<MaterialDesc> materials;
    std::vector<TextureDesc> textures;
    std::vector<LightDesc> lights;
    std::vector<AreaLightDesc> areaLights;
    std::vector<ObjectDesc> objects;
    std::vector<InstanceDesc> instances;
    std::vector<CsgDesc> csg;       // top-level CSG nodes (nested ones are their children)
    std::vector<MediumDesc> media;  // MakeNamedMedium, in directive order
    std::string baseDir;            // directory of the top-level file: relative paths resolve here
    std::string sourceFile;         // the top-level file
    std::string format;             // "pbrt", "obj", "gltf", "ply"
    // The version of the pbrt format whose rules the file was read by (pbrt files only;
    // scene/pbrt_version.h) and what chose it.
    PbrtVersionChoice pbrtVersion;
    bool studioRig = false;  // the lights are Prism's studio rig (AddStudioRig)
    std::vector<EmbeddedImage> embeddedImages;
    // Informational notes from the reader about what it supplied or interpreted, e.g. "no
    // camera in file: framed the bounding box" (not warnings: nothing is wrong with the file).
    std::vector<std::string> notes;
};

// The ObjectBegin group an ObjectInstance named `name` refers to, or nullptr: the last
// definition, as in pbrt-v3 (a redefinition replaces the object). The one lookup of objects by
// name: the pbrt scene builder, the render-scene builder and `prism info` use it.
const ObjectDesc *FindObject(const SceneDescription &desc, const std::string &name);

// A path from a scene file (Include, .spd, texture, PLY, ...) resolved against `baseDir`, the
// directory of the top-level file (pbrt-v3 semantics); absolute paths are returned unchanged.
// Every reader and the renderer resolve scene paths here.
std::string ResolveScenePath(const std::string &baseDir, const std::string &file);
inline std::string ResolveScenePath(const SceneDescription &desc, const std::string &file) {
    return ResolveScenePath(desc.baseDir, file);
}

// Whether `canonicalPath` (see CanonicalPath in core/file_io.h) lies inside the directory
// `dir` ("" is the current directory): the confinement of PbrtParseOptions::confineIncludes.
bool IsInsideDirectory(const std::string &canonicalPath, const std::string &dir);

}  // namespace prism
