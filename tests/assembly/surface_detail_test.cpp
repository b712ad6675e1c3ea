// Bump maps, normal maps and cut-outs through whole scenes: pbrt's "bumpmap" imagemap of a sine
// shades like the analytic normal field, a flat normal map changes nothing, textured "alpha"
// (pbrt), alphaMode MASK / BLEND (glTF) and map_d (OBJ) let exactly the cut-out rays through,
// and `prism info`'s effect set names them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/gltf_scene.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"
#include "support/text.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

Built BuildFile(const std::string &path, BuildSettings opts = {}) {
    opts.spp = 1;
    if (opts.defaultIntegrator.empty()) opts.defaultIntegrator = "whitted";
    return BuildSceneFile(path, opts);
}

class SurfaceDetail : public test::FreshDirTest {
  protected:
    std::string Write(const std::string &name, const std::string &text) {
        return test::WriteTestFile(dir_ / name, text);
    }
};

constexpr float BumpA = 0.05f;
constexpr int BumpW = 1024;

// The quad [0,1]^2 at z = 0 with uv = (x, y), seen straight down by an orthographic camera,
// 64 x 8 pixels of 1/64 each; a distant light from (1, 0, 1).
std::string BumpScene(const std::string &material) {
    return R"(LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.0625 0.0625]
Film "image" "integer xresolution" [64] "integer yresolution" [8]
PixelFilter "box"
WorldBegin
LightSource "distant" "point from" [1 0 1] "point to" [0 0 0] "rgb L" [1 1 1]
Texture "h" "float" "imagemap" "string filename" "h.exr"
)" + material +
           R"(
Shape "trianglemesh" "point P" [0 0 0 1 0 0 1 1 0 0 1 0] "integer indices" [0 1 2 0 2 3]
  "float uv" [0 0 1 0 1 1 0 1]
WorldEnd
)";
}

TEST_F(SurfaceDetail, SineBumpMapShadesLikeTheAnalyticNormalField) {
    // h(u) = A sin(2 pi u), sampled at texel centres.
    Image h(BumpW, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < BumpW; ++x)
            h.SetRGB(x, y, RGB(BumpA * std::sin(2 * float(Pi) * (float(x) + 0.5f) / BumpW)));
    WriteImage(Path("h.exr"), h);
    const std::string bumped = Write(
        "bump.pbrt", BumpScene(R"(Material "matte" "rgb Kd" [.5 .5 .5] "texture bumpmap" "h")"));
    const std::string flat =
        Write("flat.pbrt", BumpScene(R"(Material "matte" "rgb Kd" [.5 .5 .5])"));
    Built b = BuildFile(bumped), f = BuildFile(flat);
    for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::BumpMapping));
    EXPECT_FALSE(f.scene.features.effects.Has(Effect::BumpMapping));
    RenderStats stats;
    Image ib = Render(b.scene, &stats), iflat = Render(f.scene, &stats);
    const Vec3f l = Normalize(Vec3f(1, 0, 1));
    float maxChange = 0;
    for (int px = 0; px < 64; ++px) {
        // h'(u) is symmetric about u = 1/2, so a mirrored image axis changes nothing.
        float u = (float(px) + 0.5f) / 64;
        float slope = BumpA * 2 * float(Pi) * std::cos(2 * float(Pi) * u);
        Vec3f n = Normalize(Vec3f(-slope, 0, 1));
        float expected = 0.5f / float(Pi) * Dot(n, l);
        for (int py = 0; py < 8; ++py) {
            float got = ib.GetRGB(px, py).g;
            EXPECT_NEAR(got, expected, 5e-3 * expected) << px << "," << py;
            maxChange = std::max(maxChange, std::abs(got - iflat.GetRGB(px, py).g) / expected);
        }
    }
    EXPECT_GT(maxChange, 0.2f);  // the bump matters
}

