// Internal to the glTF reader (gltf_reader.cpp, gltf_materials.cpp): the converter from a
// tinygltf model to a SceneDescription.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/memory.h"
#include "core/transform.h"
#include "scene/scene_description.h"

namespace prism::gltf_internal {

// Validated view of one accessor's elements: in its buffer, or (an accessor without a buffer
// view, or a sparse one) in `owned`, the elements made whole.
struct AccessorView {
    const unsigned char *data = nullptr;
    size_t count = 0, stride = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
    std::shared_ptr<const std::vector<unsigned char>> owned;
};

// The element types a vertex attribute accepts (View checks them): floats, glTF's normalized
// integers, and what KHR_mesh_quantization adds.
enum class AttributeKind {
    Position,   // float; with quantization (un)signed byte or short, normalized or not
    Direction,  // NORMAL, TANGENT: float; with quantization normalized signed byte or short
    TexCoord,   // float, normalized unsigned byte or short; with quantization any (un)signed
                // byte or short, normalized or not
};

// glTF's T · R · S: translation t, quaternion q (x, y, z, w; normalized here), scale s.
Matrix4 TrsMatrix(const double t[3], const double q[4], const double s[3]);

// One component of element i as double (normalized integers in [0, 1] / [-1, 1]).
double Component(const AccessorView &v, size_t i, int c);

// A number in a material's glTF extension object (`def` if absent).
double ExtNumber(const tinygltf::ExtensionMap &ext, const char *extName, const char *key,
                 double def);

class GltfConverter {
  public:
    // Each node instance (a node reached by one path from a root) and each mesh instance
    // counted against the budget before the graph is expanded: nodes that share children
    // can name 2^40 paths in 2 KB.
    static constexpr uint64_t kBytesPerNodeInstance = 128;   // its world matrix, the visit
    static constexpr uint64_t kBytesPerMeshInstance = 1024;  // a ShapeDesc and its parameters

    GltfConverter(const tinygltf::Model &model, const std::string &path, Diagnostics &diag,
                  SceneDescription &desc)
        : model_(model), loc_{path}, diag_(diag), desc_(desc) {}

    // With a budget (--max-memory), Read refuses a node graph whose expansion does not fit.
    void SetBudget(const MemoryBudget *budget) { budget_ = budget; }
    // The camera to view through (--camera): a camera's name or index; "" the first reached.
    void SetCamera(const std::string &camera) { cameraName_ = camera; }
    void Read();

  private:
    AccessorView View(int accessorIndex, const std::string &what);
    // The bytes [byteOffset, byteOffset + bytes) of buffer view `bufferView`, checked to lie in
    // it and its buffer (`name` and `role` for the errors).
    const unsigned char *ViewBytes(int bufferView, uint64_t byteOffset, uint64_t bytes,
                                   const std::string &name, const std::string &role);
    // Writes the sparse elements of accessor `a` into `elements` (count × elemSize bytes).
    void ApplySparse(const tinygltf::Accessor &a, const std::string &name, uint64_t elemSize,
                     std::vector<unsigned char> &elements);
    // Fails unless v's element type suits a vertex attribute of this kind.
    void CheckAttributeType(const AccessorView &v, AttributeKind kind, const std::string &what);
    std::vector<Vec3f> ReadVec3(int accessor, const std::string &what, AttributeKind kind);
    std::vector<Vec2f> ReadTexcoords(int accessor, const std::string &name = "TEXCOORD_0");
    std::vector<int> ReadIndices(int accessor, size_t vertexCount);

