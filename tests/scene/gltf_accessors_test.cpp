// glTF accessors (scene/gltf_accessors.cpp): KHR_mesh_quantization's integer attributes read
// as the numbers they encode, sparse accessors (over a buffer view or zeros) made whole, clean
// errors for what either gets wrong, morph targets displacing by their default weights, and
// skins posing their meshes at the joints' rest transforms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "scene/gltf_reader.h"
#include "support/errors.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

std::string Replace(const std::string &s, const std::string &from, const std::string &to) {
    EXPECT_NE(s.find(from), std::string::npos) << from;
    return ReplaceFirst(s, from, to);
}

// One triangle whose attributes are quantized: POSITION as shorts (normalized), NORMAL as
// normalized bytes, TEXCOORD_0 as unnormalized unsigned shorts (the node's scale would
// dequantize them in a real file; here the raw values are checked).
std::string QuantizedBuffer() {
    std::string b;
    PutBytes<int16_t>(b, {0, 0, 0, 0, 0, 32767, 0, 0, -32767, 0, 0, 0});  // 3 × (x y z pad): 24 B
    PutBytes<int8_t>(b, {0, 0, 127, 0, 0, 127, 0, 0, -127, 0, 0, 0});     // 3 × (x y z pad): 12 B
    PutBytes<uint16_t>(b, {0, 0, 2, 0, 0, 3});                            // 12 B
    return b;                                                             // 48 B
}

const char *kQuantized = R"({
  "asset": {"version": "2.0"},
  EXTENSIONS
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}]}],
  "buffers": [{"uri": "BUFFER", "byteLength": 48}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 24, "byteStride": 8},
    {"buffer": 0, "byteOffset": 24, "byteLength": 12, "byteStride": 4},
    {"buffer": 0, "byteOffset": 36, "byteLength": 12}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5122, "normalized": true, "count": 3, "type": "VEC3",
     "min": [-1, 0, 0], "max": [0, 1, 0]},
    {"bufferView": 1, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5123, "count": 3, "type": "VEC2"}
  ]
})";

const char *kUsed =
    R"("extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],)";

std::string WriteQuantized(const std::string &name, const std::string &extensions) {
    std::string json = Replace(kQuantized, "EXTENSIONS", extensions);
    json = Replace(json, "BUFFER",
                   "data:application/octet-stream;base64," + Base64(QuantizedBuffer()));
    return WriteScratchFile(name + ".gltf", json);
}

std::string ErrorOf(const std::string &path) {
    return test::ErrorOf<SceneError>([&] {
        Diagnostics diag;
        ReadGltfFile(path, diag);
    });
}

TEST(GltfAccessors, QuantizedAttributesReadAsTheirValues) {
    Diagnostics diag;
    const SceneDescription d = ReadGltfFile(WriteQuantized("gltfa_quant", kUsed), diag);
    ASSERT_EQ(d.shapes.size(), 1u);
    const ParamSet &ps = d.shapes[0].params;
    EXPECT_EQ(ps.GetPoint3s("P"),
              (std::vector<Vec3f>{Vec3f(0, 0, 0), Vec3f(0, 1, 0), Vec3f(-1, 0, 0)}));
    EXPECT_EQ(ps.GetNormals("N"),
              (std::vector<Vec3f>{Vec3f(0, 0, 1), Vec3f(0, 1, 0), Vec3f(-1, 0, 0)}));
    // Unnormalized texture coordinates are the integers (v flipped to pbrt's convention).
    EXPECT_EQ(ps.GetPoint2s("uv"), (std::vector<Vec2f>{Vec2f(0, 1), Vec2f(2, 1), Vec2f(0, -2)}));
    for (const Warning &w : diag.Warnings())
        EXPECT_EQ(w.message.find("KHR_mesh_quantization"), std::string::npos) << w.message;
}