TEST_F(SurfaceDetail, FlatNormalMapChangesNothing) {
    // A float EXR of (0.5, 0.5, 1) and a constant: meshes (generated tangents) and a sphere,
    // matte (no BSDF) and plastic (BSDF frame from the tangent).
    Image nm(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) nm.SetRGB(x, y, RGB(0.5f, 0.5f, 1.f));
    WriteImage(Path("flat_n.exr"), nm);
    auto scene = [&](const std::string &extra) {
        return R"(LookAt 0 -4 2  0 0 0  0 0 1
Camera "perspective" "float fov" [40]
Film "image" "integer xresolution" [48] "integer yresolution" [32]
PixelFilter "box"
WorldBegin
LightSource "point" "point from" [2 -3 4] "rgb I" [20 20 20]
LightSource "distant" "point from" [-1 -1 2] "point to" [0 0 0] "rgb L" [1 1 1]
AttributeBegin
Material "plastic" "rgb Kd" [.4 .3 .2] "rgb Ks" [.3 .3 .3] "float roughness" [.05] )" +
               extra + R"(
Shape "sphere" "float radius" [0.7]
AttributeEnd
Material "matte" "rgb Kd" [.5 .5 .5] )" +
               extra + R"(
Shape "trianglemesh" "point P" [-3 -3 -0.7 3 -3 -0.7 3 3 -0.7 -3 3 -0.7]
  "integer indices" [0 1 2 0 2 3] "float uv" [0 0 1 0 1 1 0 1]
  "normal N" [0 0 1 0 0 1 0 0 1 0 0 1]
WorldEnd
)";
    };
    RenderStats stats;
    Built plain = BuildFile(Write("plain.pbrt", scene("")));
    Image ref = Render(plain.scene, &stats);
    for (const std::string &extra :
         {std::string(R"("string normalmap" "flat_n.exr")"),
          std::string(R"("rgb normalmap" [0.5 0.5 1] "float normalscale" [3])")}) {
        SCOPED_TRACE(extra);
        Built b = BuildFile(Write("n.pbrt", scene(extra)));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        EXPECT_TRUE(b.scene.features.effects.Has(Effect::NormalMapping));
        Image img = Render(b.scene, &stats);
        ASSERT_EQ(img.pixels.size(), ref.pixels.size());
        double maxRef = 0;
        for (float v : ref.pixels) maxRef = std::max(maxRef, double(v));
        ASSERT_GT(maxRef, 0.05);
        for (size_t i = 0; i < ref.pixels.size(); ++i)
            ASSERT_NEAR(img.pixels[i], ref.pixels[i], 1e-6 * std::max(1.0, double(ref.pixels[i])))
                << i;
    }
}

// Shoots a grid of n x n rays at mesh shape `shape` of the render scene, down its geometric
// normal through the centres of the cells of its first triangle pair (p0, p1, p3 corners), and
// counts the camera rays that hit it and the shadow rays it blocks.
struct Through {
    int camera = 0, shadow = 0, total = 0;
};
Through CountThrough(const RenderScene &s, int shape, int n) {
    const TriangleMesh *m = s.accel->Mesh(shape);
    EXPECT_NE(m, nullptr);
    Through c;
    if (!m) return c;
    Vec3f p0 = m->Position(0), p1 = m->Position(1), p3 = m->Position(3);
    Vec3f nrm = m->GeometricNormal(0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Vec3f p = p0 + (p1 - p0) * ((float(i) + 0.5f) / float(n)) +
                      (p3 - p0) * ((float(j) + 0.5f) / float(n));
            Ray r{p + nrm * 0.5f, -nrm, Infinity, 0, 0};
            RawHit h;
            c.camera += s.accel->IntersectRaw(r, &h) && h.shape == shape;
            Ray sr{p + nrm * 0.5f, -nrm, 0.75f, 0, 0};
            c.shadow += s.accel->Occluded(sr);
            c.total++;
        }
    return c;
}

