// glTF reader: node transforms, primitives, camera conventions, KHR lights, materials,
// embedded images, and clean errors for malformed accessors.
#include "scene/gltf_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include "core/memory.h"
#include "support/errors.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace prism {
namespace {

using namespace test;

// 140 bytes: 4 positions (0), 6 ushort indices (48), 4 normals (60), 4 texcoords (108).
std::string QuadBuffer() {
    std::string b;
    PutBytes<float>(b, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    PutBytes<uint16_t>(b, {0, 1, 2, 0, 2, 3});
    for (int i = 0; i < 4; ++i) PutBytes<float>(b, {0, 0, 1});
    PutBytes<float>(b, {0, 0, 1, 0, 1, 1, 0, 1});
    return b;
}

std::string Replace(const std::string &s, const std::string &from, const std::string &to) {
    return ReplaceFirst(s, from, to);
}

const char *kGltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                     "KHR_materials_emissive_strength", "EXT_made_up"],
  "extensionsRequired": ["KHR_lights_punctual"],
  "scene": SCENE,
  "scenes": [{"nodes": [0]}, {"nodes": [5]}, {"nodes": [6]}],
  "nodes": [
    {"name": "root", "translation": [1, 2, 3], "children": [1, 2, 3, 4]},
    {"mesh": 0, "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "scale": [2, 2, 2]},
    {"mesh": 1, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,-5,1]},
    {"camera": 0, "translation": [0, 0, 10]},
    {"rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"camera": 1},
    {"camera": 2}
  ],
  "cameras": [
    {"type": "perspective", "perspective": {"aspectRatio": 1.5, "yfov": 0.5, "znear": 0.1}},
    {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1.5, "znear": 0.1, "zfar": 10}},
    {"type": "perspective", "perspective": {"aspectRatio": 0.5, "yfov": 0.8, "znear": 0.1}}
  ],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 100,
     "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}},
  "meshes": [
    {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2, "TEXCOORD_0": 3},
                     "indices": 1, "material": 0}]},
    {"primitives": [{"attributes": {"POSITION": 4}, "material": 1},
                    {"attributes": {"POSITION": 0}, "mode": 1},
                    {"attributes": {"POSITION": 0}, "mode": 0},
                    {"attributes": {"POSITION": 0}, "mode": 1},
                    {"attributes": {"POSITION": 4}, "material": 2, "mode": 4},
                    {"attributes": {"POSITION": 4}, "material": 3},
                    {"attributes": {"POSITION": 4}, "material": 4}]}
  ],
  "materials": [
    {"name": "textured", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
      "baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.5}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1],
      "metallicFactor": 1, "roughnessFactor": 0.2}},
    {"name": "water", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                     "KHR_materials_ior": {"ior": 1.33}}},
    {"name": "lamp", "emissiveFactor": [1, 0.5, 0.25],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
    {"name": "embedded", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1},
      "metallicFactor": 0}}
  ],
  "textures": [{"source": 0}, {"source": 1, "sampler": 0}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "images": [{"uri": "gltft%20tex.png"}, {"uri": "data:image/png;base64,IMAGE64"}],
  "buffers": [{"uri": "BUFFERURI", "byteLength": 140}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 12},
    {"buffer": 0, "byteOffset": 60, "byteLength": 48},
    {"buffer": 0, "byteOffset": 108, "byteLength": 32}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 3, "componentType": 5126, "count": POSCOUNT, "type": "VEC2"},
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]}
  ]
})";

// kGltf with its placeholders filled, after the edits `from` -> `to` of `edits`.
std::string WriteGltf(const std::string &name, int scene, bool dataUriBuffer = false,
                      const std::string &texcoordCount = "4",
                      const std::vector<std::pair<std::string, std::string>> &edits = {}) {
    std::string json = kGltf;
    for (const auto &[from, to] : edits) {
        EXPECT_NE(json.find(from), std::string::npos) << from;
        json = Replace(json, from, to);
    }
    json = Replace(json, "SCENE", std::to_string(scene));
    json = Replace(json, "POSCOUNT", texcoordCount);
    json = Replace(json, "IMAGE64", Base64("PNGDATA"));
    if (dataUriBuffer) {
        json = Replace(json, "BUFFERURI",
                       "data:application/octet-stream;base64," + Base64(QuadBuffer()));
    } else {
        WriteScratchFile(name + ".bin", QuadBuffer());
        json = Replace(json, "BUFFERURI", name + ".bin");
    }
    WriteScratchFile("gltft tex.png", "not really a png");
    return WriteScratchFile(name + ".gltf", json);
}