TEST(GltfAccessors, IntegerAttributesNeedTheQuantizationExtension) {
    const std::string e = ErrorOf(WriteQuantized("gltfa_noquant", ""));
    EXPECT_NE(e.find("POSITION accessor must have float components"), std::string::npos) << e;
    EXPECT_NE(e.find("KHR_mesh_quantization"), std::string::npos) << e;
    EXPECT_NE(e.find("gltfa_noquant.gltf"), std::string::npos) << e;
    // Normals stay normalized signed integers, even with the extension.
    std::string json = Replace(kQuantized, "EXTENSIONS", kUsed);
    json =
        Replace(json, R"("componentType": 5120, "normalized": true)", R"("componentType": 5120)");
    json = Replace(json, "BUFFER",
                   "data:application/octet-stream;base64," + Base64(QuantizedBuffer()));
    const std::string n = ErrorOf(WriteScratchFile("gltfa_badnormal.gltf", json));
    EXPECT_NE(n.find("NORMAL accessor must have float components"), std::string::npos) << n;
}

// A quad whose POSITION accessor is sparse: over its buffer view (vertex 2 moved) or over
// zeros (no buffer view; vertices 1 to 3 given).
std::string SparseBuffer() {
    std::string b;
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});  // 48 B: the quad
    PutBytes<uint16_t>(b, {0, 1, 2, 0, 2, 3});                 // 12 B: indices (at 48)
    PutBytes<uint8_t>(b, {2, 0, 0, 0});                        // 4 B: sparse index 2 (at 60)
    PutBytes<float>(b, {2, 2, 0});                             // 12 B: its value (at 64)
    PutBytes<uint32_t>(b, {1, 2, 3});                          // 12 B: sparse indices (at 76)
    PutBytes<float>(b, {1, 0, 0, 1, 1, 0, 0, 1, 0});           // 36 B: their values (at 88)
    return b;                                                  // 124 B
}

const char *kSparse = R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"mesh": 1}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]},
             {"primitives": [{"attributes": {"POSITION": 2}, "indices": 1}]}],
  "buffers": [{"uri": "BUFFER", "byteLength": 124}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 12},
    {"buffer": 0, "byteOffset": 60, "byteLength": 4},
    {"buffer": 0, "byteOffset": 64, "byteLength": 12},
    {"buffer": 0, "byteOffset": 76, "byteLength": 12},
    {"buffer": 0, "byteOffset": 88, "byteLength": 36}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5121},
                "values": {"bufferView": 3}}},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"componentType": 5126, "count": 4, "type": "VEC3",
     "sparse": {"count": 3, "indices": {"bufferView": 4, "componentType": 5125},
                "values": {"bufferView": 5}}}
  ]
})";

std::string WriteSparse(const std::string &name,
                        const std::vector<std::pair<std::string, std::string>> &edits = {}) {
    std::string json = kSparse;
    for (const auto &[from, to] : edits) json = Replace(json, from, to);
    json =
        Replace(json, "BUFFER", "data:application/octet-stream;base64," + Base64(SparseBuffer()));
    return WriteScratchFile(name + ".gltf", json);
}

TEST(GltfAccessors, SparseAccessorsAreMadeWhole) {
    Diagnostics diag;
    const SceneDescription d = ReadGltfFile(WriteSparse("gltfa_sparse"), diag);
    ASSERT_EQ(d.shapes.size(), 2u);
    EXPECT_EQ(d.shapes[0].params.GetPoint3s("P"),
              (std::vector<Vec3f>{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(2, 2, 0), Vec3f(0, 1, 0)}));
    EXPECT_EQ(d.shapes[1].params.GetPoint3s("P"),
              (std::vector<Vec3f>{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)}));
}

// The sparse buffer with sparse indices `indices` for the zero-based accessor.
std::string WriteSparseIndices(const std::string &name, const uint32_t (&indices)[3]) {
    std::string buf = SparseBuffer();
    std::memcpy(buf.data() + 76, indices, sizeof indices);
    return WriteScratchFile(
        name + ".gltf",
        Replace(kSparse, "BUFFER", "data:application/octet-stream;base64," + Base64(buf)));
}

