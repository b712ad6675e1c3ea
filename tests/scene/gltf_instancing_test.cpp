// EXT_mesh_gpu_instancing (scene/gltf_instancing.cpp): a node's mesh drawn once per instance at
// the node's transform times the instance's T · R · S, as one object the renderer instances;
// an emissive mesh copied instead; malformed instance attributes refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/gltf_reader.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

// A unit triangle (36 B), three instance translations (36 B), rotations (48 B: identity,
// identity, 90 degrees about z) and scales (36 B).
std::string InstanceBuffer() {
    std::string b;
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0});
    PutBytes<float>(b, {0, 0, 0, 3, 0, 0, -3, 0, 0});
    const float h = float(std::sqrt(0.5));
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, h, h});
    PutBytes<float>(b, {1, 1, 1, 1, 1, 1, 2, 2, 2});
    return b;  // 156 B
}

const char *kInstanced = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["EXT_mesh_gpu_instancing"],
  "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
  "nodes": [{"camera": 0, "translation": [0, 0, 10]},
            {"mesh": 0, "translation": [0, 0, -5],
             "extensions": {"EXT_mesh_gpu_instancing": {"attributes":
               {"TRANSLATION": 1, "ROTATION": 2, "SCALE": 3}}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                 "metallicFactor": 0}}],
  "buffers": [{"uri": "BUFFER", "byteLength": 156}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 48},
    {"buffer": 0, "byteOffset": 120, "byteLength": 36}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"},
    {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"}
  ]
})";

std::string WriteInstanced(const std::string &name,
                           const std::vector<std::pair<std::string, std::string>> &edits = {}) {
    std::string json = kInstanced;
    for (const auto &[from, to] : edits) {
        EXPECT_NE(json.find(from), std::string::npos) << from;
        json = ReplaceFirst(json, from, to);
    }
    json = ReplaceFirst(json, "BUFFER",
                        "data:application/octet-stream;base64," + Base64(InstanceBuffer()));
    return WriteScratchFile(name + ".gltf", json);
}

TEST(GltfInstancing, EachInstanceIsTheNodeTimesItsTrs) {
    Diagnostics diag;
    const SceneDescription d = ReadGltfFile(WriteInstanced("gltfi_grid"), diag);
    EXPECT_TRUE(d.shapes.empty());
    ASSERT_EQ(d.objects.size(), 1u);
    ASSERT_EQ(d.objects[0].shapes.size(), 1u);
    ASSERT_EQ(d.instances.size(), 3u);
    for (const InstanceDesc &i : d.instances) EXPECT_EQ(i.object, d.objects[0].name);
    // Instance 1: translated by (3, 0, 0), then the node's (0, 0, -5).
    const Vec3d p1 = d.instances[1].worldFromInstance.Point(Vec3d(1, 0, 0));
    EXPECT_NEAR(p1.x, 4, 1e-6);
    EXPECT_NEAR(p1.z, -5, 1e-6);
    // Instance 2: scaled 2, turned 90 degrees about z, at (-3, 0, -5): (1, 0, 0) -> (-3, 2, -5).
    const Vec3d p2 = d.instances[2].worldFromInstance.Point(Vec3d(1, 0, 0));
    EXPECT_NEAR(p2.x, -3, 1e-6);
    EXPECT_NEAR(p2.y, 2, 1e-6);
    EXPECT_NEAR(p2.z, -5, 1e-6);
    for (const Warning &w : diag.Warnings())
        EXPECT_EQ(w.message.find("EXT_mesh_gpu_instancing"), std::string::npos) << w.message;
}

TEST(GltfInstancing, EveryInstanceRenders) {
    // Seen by the file's camera: three instances cover more pixels than the first alone (a
    // pixel covered: apart from the background, the corner's, by more than 5%).
    BuildSettings opts = SizedSettings(64, 48, 4);
    const Rendered three = RenderSceneFile(WriteInstanced("gltfi_three"), opts);
    const Rendered one =
        RenderSceneFile(WriteInstanced("gltfi_one", {{"\"count\": 3, \"type\": \"VEC3\"}",
                                                      "\"count\": 1, "
                                                      "\"type\": \"VEC3\"}"},
                                                     {"\"count\": 3, \"type\": \"VEC4\"}",
                                                      "\"count\": 1, "
                                                      "\"type\": \"VEC4\"}"},
                                                     {"\"count\": 3, \"type\": \"VEC3\"}\n  ]",
                                                      "\"count\": 1, \"type\": \"VEC3\"}\n  ]"}}),
                        opts);
    auto covered = [](const Image &img) {
        const float background = img.GetRGB(0, 0).Luminance();
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                n += std::abs(img.GetRGB(x, y).Luminance() - background) > 0.05f * background;
        return n;
    };
    EXPECT_GT(covered(one.image), 0);
    EXPECT_GT(covered(three.image), covered(one.image));
}

TEST(GltfInstancing, MalformedInstanceAttributesAreSceneErrors) {
    auto error = [](const std::string &path) {
        return ErrorOf<SceneError>([&] {
            Diagnostics diag;
            ReadGltfFile(path, diag);
        });
    };
    std::string e = error(WriteInstanced(
        "gltfi_count", {{"{\"bufferView\": 3, \"componentType\": 5126, \"count\": 3",
                         "{\"bufferView\": 3, \"componentType\": 5126, \"count\": 2"}}));
    EXPECT_NE(e.find("attributes differ in count"), std::string::npos) << e;
    e = error(WriteInstanced("gltfi_type", {{"\"bufferView\": 2, \"componentType\": 5126",
                                             "\"bufferView\": 2, \"componentType\": 5125"}}));
    EXPECT_NE(e.find("instance ROTATION accessor must be VEC4"), std::string::npos) << e;
    e = error(WriteInstanced("gltfi_none",
                             {{"{\"TRANSLATION\": 1, \"ROTATION\": 2, \"SCALE\": 3}", "{}"}}));
    EXPECT_NE(e.find("has no TRANSLATION, ROTATION or SCALE"), std::string::npos) << e;
    EXPECT_NE(e.find("/nodes/1/extensions/EXT_mesh_gpu_instancing"), std::string::npos) << e;
}

}  // namespace
}  // namespace prism