Vec3d Apply(const Transform &t, Vec3d p) { return t.Point(p); }

void ExpectNear(Vec3d a, Vec3d b, double eps = 1e-9) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

const TextureDesc *FindTexture(const SceneDescription &d, const std::string &name) {
    for (const TextureDesc &t : d.textures)
        if (t.name == name) return &t;
    return nullptr;
}

TEST(GltfReader, NodesPrimitivesAndWarnings) {
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteGltf("gltft_main", 0), diag);
    EXPECT_EQ(d.format, "gltf");
    ASSERT_EQ(d.shapes.size(), 5u);  // 1 indexed quad + 4 non-indexed triangles

    const ShapeDesc &quad = d.shapes[0];
    EXPECT_EQ(quad.type, "trianglemesh");
    EXPECT_EQ(quad.params.GetInts("indices"), (std::vector<int>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(quad.params.GetNormals("N").size(), 4u);
    std::vector<Vec2f> uv = quad.params.GetPoint2s("uv");
    ASSERT_EQ(uv.size(), 4u);
    EXPECT_EQ(uv[0], Vec2f(0, 1));  // glTF's v runs downwards; flipped to pbrt's convention
    EXPECT_EQ(uv[2], Vec2f(1, 0));
    // root T(1,2,3) * R_y(90°) * S(2): object (1,0,0) → (0,0,-2) → (1,2,1).
    ExpectNear(Apply(quad.worldFromObject, Vec3d(1, 0, 0)), Vec3d(1, 2, 1), 1e-6);
    ExpectNear(Apply(quad.worldFromObject, Vec3d(0, 1, 0)), Vec3d(1, 4, 3), 1e-6);

    const ShapeDesc &tri = d.shapes[1];
    EXPECT_EQ(tri.params.GetInts("indices"), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(tri.params.GetPoint3s("P").size(), 3u);
    ExpectNear(Apply(tri.worldFromObject, Vec3d(0, 0, 0)), Vec3d(1, 2, -2));

    int modeWarnings = 0, extWarnings = 0;
    for (const Warning &w : diag.Warnings()) {
        modeWarnings += w.message.find("primitive mode") != std::string::npos;
        if (w.message.find("EXT_made_up") != std::string::npos) {
            ++extWarnings;
            EXPECT_EQ(w.message.find("KHR_lights_punctual"), std::string::npos) << w.message;
        }
    }
    EXPECT_EQ(modeWarnings, 2);  // modes 0 and 1, once each
    EXPECT_EQ(extWarnings, 1);
}

TEST(GltfReader, PerspectiveCameraConvention) {
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteGltf("gltft_cam", 0), diag);
    const CameraDesc &c = d.camera;
    ASSERT_TRUE(c.specified);
    EXPECT_EQ(c.type, "perspective");
    // aspect 1.5 > 1: the vertical axis is the shorter one, so pbrt's fov is yfov.
    EXPECT_NEAR(c.params.GetFloat("fov", 0), 0.5 * 180 / Pi, 1e-4);
    EXPECT_EQ(d.film.params.GetInt("xresolution", 0), 1280);
    EXPECT_EQ(d.film.params.GetInt("yresolution", 0), 853);
    // The camera sits at (1, 2, 13) looking down world -z.
    const Transform &cw = c.cameraFromWorld;
    ExpectNear(Apply(cw, Vec3d(1, 2, 13)), Vec3d(0, 0, 0), 1e-9);
    Vec3d ahead = Apply(cw, Vec3d(1, 2, 3));
    EXPECT_NEAR(ahead.z, 10, 1e-9);             // in front → z > 0
    EXPECT_GT(Apply(cw, Vec3d(2, 2, 8)).x, 0);  // camera's right (+x) → x > 0
    EXPECT_GT(Apply(cw, Vec3d(1, 3, 8)).y, 0);  // up stays up
}

TEST(GltfReader, OrthographicAndPortraitCameras) {
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteGltf("gltft_ortho", 1), diag);
    ASSERT_TRUE(d.camera.specified);
    EXPECT_EQ(d.camera.type, "orthographic");
    EXPECT_EQ(d.camera.params.GetFloats("screenwindow"), (std::vector<float>{-2, 2, -1.5, 1.5}));
    EXPECT_TRUE(d.shapes.empty());

    SceneDescription p = ReadGltfFile(WriteGltf("gltft_portrait", 2), diag);
    // aspect 0.5: the horizontal axis is shorter; its fov is 2 atan(tan(yfov/2) * aspect).
    double expect = 2 * std::atan(std::tan(0.4) * 0.5) * 180 / Pi;
    EXPECT_NEAR(p.camera.params.GetFloat("fov", 0), expect, 1e-4);
    EXPECT_EQ(p.film.params.GetInt("xresolution", 0), 640);
    EXPECT_EQ(p.film.params.GetInt("yresolution", 0), 1280);
}