TEST(GltfAccessors, MalformedSparseAccessorsAreSceneErrors) {
    struct Case {
        std::string from, to, error;
    };
    const Case cases[] = {
        {"\"count\": 1, \"indices\": {\"bufferView\": 2",
         "\"count\": 5, \"indices\": {\"bufferView\": 2", "sparse count 5 is not 1 to"},
        {"\"componentType\": 5121}", "\"componentType\": 5126}", "sparse indices must be unsigned"},
        {"\"values\": {\"bufferView\": 3}", "\"values\": {\"bufferView\": 3, \"byteOffset\": 4}",
         "its sparse values reaches past the end of its buffer view"},
        {"\"indices\": {\"bufferView\": 4", "\"indices\": {\"bufferView\": 40",
         "its sparse indices has no valid buffer view"},
    };
    int n = 0;
    for (const Case &c : cases) {
        const std::string e =
            ErrorOf(WriteSparse("gltfa_bad" + std::to_string(n++), {{c.from, c.to}}));
        EXPECT_NE(e.find(c.error), std::string::npos) << c.error << ": " << e;
        EXPECT_NE(e.find("accessor"), std::string::npos) << e;
    }
    std::string e = ErrorOf(WriteSparseIndices("gltfa_range", {1, 2, 9}));
    EXPECT_NE(e.find("sparse index 9 is out of range (4 elements)"), std::string::npos) << e;
    e = ErrorOf(WriteSparseIndices("gltfa_order", {2, 1, 3}));
    EXPECT_NE(e.find("sparse indices must increase strictly (1 follows 2)"), std::string::npos)
        << e;
}

// A triangle with two morph targets: target 0 moves vertex 2 by (0, 0, 2) (dense), target 1
// moves vertex 0 by (1, 0, 0) (sparse over zeros); normals point up and target 0 tilts
// vertex 2's.
std::string MorphBuffer() {
    std::string b;
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0});   // 36 B: POSITION
    PutBytes<float>(b, {0, 0, 2, 0, 0, 2, 0, 0, 2});   // 36 B: target 0 POSITION (at 36)
    PutBytes<uint8_t>(b, {0, 0, 0, 0});                // 4 B: target 1 sparse index (at 72)
    PutBytes<float>(b, {1, 0, 0});                     // 12 B: its value (at 76)
    PutBytes<float>(b, {0, 0, 1, 0, 0, 1, 0, 0, 1});   // 36 B: NORMAL (at 88)
    PutBytes<float>(b, {0, 0, 0, 0, 0, 0, 1, 0, -1});  // 36 B: target 0 NORMAL (at 124)
    return b;                                          // 160 B
}

const char *kMorph = R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0 NODEWEIGHTS}],
  "meshes": [{"weights": [0.5, 1],
              "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 3},
                              "targets": [{"POSITION": 1, "NORMAL": 4}, {"POSITION": 2}]}]}],
  "buffers": [{"uri": "BUFFER", "byteLength": 160}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 4},
    {"buffer": 0, "byteOffset": 76, "byteLength": 12},
    {"buffer": 0, "byteOffset": 88, "byteLength": 36},
    {"buffer": 0, "byteOffset": 124, "byteLength": 36}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"componentType": 5126, "count": 3, "type": "VEC3",
     "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5121},
                "values": {"bufferView": 3}}},
    {"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 5, "componentType": 5126, "count": 3, "type": "VEC3"}
  ]
})";

SceneDescription ReadMorph(const std::string &name, const std::string &nodeWeights) {
    std::string json = Replace(kMorph, "NODEWEIGHTS", nodeWeights);
    json = Replace(json, "BUFFER", "data:application/octet-stream;base64," + Base64(MorphBuffer()));
    Diagnostics diag;
    return ReadGltfFile(WriteScratchFile(name + ".gltf", json), diag);
}