const char *QuadWithAlpha = R"(
Shape "trianglemesh" "point P" [0 0 0 1 0 0 1 1 0 0 1 0] "integer indices" [0 1 2 0 2 3]
  "float uv" [0 0 1 0 1 1 0 1] )";

TEST_F(SurfaceDetail, PbrtCheckerboardAlphaLetsExactlyHalfThrough) {
    const std::string head = R"(LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0
Camera "perspective"
WorldBegin
LightSource "point" "point from" [0.5 0.5 3]
Texture "check" "float" "checkerboard" "float uscale" [4] "float vscale" [4]
  "float tex1" [0] "float tex2" [1]
)";
    {
        Built b = BuildFile(Write("a.pbrt", head + QuadWithAlpha + R"("texture alpha" "check")"));
        for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
        EXPECT_TRUE(b.scene.features.effects.Has(Effect::Alpha));
        Through t = CountThrough(b.scene, 0, 32);
        EXPECT_EQ(t.camera, t.total / 2);
        EXPECT_EQ(t.shadow, t.total / 2);  // "shadowalpha" follows "alpha"
    }
    {
        // Shadows only: every camera ray hits, half the shadow rays pass.
        Built b =
            BuildFile(Write("s.pbrt", head + QuadWithAlpha + R"("texture shadowalpha" "check")"));
        Through t = CountThrough(b.scene, 0, 32);
        EXPECT_EQ(t.camera, t.total);
        EXPECT_EQ(t.shadow, t.total / 2);
    }
    {
        // A constant shadowalpha 0 beside a textured alpha: no shadows at all.
        Built b = BuildFile(Write(
            "c.pbrt", head + QuadWithAlpha + R"("texture alpha" "check" "float shadowalpha" 0)"));
        Through t = CountThrough(b.scene, 0, 32);
        EXPECT_EQ(t.camera, t.total / 2);
        EXPECT_EQ(t.shadow, 0);
    }
}

TEST_F(SurfaceDetail, RenderedCheckerboardAlphaShowsExactlyHalfTheQuad) {
    // The same cut-out through the renderer's threads and packets (Embree runs them with
    // denormals flushed to zero): an orthographic view that the quad fills, 8 x 8 pixels per
    // checker cell; the pixels whose camera ray hits the quad are lit, the others see nothing.
    const std::string text = R"(LookAt 0.5 0.5 5  0.5 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.5 0.5]
Film "image" "integer xresolution" [32] "integer yresolution" [32]
PixelFilter "box"
WorldBegin
LightSource "point" "point from" [0.5 0.5 3]
Texture "check" "float" "checkerboard" "float uscale" [4] "float vscale" [4]
  "float tex1" [0] "float tex2" [1]
)" + std::string(QuadWithAlpha) +
                             R"("texture alpha" "check")";
    Built b = BuildFile(Write("r.pbrt", text));
    RenderStats stats;
    Image img = Render(b.scene, &stats);
    int lit = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) lit += img.GetRGB(x, y).g > 0;
    EXPECT_EQ(lit, 512);
    EXPECT_EQ(stats.rays.shadow, 512u);  // one shadow ray per hit
}

// A glTF quad (z = 0, [0,1]^2) with one material given as JSON.
std::string GltfQuad(const std::string &material) {
    // 4 float3 positions (48 bytes), 4 float2 uv (32 bytes), 6 ushort indices (12 bytes).
    std::string bin;
    auto put = [&](const void *p, size_t n) { bin.append(static_cast<const char *>(p), n); };
    float P[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    put(P, sizeof P);
    put(uv, sizeof uv);
    put(idx, sizeof idx);
    const std::string enc = test::Base64(bin);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
"nodes": [{"mesh": 0}],
"meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
  "material": 0}]}],
"materials": [)" +
           material + R"(],
"buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,)" +
           enc + R"("}],
"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
  {"buffer": 0, "byteOffset": 48, "byteLength": 32},
  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
"accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
    "min": [0, 0, 0], "max": [1, 1, 0]},
  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