// --camera: a camera by name or index among those the scene's nodes use; the default is the
// first one the traversal reaches; anything else is an error that lists the cameras.
TEST(GltfReader, CameraChosenByNameOrIndex) {
    const std::vector<std::pair<std::string, std::string>> edits = {
        {R"("scenes": [{"nodes": [0]})", R"("scenes": [{"nodes": [0, 5]})"},
        {R"({"type": "orthographic")", R"({"name": "top", "type": "orthographic")"}};
    auto read = [&](const std::string &camera) {
        Diagnostics diag;
        MemoryBudget budget(0);
        return ReadGltfFile(WriteGltf("gltft_cameras", 0, true, "4", edits), diag, budget, camera);
    };
    EXPECT_EQ(read("").camera.type, "perspective");
    EXPECT_EQ(read("top").camera.type, "orthographic");
    EXPECT_EQ(read("1").camera.type, "orthographic");
    EXPECT_EQ(read("0").camera.type, "perspective");
    auto error = [&](const std::string &camera) {
        return ErrorOf<SceneError>([&] { read(camera); });
    };
    std::string e = error("side");
    EXPECT_NE(
        e.find("--camera \"side\": the file has no such camera (its cameras: 0, 1 \"top\", 2)"),
        std::string::npos)
        << e;
    e = error("2");  // in the file, but no node of scene 0 uses it
    EXPECT_NE(e.find("no node of the scene uses camera 2"), std::string::npos) << e;
}

TEST(GltfReader, SpotLight) {
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteGltf("gltft_light", 0), diag);
    ASSERT_EQ(d.lights.size(), 1u);
    const LightDesc &l = d.lights[0];
    EXPECT_EQ(l.type, "spot");
    RGB I = l.params.GetRGB("I", RGB(0));
    EXPECT_FLOAT_EQ(I.r, 100);
    EXPECT_FLOAT_EQ(I.g, 50);
    EXPECT_FLOAT_EQ(I.b, 25);
    EXPECT_NEAR(l.params.GetFloat("coneangle", 0), 0.5 * 180 / Pi, 1e-4);
    EXPECT_NEAR(l.params.GetFloat("conedeltaangle", 0), 0.3 * 180 / Pi, 1e-4);
    Vec3d from = l.worldFromLight.Point(Vec3d(l.params.GetPoint3("from", Vec3f(9, 9, 9))));
    Vec3d to = l.worldFromLight.Point(Vec3d(l.params.GetPoint3("to", Vec3f(9, 9, 9))));
    ExpectNear(from, Vec3d(1, 2, 3), 1e-6);
    ExpectNear(Normalize(to - from), Vec3d(0, -1, 0), 1e-6);  // rotated to point down
}