TEST(GltfAccessors, MorphTargetsDisplaceByTheirWeights) {
    // The mesh's weights 0.5 and 1.
    SceneDescription d = ReadMorph("gltfa_morph", "");
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].params.GetPoint3s("P"),
              (std::vector<Vec3f>{Vec3f(1, 0, 1), Vec3f(1, 0, 1), Vec3f(0, 1, 1)}));
    const std::vector<Vec3f> N = d.shapes[0].params.GetNormals("N");
    ASSERT_EQ(N.size(), 3u);
    EXPECT_EQ(N[0], Vec3f(0, 0, 1));
    // (0, 0, 1) + 0.5 (1, 0, -1), normalized.
    EXPECT_NEAR(N[2].x, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(N[2].z, std::sqrt(0.5f), 1e-6f);
    // The node's weights win: target 0 in full, target 1 not at all.
    d = ReadMorph("gltfa_morph_node", ", \"weights\": [1, 0]");
    EXPECT_EQ(d.shapes[0].params.GetPoint3s("P"),
              (std::vector<Vec3f>{Vec3f(0, 0, 2), Vec3f(1, 0, 2), Vec3f(0, 1, 2)}));
}

// A skinned triangle: vertex 0 on joint 0, vertex 1 on joint 1, vertex 2 half on each. Joint
// 1's node rests 2 above joint 0's; the mesh's own node is moved, which a skinned mesh
// ignores. The inverse bind matrices (identity, then 2 down) put the bind pose at the rest
// pose, when given.
std::string SkinBuffer() {
    std::string b;
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0});               // 36 B: POSITION
    PutBytes<uint8_t>(b, {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0});    // 12 B: JOINTS_0 (at 36)
    PutBytes<float>(b, {1, 0, 0, 0, 1, 0, 0, 0, 0.5, 0.5, 0, 0});  // 48 B: WEIGHTS_0 (at 48)
    PutBytes<float>(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});   // (at 96)
    PutBytes<float>(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -2, 0, 1});  // (at 160)
    return b;                                                               // 224 B
}

const char *kSkin = R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0, "skin": 0, "translation": [5, 0, 0]},
            {"children": [2]}, {"translation": [0, 2, 0]}],
  "skins": [{"joints": [1, 2] IBM}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}}]}],
  "buffers": [{"uri": "BUFFER", "byteLength": 224}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 12},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 128}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5121, "count": 3, "type": "VEC4"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"},
    {"bufferView": 3, "componentType": 5126, "count": 2, "type": "MAT4"}
  ]
})";

std::vector<Vec3f> SkinnedPositions(const std::string &name, const std::string &ibm) {
    std::string json = Replace(kSkin, "IBM", ibm);
    json = Replace(json, "BUFFER", "data:application/octet-stream;base64," + Base64(SkinBuffer()));
    Diagnostics diag;
    const SceneDescription d = ReadGltfFile(WriteScratchFile(name + ".gltf", json), diag);
    EXPECT_EQ(d.shapes.size(), 1u);
    if (d.shapes.empty()) return {};
    const Transform &t = d.shapes[0].worldFromObject;
    std::vector<Vec3f> P;
    for (Vec3f p : d.shapes[0].params.GetPoint3s("P")) P.push_back(Vec3f(t.Point(Vec3d(p))));
    return P;
}

TEST(GltfAccessors, SkinsPoseTheirMeshesAtTheJointsRestTransforms) {
    // No inverse bind matrices: joint 1's rest lifts its vertices by 2, half of it vertex 2's;
    // the mesh node's own translation is not applied.
    EXPECT_EQ(SkinnedPositions("gltfa_skin", ""),
              (std::vector<Vec3f>{Vec3f(0, 0, 0), Vec3f(1, 2, 0), Vec3f(0, 2, 0)}));
    // Inverse bind matrices that undo the rest transforms: the mesh as written.
    EXPECT_EQ(SkinnedPositions("gltfa_skin_ibm", ", \"inverseBindMatrices\": 3"),
              (std::vector<Vec3f>{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)}));
}