    void Traverse(int node, const Matrix4 &parent, std::vector<int> &path);
    // Checks what traversing `roots` would expand (node and mesh instances, counted per node
    // once, saturating) against budget_.
    void CheckExpansion(const std::vector<int> &roots) const;
    // nodeWeights: the node's morph target weights (empty: the mesh's own); skin: the node's
    // skin (its joints then place the vertices in the world: worldFromObject is identity).
    void AddMesh(int meshIndex, const Transform &worldFromObject,
                 const std::vector<double> &nodeWeights = {}, int skin = -1);
    // A node's world matrix from the nodes' own (rest) transforms, through its parents.
    Matrix4 NodeWorldMatrix(int node);
    // gltf_skin.cpp: P and N moved by skin `skin`'s joints at their rest transforms (linear
    // blend skinning with JOINTS_n/WEIGHTS_n), into world space; *frames: each vertex's
    // blended matrix (for its TANGENT).
    void ApplySkin(int skin, const tinygltf::Primitive &prim, std::vector<Vec3f> &P,
                   std::vector<Vec3f> &N, std::vector<Matrix4> *frames);
    // Adds each morph target's POSITION and NORMAL displacements times its weight to P and N.
    void ApplyMorphTargets(const tinygltf::Primitive &prim, const std::vector<double> &weights,
                           std::vector<Vec3f> &P, std::vector<Vec3f> &N);
    // gltf_instancing.cpp: EXT_mesh_gpu_instancing, node's mesh once per instance (an object
    // instanced by the renderer, or copies when it emits light).
    void AddMeshInstances(const tinygltf::Node &node, const Matrix4 &world);
    void AddCamera(const tinygltf::Node &node, const Matrix4 &world);
    void ResolveCamera();           // cameraName_ → wantedCamera_, or an error naming the cameras
    void CheckCameraFound() const;  // after the traversal: the wanted camera was used
    void AddLight(const tinygltf::Node &node, const Matrix4 &world);
    void CheckExtensions();
    void ConvertMaterials();
    // The scene material of a primitive without one: glTF's default material (base colour 1,
    // metallic 1, roughness 1), added after the file's own on first use.
    int DefaultMaterial();
    std::string TextureFor(int textureIndex, bool linear);
    bool AddMap(ParamSet &ps, const std::string &param, int textureIndex, int texCoord,
                const tinygltf::ExtensionMap &ext, bool linear);
    // The texture coordinate set a textureInfo reads (KHR_texture_transform's texCoord wins);
    // sets other than 0 and 1 are warned about and read as 0. Notes set 1 for `material`.
    int TexCoordOf(int texCoord, const tinygltf::ExtensionMap &ext, int material);
    // "<param>texcoord" 1 and "<param>transform" (KHR_texture_transform) for one texture map.
    void AddTexCoordParams(ParamSet &ps, const std::string &param, int texCoord,
                           const tinygltf::ExtensionMap &ext, int material);
    std::string ImageFilename(int imageIndex);
    // The imagemap "wraps"/"wrapt" of sampler `sampler`'s wrapS and wrapT (none for repeat, the
    // default, and for no sampler).
    void AddSamplerWrap(ParamSet &ps, int sampler);
    // gltf_surface.cpp: normalTexture on a material; alphaMode and TANGENT on a primitive.
    void AddNormalMap(const tinygltf::Material &m, ParamSet &materialParams);
    // skinFrames: a skinned primitive's per-vertex matrices, which move its TANGENTs.
    void AddSurfaceParams(const tinygltf::Primitive &prim, size_t vertices, ParamSet &shapeParams,
                          const std::vector<Matrix4> *skinFrames = nullptr);
    std::string AlphaTextureFor(int material);

    // A SceneError at the JSON value being converted (where_: its line and column in a .gltf,
    // and its JSON pointer in the message), else at the file.
    [[noreturn]] void Fail(const std::string &msg) const;
    // Sets where_ (a JSON pointer such as "/meshes/2/primitives/0") for the guard's scope.
    class Where {
      public:
        Where(const GltfConverter &c, std::string pointer) : c_(c), saved_(std::move(c.where_)) {
            c_.where_ = std::move(pointer);
        }
        ~Where() { c_.where_ = std::move(saved_); }
        Where(const Where &) = delete;
        Where &operator=(const Where &) = delete;

      private:
        const GltfConverter &c_;
        std::string saved_;
    };

    const tinygltf::Model &model_;
    const MemoryBudget *budget_ = nullptr;
    FileLoc loc_;
    Diagnostics &diag_;
    SceneDescription &desc_;
    std::vector<int> areaLightOfMaterial_;
    std::map<int64_t, std::string> textureNames_;  // by index, linear ones at -2 - index
    std::map<int, std::string> imageFilenames_;
    std::map<int, std::string> alphaTextures_;  // material → its alpha texture ("" if none)
    std::set<int> warnedModes_;
    int warnedTexCoord_ = 0;
    int currentMaterial_ = -1;               // the material ConvertMaterials is converting
    std::set<int> materialsUsingTexCoord1_;  // their primitives read TEXCOORD_1 ("uv1")
    bool warnedMissingTexCoord1_ = false;
    bool quantization_ = false;  // KHR_mesh_quantization is in extensionsUsed
    std::string cameraName_;
    int wantedCamera_ = -1;
    std::vector<int> parents_;  // each node's parent (-1: a root), once NodeWorldMatrix needs it
    // Mesh (and the node, when its own morph weights shape it) → its ObjectDesc
    // (EXT_mesh_gpu_instancing).
    std::map<std::pair<int, const tinygltf::Node *>, std::string> meshObjects_;
    int defaultMaterial_ = -1;  // DefaultMaterial's index, once added
    bool haveCamera_ = false;
    mutable std::string where_;  // the JSON pointer of what is being converted ("": the file)
};

// The line and column of the value the JSON pointer `pointer` names in the .gltf file
// `gltfPath` (the whole file for a .glb or a pointer that names nothing).
FileLoc LocateJsonPointer(const std::string &gltfPath, const std::string &pointer);

// The location of the "uri" in the glTF file `gltfPath` that names the file `path` (as
// tinygltf resolved it), or the whole file when none does: for --confine errors. *written
// (if given) is set to the URI as the file writes it (else the file name of `path`), which
// is what the error names: never where the path resolves.
FileLoc LocateUri(const std::string &gltfPath, const std::string &path,
                  std::string *written = nullptr);

}  // namespace prism::gltf_internal