TEST(GltfReader, Materials) {
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteGltf("gltft_mat", 0, /*dataUriBuffer=*/true), diag);
    ASSERT_EQ(d.materials.size(), 5u);
    // glTF names no integrator: rough metals reflect through Prism's distribution integrator.
    EXPECT_EQ(d.integrator.type, "distribution");

    // Every material is Prism's "gltf" metallic-roughness material with the glTF factors.
    for (const MaterialDesc &m : d.materials) EXPECT_EQ(m.type, "gltf");
    const MaterialDesc &tex = d.materials[0];
    EXPECT_NEAR(tex.params.GetFloat("roughness", 0), 0.5, 1e-6);
    EXPECT_NEAR(tex.params.GetFloat("metallic", 1), 0, 1e-6);
    EXPECT_FLOAT_EQ(tex.params.GetRGB("basecolor", RGB(0)).g, 0.5f);  // factor 0.5 × texture
    const TextureDesc *image = FindTexture(d, tex.params.GetTexture("basecolormap"));
    ASSERT_TRUE(image);
    EXPECT_EQ(image->type, "imagemap");
    EXPECT_EQ(image->params.GetString("filename", ""), "gltft tex.png");  // %20 decoded

    const MaterialDesc &gold = d.materials[1];
    RGB base = gold.params.GetRGB("basecolor", RGB(0));
    EXPECT_FLOAT_EQ(base.r, 0.9f);
    EXPECT_FLOAT_EQ(base.g, 0.6f);
    EXPECT_FLOAT_EQ(base.b, 0.3f);
    EXPECT_NEAR(gold.params.GetFloat("metallic", 0), 1, 1e-6);
    EXPECT_NEAR(gold.params.GetFloat("roughness", 0), 0.2, 1e-6);

    EXPECT_NEAR(d.materials[2].params.GetFloat("transmission", 0), 1, 1e-6);
    EXPECT_NEAR(d.materials[2].params.GetFloat("ior", 0), 1.33, 1e-6);

    ASSERT_EQ(d.areaLights.size(), 1u);
    RGB L = d.areaLights[0].params.GetRGB("L", RGB(0));
    EXPECT_FLOAT_EQ(L.r, 4);
    EXPECT_FLOAT_EQ(L.g, 2);
    EXPECT_FLOAT_EQ(L.b, 1);
    int emissive = 0;
    for (const ShapeDesc &s : d.shapes)
        if (s.areaLight >= 0) {
            ++emissive;
            EXPECT_EQ(s.material, 3);
        }
    EXPECT_EQ(emissive, 1);

    // An embedded (data URI) image is kept in memory and referenced as "embedded:<i>".
    const TextureDesc *emb = FindTexture(d, d.materials[4].params.GetTexture("basecolormap"));
    ASSERT_TRUE(emb);
    EXPECT_EQ(emb->type, "imagemap");
    EXPECT_EQ(emb->params.GetString("filename", ""), "embedded:0");
    // Its sampler is NEAREST for both filters: point lookups; the other texture keeps the
    // default (EWA).
    EXPECT_EQ(emb->params.GetString("filter", ""), "point");
    EXPECT_EQ(image->params.GetString("filter", "default"), "default");
    // Its sampler's wrap modes: none given, repeat (the default).
    EXPECT_FALSE(emb->params.Has("wraps") || emb->params.Has("wrapt"));
    EXPECT_EQ(EmbeddedImageIndex("embedded:0"), 0);
    EXPECT_EQ(EmbeddedImageIndex("embedded:12"), 12);
    EXPECT_EQ(EmbeddedImageIndex("textures/a.png"), -1);
    EXPECT_EQ(EmbeddedImageIndex("embedded:"), -1);
    EXPECT_EQ(EmbeddedImageIndex("embedded:1x"), -1);
    ASSERT_EQ(d.embeddedImages.size(), 1u);
    EXPECT_EQ(d.embeddedImages[0].mimeType, "image/png");
    EXPECT_EQ(std::string(d.embeddedImages[0].bytes.begin(), d.embeddedImages[0].bytes.end()),
              "PNGDATA");
}