TEST(GltfAccessors, SkinsTurnTheirTangents) {
    // Joint 1 also turned 90 degrees about z: vertex 1's tangent (1, 0, 0) follows it to
    // (0, 1, 0); vertex 0's stays. The bitangent sign (w) is kept (no mirroring).
    std::string buffer = SkinBuffer();
    PutBytes<float>(buffer, {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1});  // 48 B: TANGENT (at 224)
    const float h = float(std::sqrt(0.5));
    std::string json = Replace(kSkin, "IBM", "");
    json = Replace(json, "{\"translation\": [0, 2, 0]}",
                   "{\"translation\": [0, 2, 0], \"rotation\": [0, 0, " + std::to_string(h) + ", " +
                       std::to_string(h) + "]}");
    json = Replace(json, "\"WEIGHTS_0\": 2}", "\"WEIGHTS_0\": 2, \"TANGENT\": 4}, \"material\": 0");
    json = Replace(json, "\"byteLength\": 224", "\"byteLength\": 272");
    json = Replace(json, "{\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 128}",
                   "{\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 128},\n"
                   "    {\"buffer\": 0, \"byteOffset\": 224, \"byteLength\": 48}");
    json = Replace(
        json, "\"count\": 2, \"type\": \"MAT4\"}",
        "\"count\": 2, \"type\": \"MAT4\"},\n"
        "    {\"bufferView\": 4, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC4\"}");
    json = Replace(json, "\"meshes\":",
                   "\"materials\": [{\"normalTexture\": {\"index\": 0}}],\n"
                   "  \"textures\": [{\"source\": 0}],\n"
                   "  \"images\": [{\"uri\": \"data:image/png;base64," +
                       Base64("PNGDATA") + "\"}],\n  \"meshes\":");
    json = Replace(json, "BUFFER", "data:application/octet-stream;base64," + Base64(buffer));
    Diagnostics diag;
    const SceneDescription d =
        ReadGltfFile(WriteScratchFile("gltfa_skin_tangent.gltf", json), diag);
    ASSERT_EQ(d.shapes.size(), 1u);
    const std::vector<float> t = d.shapes[0].params.GetFloats("tangent");
    ASSERT_EQ(t.size(), 12u);
    EXPECT_NEAR(t[0], 1, 1e-6);
    EXPECT_NEAR(t[4], 0, 1e-6);
    EXPECT_NEAR(t[5], 1, 1e-6);
    EXPECT_EQ(t[7], 1);
}

TEST(GltfAccessors, MalformedSkinsAreSceneErrors) {
    auto error = [](const std::string &name, const std::string &from, const std::string &to) {
        std::string json = Replace(Replace(kSkin, "IBM", ""), from, to);
        json =
            Replace(json, "BUFFER", "data:application/octet-stream;base64," + Base64(SkinBuffer()));
        return ErrorOf(WriteScratchFile(name + ".gltf", json));
    };
    std::string e = error("gltfa_skin_joint", "\"joints\": [1, 2]", "\"joints\": [1]");
    EXPECT_NE(e.find("JOINTS_0 names joint 1 of a skin of 1"), std::string::npos) << e;
    e = error("gltfa_skin_noweights", ", \"WEIGHTS_0\": 2", "");
    EXPECT_NE(e.find("needs JOINTS_0 and WEIGHTS_0"), std::string::npos) << e;
    e = error("gltfa_skin_ibmtype", "\"joints\": [1, 2]",
              "\"joints\": [1, 2], \"inverseBindMatrices\": 2");
    EXPECT_NE(e.find("inverseBindMatrices accessor must be MAT4"), std::string::npos) << e;
}

}  // namespace
}  // namespace prism
