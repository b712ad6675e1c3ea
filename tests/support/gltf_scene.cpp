#include "support/gltf_scene.h"

#include <cstdint>

#include "image/image.h"
#include "image/image_io.h"
#include "support/text.h"

namespace prism::test {

std::string GltfTwoUvQuad(const std::string &material) {
    std::string bin;
    auto put = [&](const void *p, size_t n) { bin.append(static_cast<const char *>(p), n); };
    float P[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    float uv0[8] = {0, 1, 1, 1, 1, 0, 0, 0};  // glTF's v runs down
    float uv1[8] = {1, 1, 0, 1, 0, 0, 1, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    put(P, sizeof P);
    put(uv0, sizeof uv0);
    put(uv1, sizeof uv1);
    put(idx, sizeof idx);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
"nodes": [{"mesh": 0}],
"meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2},
  "indices": 3, "material": 0}]}],
"materials": [)" +
           material + R"(],
"textures": [{"source": 0}], "images": [{"uri": "tex.png"}],
"buffers": [{"byteLength": 124, "uri": "data:application/octet-stream;base64,)" +
           Base64(bin) + R"("}],
"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
  {"buffer": 0, "byteOffset": 48, "byteLength": 32},
  {"buffer": 0, "byteOffset": 80, "byteLength": 32},
  {"buffer": 0, "byteOffset": 112, "byteLength": 12}],
"accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
    "min": [0, 0, 0], "max": [1, 1, 0]},
  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
  {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
  {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

void WriteHalfImage(const std::string &path, bool leftWhite) {
    Image img(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) img.SetRGB(x, y, RGB((x < 4) == leftWhite ? 1.f : 0.f));
    WriteImage(path, img);
}

}  // namespace prism::test