// KHR_texture_transform, _specular, _clearcoat and textured emission reach the material.
// wrapS and wrapT per axis: MIRRORED_REPEAT is "mirror", CLAMP_TO_EDGE "clamp".
TEST(GltfReader, SamplerWrapModesPerAxis) {
    Diagnostics diag;
    const SceneDescription d =
        ReadGltfFile(WriteGltf("gltft_wrap", 0, true, "4",
                               {{R"("samplers": [{"magFilter": 9728, "minFilter": 9728}])",
                                 R"("samplers": [{"wrapS": 33648, "wrapT": 33071}])"}}),
                     diag);
    const TextureDesc *emb = FindTexture(d, d.materials[4].params.GetTexture("basecolormap"));
    ASSERT_TRUE(emb);
    EXPECT_EQ(emb->params.GetString("wraps", ""), "mirror");
    EXPECT_EQ(emb->params.GetString("wrapt", ""), "clamp");
}

TEST(GltfReader, MaterialExtensionsAndTextureTransform) {
    std::string json = Replace(
        kGltf, R"({"name": "embedded", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1},
      "metallicFactor": 0}})",
        R"({"name": "embedded", "pbrMetallicRoughness": {
      "baseColorTexture": {"index": 1, "extensions": {"KHR_texture_transform":
        {"offset": [0.5, 0.25], "rotation": 0.3, "scale": [2, 4]}}},
      "metallicRoughnessTexture": {"index": 0}, "metallicFactor": 0.5},
      "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 1, 0.5],
      "occlusionTexture": {"index": 0, "strength": 0.7},
      "extensions": {"KHR_materials_specular": {"specularFactor": 0.5,
                                                "specularColorFactor": [1, 0.5, 0.25]},
                     "KHR_materials_clearcoat": {"clearcoatFactor": 0.8,
                                                 "clearcoatRoughnessFactor": 0.1},
                     "KHR_materials_emissive_strength": {"emissiveStrength": 2}}})");
    json = Replace(json, "SCENE", "0");
    json = Replace(json, "POSCOUNT", "4");
    json = Replace(json, "IMAGE64", Base64("PNGDATA"));
    json =
        Replace(json, "BUFFERURI", "data:application/octet-stream;base64," + Base64(QuadBuffer()));
    WriteScratchFile("gltft tex.png", "not really a png");
    Diagnostics diag;
    SceneDescription d = ReadGltfFile(WriteScratchFile("gltft_ext.gltf", json), diag);
    // The fixture's own warnings (EXT_made_up, line and point primitives) are about other
    // things; none names a material feature.
    for (const Warning &w : diag.Warnings())
        for (const char *what : {"KHR_materials", "KHR_texture", "texture", "emissi", "material"})
            EXPECT_EQ(w.message.find(what), std::string::npos) << w.message;
    ASSERT_EQ(d.materials.size(), 5u);
    const ParamSet &ps = d.materials[4].params;
    std::vector<float> tt = ps.GetFloats("basecolormaptransform");
    ASSERT_EQ(tt.size(), 5u);
    EXPECT_FLOAT_EQ(tt[0], 0.5f);
    EXPECT_FLOAT_EQ(tt[1], 0.25f);
    EXPECT_FLOAT_EQ(tt[2], 0.3f);
    EXPECT_FLOAT_EQ(tt[3], 2);
    EXPECT_FLOAT_EQ(tt[4], 4);
    EXPECT_NEAR(ps.GetFloat("specular", 0), 0.5, 1e-6);
    EXPECT_FLOAT_EQ(ps.GetRGB("specularcolor", RGB(0)).b, 0.25f);
    EXPECT_NEAR(ps.GetFloat("clearcoat", 0), 0.8, 1e-6);
    EXPECT_NEAR(ps.GetFloat("clearcoatroughness", 0), 0.1, 1e-6);
    EXPECT_NEAR(ps.GetFloat("occlusionstrength", 0), 0.7, 1e-6);
    // Textured emission is a textured area light (factor × strength × "emissionmap") on the
    // material's shapes; the material itself emits nothing.
    EXPECT_FALSE(ps.Has("emissive"));
    EXPECT_FALSE(ps.Has("emissivemap"));
    int lit = 0;
    for (const ShapeDesc &s : d.shapes)
        if (s.material == 4) {
            ASSERT_GE(s.areaLight, 0);
            const ParamSet &al = d.areaLights[size_t(s.areaLight)].params;
            EXPECT_FLOAT_EQ(al.GetRGB("L", RGB(0)).b, 1.f);
            EXPECT_FALSE(al.GetTexture("emissionmap").empty());
            ++lit;
        }
    EXPECT_GT(lit, 0);
    // metallicRoughness is data: its imagemap is read without the sRGB curve.
    const TextureDesc *mr = FindTexture(d, ps.GetTexture("metallicroughnessmap"));
    ASSERT_TRUE(mr);
    EXPECT_FALSE(mr->params.GetBool("gamma", true));
    const TextureDesc *bc = FindTexture(d, d.materials[0].params.GetTexture("basecolormap"));
    ASSERT_TRUE(bc);
    EXPECT_FALSE(bc->params.Has("gamma"));  // sRGB
    // The untextured "lamp" and the textured emission of "embedded" (issue 13: emissive
    // textures are area lights too).
    ASSERT_EQ(d.areaLights.size(), 2u);
}

