// Entry point for reading any supported scene file: dispatches on the extension (.pbrt, .obj,
// .gltf/.glb, .ply, .stl) and, for formats without a camera or lights, supplies sensible defaults.
#pragma once

#include <string>
#include <vector>

#include "core/color.h"
#include "core/memory.h"
#include "core/vecmath.h"
#include "scene/pbrt_parser.h"
#include "scene/scene_description.h"

namespace prism {

struct LoadOptions {
    PbrtParseOptions pbrt;
    // For OBJ/glTF/PLY input: frame the geometry when the file has no camera, and add lights
    // when it has neither lights nor emissive materials. (pbrt files keep pbrt's defaults.)
    bool defaultCamera = true;
    bool defaultLights = true;
    // The render's memory budget (core/memory.h). LoadScene charges to it every scene file it
    // reads (the top-level file and every Include; OBJ and MTL; glTF, its buffers and embedded
    // images) and the mesh parameters it builds or parses (trianglemesh arrays, OBJ and glTF
    // geometry); the charges are kept, so the builder and the renderer charge the rest to the
    // same budget. A top-level .ply is checked too, but its charge is given back: the builder
    // reads the mesh again through the "plymesh" shape and charges it then. Anything that would
    // exceed it is refused with a MemoryBudgetError (a SceneError) before it is read or allocated.
    // When null, a budget of `maxMemory` bytes (0: 75% of physical RAM) is used for this call
    // alone.
    MemoryBudget *budget = nullptr;
    uint64_t maxMemory = 0;
    // glTF: the camera to view through, by name or index (--camera); "": the first the scene
    // reaches. Other formats have one camera at most: naming one is an error.
    std::string camera;
};

// Throws SceneError: `cannot open file "..."` for a missing file, `unsupported scene format
// ".xyz" (...)` for an unknown extension, and whatever the format's reader reports.
// LoadScene dispatches on the extension to ParsePbrtFile (pbrt_parser.h), ReadObjFile
// (obj_reader.h), ReadGltfFile (gltf_reader.h) or ReadPlyFile (ply_reader.h).
SceneDescription LoadScene(const std::string &path, Diagnostics &diag,
                           const LoadOptions &opts = {});

// Whether LoadScene reads files with this extension (".pbrt", ".obj", ".gltf", ".glb",
// ".ply"; any case). The one list of scene formats: `prism batch` collects scenes with it.
bool IsSceneExtension(const std::string &extension);
// The same list for messages: ".pbrt, .obj, .gltf, .glb, .ply or .stl".
std::string SceneExtensionList();

// The files a scene file names directly, as canonical paths (CanonicalPath): for pbrt, the
// targets of Include/Import and every "string filename" parameter (plymesh meshes, image
// textures, ...), found with the pbrt tokenizer, not resolved recursively; other formats
// return nothing. `prism batch DIR` uses it so that a mesh or an included file inside a scene
// folder is not rendered as a scene of its own. The file is read in chunks and tokenized a
// line at a time, so the scan holds at most one line (cut at 1 MiB), never the whole file;
// only regular files are read. Unreadable or malformed files give what was found (the render
// reports the problem itself).
std::vector<std::string> ReferencedFiles(const std::string &sceneFile);

// World-space bounds of the scene's "trianglemesh" shapes (P through worldFromObject, for
// top-level shapes and object instances). Other shape types are not included.
Bounds3f SceneMeshBounds(const SceneDescription &desc);

// Sets a perspective camera (fov 40 degrees on the shorter axis, +y up) looking at the centre
// of `bounds` from the front, right and above, far enough for the bounding sphere to fit.
void FrameDefaultCamera(SceneDescription &desc, const Bounds3f &bounds);

// The studio rig every OBJ, glTF or PLY file without lights (and without emissive materials)
// gets (docs/USAGE.md "Lighting"): a distant key light of L = 2.5 from above the camera, slightly
// left and behind the viewer; a distant fill of L = 0.6 from the camera's right at a low angle;
// and a dim uniform environment of L = 0.15 (16 samples), which is also the background. The key
// and fill directions follow desc.camera (framed by the model's bounds when the file has none),
// so call it after the camera is final; being distant and infinite lights, they light a model
// the same whatever its size or units.
void AddStudioRig(SceneDescription &desc);

// --env: an environment light added to (or replacing) a scene's lights.
struct EnvironmentSpec {
    std::string mapFile;   // an equirectangular .exr or .hdr (absolute or relative to the cwd)
    RGB L{1};              // the uniform radiance without a map; the map's scale with one
    double rotateDeg = 0;  // about the up axis, counterclockwise seen from above
    bool replace = true;   // drop every LightSource (and the studio rig) first
    int nSamples = 16;     // shadow rays per shading point (--light-samples overrides)
};

// The scene's up axis for environments: +y for OBJ, glTF and PLY; for pbrt scenes the world axis
// nearest to the camera's up direction.
Vec3d SceneUpAxis(const SceneDescription &desc);

// worldFromLight for an equirectangular map on pbrt's "infinite" light (map row 0 is the light's
// +z pole), chosen so that the map's top row is the scene's up axis, its centre column faces the
// scene's forward axis (-z for y-up formats; for pbrt scenes the world axis nearest to the
// camera's view direction), u grows to the right of a viewer facing that way (the usual
// panorama convention, not pbrt-v3's mirrored one; in pbrt scenes, the side the camera shows on
// the image's right) and the whole is turned by `rotateDeg` about up, counterclockwise seen
// from above (+90 brings what was ahead to the viewer's left).
Transform EnvironmentFrame(const SceneDescription &desc, double rotateDeg);

// Adds the environment as an "infinite" LightSource (with "mapname" when it has a map), after
// removing every LightSource when spec.replace. Emissive shapes (area lights) keep emitting.
void AddEnvironment(SceneDescription &desc, const EnvironmentSpec &spec);

}  // namespace prism