TEST_F(SurfaceDetail, GltfMaskAndBlend) {
    auto count = [&](const std::string &name, const std::string &material) {
        Built b = BuildFile(Write(name, GltfQuad(material)));
        for (const Warning &w : b.warnings) ADD_FAILURE() << name << ": " << w.ToString();
        // The studio rig's lights are added after the model: the quad is shape 0, if present.
        if (b.scene.accel->NumShapes() == 0 || !b.scene.accel->Mesh(0)) return Through{};
        return CountThrough(b.scene, 0, 32);
    };
    const std::string base = R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, )";
    // MASK: the factor's alpha against alphaCutoff decides for the whole quad.
    Through opaque = count("m1.gltf", base + R"(0.6]}, "alphaMode": "MASK"})");
    EXPECT_EQ(opaque.camera, 32 * 32);
    Through cut = count("m2.gltf", base + R"(0.4]}, "alphaMode": "MASK"})");
    EXPECT_EQ(cut.camera, 0);
    Through cutoff = count("m3.gltf", base + R"(0.6]}, "alphaMode": "MASK", "alphaCutoff": 0.7})");
    EXPECT_EQ(cutoff.camera, 0);
    // BLEND: stochastic transparency of camera and shadow rays, about alpha of them hit (issue
    // 13: blended materials cast stochastic shadows; before, they cast none).
    Through blend = count("b.gltf", base + R"(0.5]}, "alphaMode": "BLEND"})");
    EXPECT_NEAR(double(blend.camera) / blend.total, 0.5, 0.05);
    EXPECT_NEAR(double(blend.shadow) / blend.total, 0.5, 0.05);
    Through again = count("b2.gltf", base + R"(0.5]}, "alphaMode": "BLEND"})");
    EXPECT_EQ(again.camera, blend.camera);  // deterministic
    // OPAQUE ignores the alpha.
    Through op = count("o.gltf", base + R"(0.1]}})");
    EXPECT_EQ(op.camera, 32 * 32);
}

TEST_F(SurfaceDetail, ObjMapDLetsExactlyTheMaskedHalfThrough) {
    // An 8 x 8 checkerboard of 0 and 1; rays at the texel centres.
    Image d(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) d.SetRGB(x, y, RGB(float((x + y) & 1)));
    WriteImage(Path("mask.exr"), d);
    Write("quad.mtl", "newmtl leaf\nKd 0.2 0.6 0.2\nmap_d mask.exr\n");
    std::string obj = Write("quad.obj", R"(mtllib quad.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl leaf
f 1/1 2/2 3/3
f 1/1 3/3 4/4
)");
    Built b = BuildFile(obj);
    for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::Alpha));
    Through t = CountThrough(b.scene, 0, 8);
    EXPECT_EQ(t.camera, 32);
    EXPECT_EQ(t.shadow, 32);
}

TEST_F(SurfaceDetail, ObjBumpAndNormMapsAreRead) {
    Image h(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) h.SetRGB(x, y, RGB(float(x) / 4, 0.5f, 1.f));
    WriteImage(Path("tex.exr"), h);
    Write("m.mtl",
          "newmtl a\nKd 0.5 0.5 0.5\nbump -bm 0.5 tex.exr\nnewmtl b\nKd 0.5 0.5 0.5\n"
          "norm tex.exr\n");
    std::string obj = Write("m.obj", R"(mtllib m.mtl
v 0 0 0
v 1 0 0
v 1 1 0
vt 0 0
vt 1 0
vt 1 1
usemtl a
f 1/1 2/2 3/3
usemtl b
f 1/1 2/2 3/3
)");
    Built b = BuildFile(obj);
    for (const Warning &w : b.warnings) ADD_FAILURE() << w.ToString();
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::BumpMapping));
    EXPECT_TRUE(b.scene.features.effects.Has(Effect::NormalMapping));
}

}  // namespace
}  // namespace prism