// Triangle strips and fans become triangle lists with glTF's vertex order (every triangle
// wound as the first); points and lines are still skipped, warned once per mode.
TEST(GltfReader, StripsAndFansBecomeTriangles) {
    Diagnostics diag;
    SceneDescription d =
        ReadGltfFile(WriteGltf("gltft_strips", 0, true, "4",
                               {{R"({"attributes": {"POSITION": 0}, "mode": 1},)",
                                 R"({"attributes": {"POSITION": 0}, "mode": 6},)"},
                                {R"({"attributes": {"POSITION": 0}, "mode": 0},)",
                                 R"({"attributes": {"POSITION": 0}, "mode": 5},)"},
                                {R"({"attributes": {"POSITION": 4}, "material": 4}]})",
                                 R"({"attributes": {"POSITION": 4}, "material": 4},
                                    {"attributes": {"POSITION": 4}, "mode": 9}]})"}}),
                     diag);
    ASSERT_EQ(d.shapes.size(), 7u);
    EXPECT_EQ(d.shapes[2].params.GetInts("indices"), (std::vector<int>{1, 2, 0, 2, 3, 0}));
    EXPECT_EQ(d.shapes[3].params.GetInts("indices"), (std::vector<int>{0, 1, 2, 1, 3, 2}));
    int modeWarnings = 0, unknownModeWarnings = 0;
    for (const Warning &w : diag.Warnings()) {
        modeWarnings += w.message.find("primitive mode 1 (points or lines)") != std::string::npos;
        // Not a glTF mode at all: not called points or lines.
        unknownModeWarnings +=
            w.message.find("primitive mode 9 is not supported") != std::string::npos;
    }
    EXPECT_EQ(modeWarnings, 1);
    EXPECT_EQ(unknownModeWarnings, 1);
}

// A primitive without a material gets glTF's default material (base colour 1, metallic 1,
// roughness 1: Prism's "gltf" material with no parameters), not Prism's grey matte.
TEST(GltfReader, APrimitiveWithoutAMaterialHasGltfsDefaultMaterial) {
    Diagnostics diag;
    SceneDescription d =
        ReadGltfFile(WriteGltf("gltft_nomat", 0, true, "4",
                               {{R"({"attributes": {"POSITION": 4}, "material": 1},)",
                                 R"({"attributes": {"POSITION": 4}},)"}}),
                     diag);
    ASSERT_EQ(d.materials.size(), 6u);  // the file's five, then the default
    const MaterialDesc &m = d.materials[5];
    EXPECT_EQ(m.type, "gltf");
    EXPECT_EQ(m.name, "glTF default material");
    EXPECT_TRUE(m.params.Params().empty());
    ASSERT_EQ(d.shapes.size(), 5u);
    EXPECT_EQ(d.shapes[1].material, 5);
    EXPECT_EQ(d.shapes[1].areaLight, -1);
    EXPECT_EQ(d.shapes[0].material, 0);
}

// Every used extension Prism does not simulate is named once, with what is lost where that is
// known; extension textures read as their factors are named with the materials using them;
// an unsupported extension the file requires is an error at its place in the file.
TEST(GltfReader, UnsupportedExtensionsAreWarnedOnceOrRefusedWhenRequired) {
    Diagnostics diag;
    ReadGltfFile(WriteGltf("gltft_ext", 0, true, "4",
                           {{R"("EXT_made_up"],)", R"("EXT_made_up", "KHR_materials_sheen",
                     "KHR_materials_clearcoat"],)"},
                            {R"({"name": "gold",)",
                             R"({"name": "gold", "extensions": {"KHR_materials_sheen": {},
                     "KHR_materials_clearcoat": {"clearcoatFactor": 1,
                       "clearcoatTexture": {"index": 0}}},)"},
                            {R"({"name": "embedded",)",
                             R"({"name": "embedded", "extensions": {"KHR_materials_clearcoat": {
                       "clearcoatFactor": 1, "clearcoatTexture": {"index": 0}}},)"}}),
                 diag);
    std::vector<std::string> messages;
    for (const Warning &w : diag.Warnings()) messages.push_back(w.message);
    auto count = [&](const std::string &part) {
        return std::count_if(messages.begin(), messages.end(), [&](const std::string &m) {
            return m.find(part) != std::string::npos;
        });
    };
    EXPECT_EQ(count("glTF extension EXT_made_up is not supported and is ignored"), 1);
    EXPECT_EQ(count("glTF extension KHR_materials_sheen is not supported and is ignored (no "
                    "sheen lobe)"),
              1);
    EXPECT_EQ(count("KHR_materials_clearcoat clearcoatTexture is ignored (clearcoatFactor alone "
                    "is used), in material \"gold\" and 1 more"),
              1);
    EXPECT_EQ(count("KHR_materials_clearcoat is not"), 0);  // simulated
    EXPECT_EQ(count("KHR_lights_punctual"), 0);

    const std::string path =
        WriteGltf("gltft_required", 0, true, "4",
                  {{R"("extensionsRequired": ["KHR_lights_punctual"],)",
                    R"("extensionsRequired": ["KHR_lights_punctual", "KHR_materials_volume"],)"}});
    try {
        ReadGltfFile(path, diag);
        ADD_FAILURE() << "a required extension Prism lacks was accepted";
    } catch (const SceneError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("gltft_required.gltf:5:"), std::string::npos) << what;
        EXPECT_NE(what.find("requires glTF extension KHR_materials_volume, which Prism does not "
                            "support (transmissive surfaces are thin"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("(at /extensionsRequired/1)"), std::string::npos) << what;
    }
}

TEST(GltfReader, MalformedFilesAreSceneErrors) {
    Diagnostics diag;
    // TEXCOORD_0 accessor claims 100 elements in a 32-byte view.
    std::string path = WriteGltf("gltft_bad", 0, true, "100");
    try {
        ReadGltfFile(path, diag);
        ADD_FAILURE() << "expected SceneError";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("reaches past"), std::string::npos) << e.what();
    }
    // Huge counts must not overflow the bounds arithmetic.
    EXPECT_THROW(ReadGltfFile(WriteGltf("gltft_bad2", 0, true, "4611686018427387904"), diag),
                 SceneError);
    // A buffer view that reaches past its buffer.
    std::string json = Replace(kGltf, "\"byteOffset\": 108, \"byteLength\": 32",
                               "\"byteOffset\": 108, \"byteLength\": 3200");
    json = Replace(Replace(Replace(json, "SCENE", "0"), "POSCOUNT", "4"), "IMAGE64", "AAAA");
    json =
        Replace(json, "BUFFERURI", "data:application/octet-stream;base64," + Base64(QuadBuffer()));
    EXPECT_THROW(ReadGltfFile(WriteScratchFile("gltft_bad3.gltf", json), diag), SceneError);
    EXPECT_THROW(ReadGltfFile(WriteScratchFile("gltft_bad4.gltf", "{ \"asset\": "), diag),
                 SceneError);
    EXPECT_THROW(
        ReadGltfFile(WriteScratchFile("gltft_bad5.glb", "glTF\x02\x00\x00\x00garbage"), diag),
        SceneError);
    EXPECT_THROW(ReadGltfFile(::testing::TempDir() + "gltft_missing.gltf", diag), SceneError);
}

}  // namespace
}  // namespace prism
