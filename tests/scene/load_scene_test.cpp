// LoadScene: format dispatch, errors, default camera/lights, bounds, and the shared external
// OBJ/glTF scenes (triangle counts from /work/shared/scenes/MANIFEST.md).
#include "scene/load_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/errors.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

std::string ErrorOf(const std::string &path) {
    // The message without its location, unlike test::ErrorOf.
    Diagnostics diag;
    try {
        LoadScene(path, diag);
    } catch (const SceneError &e) {
        return e.Message();
    }
    return kNoError;
}

size_t TriangleCount(const SceneDescription &d) {
    size_t n = 0;
    for (const ShapeDesc &s : d.shapes)
        if (s.type == "trianglemesh") n += s.params.GetInts("indices").size() / 3;
    return n;
}

bool HasNote(const SceneDescription &d, const std::string &text) {
    for (const std::string &n : d.notes)
        if (n.find(text) != std::string::npos) return true;
    return false;
}

TEST(LoadScene, Errors) {
    std::string xyz = WriteScratchFile("ls_scene.xyz", "whatever");
    EXPECT_EQ(
        ErrorOf(xyz),
        "unsupported scene format \".xyz\" (expected .pbrt, .obj, .gltf, .glb, .ply or .stl)");
    std::string missing = ::testing::TempDir() + "ls_missing.obj";
    EXPECT_EQ(ErrorOf(missing), "cannot open file \"" + missing + "\"");
}

TEST(LoadScene, DispatchesPbrt) {
    std::string path = WriteScratchFile("ls_tiny.pbrt",
                                        "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\n"
                                        "WorldBegin\nShape \"sphere\"\nWorldEnd\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    EXPECT_EQ(d.format, "pbrt");
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].type, "sphere");
    EXPECT_TRUE(d.lights.empty());  // pbrt files get no default lights
}

// The default view of a right-handed, y-up scene: the centre is ahead, world +x appears on
// the right, +y up, and the whole bounding box is inside the 40° field of view.
TEST(LoadScene, ObjGetsFramedCameraAndDefaultLights) {
    std::string path = WriteScratchFile("ls_box.obj",
                                        "v -1 0 -2\nv 3 0 -2\nv 3 2 -2\nv -1 2 -2\n"
                                        "v -1 0 2\nv 3 0 2\nv 3 2 2\nv -1 2 2\n"
                                        "f 1 2 3 4\nf 5 6 7 8\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    ASSERT_TRUE(d.camera.specified);
    EXPECT_EQ(d.camera.type, "perspective");
    EXPECT_EQ(d.camera.params.GetFloat("fov", 0), 40.f);
    EXPECT_TRUE(HasNote(d, "no camera in file"));
    EXPECT_TRUE(HasNote(d, "no lights in file"));
    // The studio rig: key, fill, environment.
    ASSERT_EQ(d.lights.size(), 3u);
    EXPECT_EQ(d.lights[0].type, "distant");
    // The key light shines from the viewer's side, upper left, in camera space.
    Vec3d from = Vec3d(d.lights[0].params.GetPoint3("from", Vec3f(0, 0, 0)));
    Vec3d to = Vec3d(d.lights[0].params.GetPoint3("to", Vec3f(0, 0, 0)));
    Vec3d towardLight = d.camera.cameraFromWorld.Vector(from - to);
    EXPECT_LT(towardLight.x, 0);
    EXPECT_GT(towardLight.y, 0);
    EXPECT_LT(towardLight.z, 0);

    Bounds3f b = SceneMeshBounds(d);
    EXPECT_EQ(b.pMin, Vec3f(-1, 0, -2));
    EXPECT_EQ(b.pMax, Vec3f(3, 2, 2));
    const Transform &cw = d.camera.cameraFromWorld;
    Vec3d c = cw.Point(Vec3d(b.Center()));
    EXPECT_NEAR(c.x, 0, 1e-6);
    EXPECT_NEAR(c.y, 0, 1e-6);
    EXPECT_GT(c.z, 0);
    Vec3d right = cw.Point(Vec3d(b.Center()) + Vec3d(1, 0, 0));
    EXPECT_GT(right.x, c.x);
    Vec3d up = cw.Point(Vec3d(b.Center()) + Vec3d(0, 1, 0));
    EXPECT_GT(up.y, c.y);
    double tanHalf = std::tan(Radians(20));
    for (int i = 0; i < 8; ++i) {
        Vec3d p = cw.Point(Vec3d(b.Corner(i)));
        ASSERT_GT(p.z, 0);
        EXPECT_LE(std::abs(p.x / p.z), tanHalf) << i;
        EXPECT_LE(std::abs(p.y / p.z), tanHalf) << i;
    }
}

// The studio rig (docs/USAGE.md "Lighting"): a key from above the camera, a
// weaker fill from its right, a dim uniform environment with stratified samples.
TEST(LoadScene, LightLessModelGetsTheStudioRig) {
    std::string path = WriteScratchFile("ls_rig.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    ASSERT_EQ(d.lights.size(), 3u);
    EXPECT_TRUE(HasNote(d, "studio rig"));
    const Transform &cw = d.camera.cameraFromWorld;
    auto toward = [&](const LightDesc &l) {
        Vec3d from = Vec3d(l.params.GetPoint3("from", Vec3f(0, 0, 0)));
        Vec3d to = Vec3d(l.params.GetPoint3("to", Vec3f(0, 0, 0)));
        return Normalize(cw.Vector(from - to));
    };
    EXPECT_EQ(d.lights[0].type, "distant");
    EXPECT_EQ(d.lights[1].type, "distant");
    Vec3d key = toward(d.lights[0]), fill = toward(d.lights[1]);
    EXPECT_GT(key.y, 0.7);   // from above the camera
    EXPECT_LT(key.z, 0);     // on the viewer's side
    EXPECT_GT(fill.x, 0.8);  // from the right
    float keyL = d.lights[0].params.GetRGB("L", RGB(0)).g;
    float fillL = d.lights[1].params.GetRGB("L", RGB(0)).g;
    EXPECT_GT(keyL, 2 * fillL);
    const LightDesc &env = d.lights[2];
    EXPECT_EQ(env.type, "infinite");
    EXPECT_EQ(env.params.GetString("mapname", ""), "");
    float envL = env.params.GetRGB("L", RGB(0)).g;
    EXPECT_GT(envL, 0.05f);
    EXPECT_LT(envL, 0.3f);  // dim: the background stays darker than a lit white surface
    EXPECT_EQ(env.params.GetInt("nsamples", 1), 16);

    // LoadOptions::defaultLights off: no rig.
    LoadOptions noLights;
    noLights.defaultLights = false;
    EXPECT_TRUE(LoadScene(path, diag, noLights).lights.empty());
}

// --env: the equirectangular frame puts the map's top row up and its centre column ahead
// (-z for y-up formats), u growing to the viewer's right (+x), turned about up by the angle.
TEST(LoadScene, EnvironmentFrameAndReplaceOrAdd) {
    std::string path = WriteScratchFile("ls_env.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    EXPECT_EQ(SceneUpAxis(d), Vec3d(0, 1, 0));
    // Light space (pbrt's infinite light): z is the pole, u = atan2(y, x) / 2pi.
    auto uv = [](const Transform &worldFromLight, Vec3d wWorld) {
        Vec3d w = Normalize(worldFromLight.Inverse().Vector(wWorld));
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * Pi;
        return std::pair{phi / (2 * Pi), std::acos(std::clamp(w.z, -1.0, 1.0)) / Pi};
    };
    Transform f = EnvironmentFrame(d, 0);
    EXPECT_NEAR(uv(f, {0, 1, 0}).second, 0, 1e-9);    // up: top row
    EXPECT_NEAR(uv(f, {0, 0, -1}).first, 0.5, 1e-9);  // ahead: centre column
    EXPECT_NEAR(uv(f, {0, 0, -1}).second, 0.5, 1e-9);
    EXPECT_NEAR(uv(f, {1, 0, 0}).first, 0.75, 1e-9);  // right: u grows
    EXPECT_NEAR(uv(f, {-1, 0, 0}).first, 0.25, 1e-9);
    // Turned by 90 degrees counterclockwise seen from above: what was ahead is now at -x.
    Transform r = EnvironmentFrame(d, 90);
    EXPECT_NEAR(uv(r, {-1, 0, 0}).first, 0.5, 1e-9);
    EXPECT_NEAR(uv(r, {0, 0, 1}).first, 0.25, 1e-6);

    EnvironmentSpec spec;
    spec.L = RGB(0.5f, 0.25f, 1.f);
    SceneDescription added = d;
    spec.replace = false;
    AddEnvironment(added, spec);
    ASSERT_EQ(added.lights.size(), 4u);  // the rig and the environment
    EXPECT_EQ(added.lights.back().type, "infinite");
    EXPECT_EQ(added.lights.back().params.GetRGB("L", RGB(0)), spec.L);
    spec.replace = true;
    spec.mapFile = "sky.exr";
    AddEnvironment(d, spec);
    ASSERT_EQ(d.lights.size(), 1u);
    std::string map = d.lights[0].params.GetString("mapname", "");
    EXPECT_TRUE(std::filesystem::path(map).is_absolute()) << map;

    // pbrt: up is the world axis nearest the camera's up, ahead the one nearest its view.
    std::string pbrt = WriteScratchFile("ls_env.pbrt",
                                        "LookAt 0 -5 1  0 0 0.9  0 0.1 1\nCamera \"perspective\"\n"
                                        "WorldBegin\nWorldEnd\n");
    SceneDescription p = LoadScene(pbrt, diag);
    EXPECT_EQ(SceneUpAxis(p), Vec3d(0, 0, 1));
    Transform pf = EnvironmentFrame(p, 0);
    EXPECT_NEAR(uv(pf, {0, 0, 1}).second, 0, 1e-9);
    EXPECT_NEAR(uv(pf, {0, 1, 0}).first, 0.5, 1e-9);  // the camera looks along +y
    // pbrt's LookAt frame is left-handed: the camera shows world -x on the image's right, and
    // that is where u grows.
    EXPECT_NEAR(uv(pf, {-1, 0, 0}).first, 0.75, 1e-9);
    EXPECT_NEAR(uv(EnvironmentFrame(p, 90), {1, 0, 0}).first, 0.5, 1e-9);
}

TEST(LoadScene, EmissiveObjGetsNoDefaultLight) {
    WriteScratchFile("ls_lamp.mtl", "newmtl lamp\nKe 1 1 1\n");
    std::string path = WriteScratchFile("ls_lamp.obj",
                                        "mtllib ls_lamp.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                        "usemtl lamp\nf 1 2 3\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    EXPECT_TRUE(d.lights.empty());
    EXPECT_FALSE(HasNote(d, "no lights"));
    LoadOptions opts;
    opts.defaultCamera = false;
    SceneDescription n = LoadScene(path, diag, opts);
    EXPECT_FALSE(n.camera.specified);
}

TEST(LoadScene, PlyBecomesPlymeshScene) {
    std::string path =
        WriteScratchFile("ls_tri.ply",
                         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n10 0 0\n0 10 0\n3 0 1 2\n");
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    EXPECT_EQ(d.format, "ply");
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].type, "plymesh");
    std::string file = d.shapes[0].params.GetString("filename", "");
    EXPECT_EQ((std::filesystem::path(d.baseDir) / file).string(), path);
    ASSERT_TRUE(d.camera.specified);
    Vec3d c = d.camera.cameraFromWorld.Point(Vec3d(5, 5, 0));
    EXPECT_NEAR(c.x, 0, 1e-6);
    EXPECT_GT(c.z, 0);
    EXPECT_FALSE(d.lights.empty());
    // A broken PLY is reported by LoadScene, not later.
    std::string bad = WriteScratchFile("ls_bad.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 5\n"
                                       "property float x\nend_header\n1\n");
    EXPECT_NE(ErrorOf(bad).find("5 vertices"), std::string::npos) << ErrorOf(bad);
}

TEST(LoadScene, MeshBoundsUseShapeTransforms) {
    SceneDescription d;
    ShapeDesc s;
    s.type = "trianglemesh";
    Param p;
    p.type = ParamType::Point3;
    p.name = "P";
    p.numbers = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.params.Add(p);
    s.worldFromObject = Translate(Vec3d(10, 0, 0)) * Scale(2, 2, 2);
    d.shapes.push_back(s);
    Bounds3f b = SceneMeshBounds(d);
    EXPECT_EQ(b.pMin, Vec3f(10, 0, 0));
    EXPECT_EQ(b.pMax, Vec3f(12, 2, 0));
}

// ---- External scenes ---------------------------------------------------------------------

struct SharedScene {
    const char *file;
    size_t triangles;
    bool hasCamera;
};

class SharedScenes : public ::testing::TestWithParam<SharedScene> {};

TEST_P(SharedScenes, LoadsWithManifestTriangleCount) {
    std::string path = std::string(PRISM_SHARED_DIR) + "/scenes/" + GetParam().file;
    PRISM_REQUIRE_SHARED(path);
    Diagnostics diag;
    SceneDescription d;
    ASSERT_NO_THROW(d = LoadScene(path, diag)) << path;
    EXPECT_EQ(TriangleCount(d), GetParam().triangles);
    EXPECT_TRUE(d.camera.specified);  // from the file or framed
    EXPECT_EQ(HasNote(d, "no camera in file"), !GetParam().hasCamera);
    EXPECT_FALSE(SceneMeshBounds(d).IsEmpty());
    for (const ShapeDesc &s : d.shapes) {
        EXPECT_LT(s.material, int(d.materials.size()));
        EXPECT_LT(s.areaLight, int(d.areaLights.size()));
    }
    // Every texture refers to an existing file or an embedded image.
    for (const TextureDesc &t : d.textures) {
        if (t.type != "imagemap") continue;
        std::string f = t.params.GetString("filename", "");
        if (f.rfind("embedded:", 0) == 0) {
            EXPECT_LT(std::stoul(f.substr(9)), d.embeddedImages.size());
        } else {
            EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(d.baseDir) / f)) << f;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Manifest, SharedScenes,
    ::testing::Values(SharedScene{"obj-cornellbox-original/CornellBox-Original.obj", 36, false},
                      SharedScene{"obj-cornellbox-mirror/CornellBox-Mirror.obj", 36, false},
                      SharedScene{"obj-spider/spider.obj", 1368, false},
                      SharedScene{"gltf-boxtextured/BoxTextured.gltf", 12, false},
                      SharedScene{"gltf-duck/Duck.gltf", 4212, true},
                      SharedScene{"gltf-damagedhelmet/DamagedHelmet.glb", 15452, false},
                      SharedScene{"gltf-2cylinderengine/2CylinderEngine.glb", 121496, true},
                      SharedScene{"gltf-shadows-spot/shadows-spot.gltf", 1108, true}),
    [](const auto &info) {
        std::string n = std::filesystem::path(info.param.file).stem().string();
        for (char &c : n)
            if (!std::isalnum((unsigned char)c)) c = '_';
        return n;
    });

std::string Shared(const std::string &rel) {
    return std::string(PRISM_SHARED_DIR) + "/scenes/" + rel;
}

TEST(SharedSceneDetails, CornellBoxMaterials) {
    std::string path = Shared("obj-cornellbox-mirror/CornellBox-Mirror.obj");
    PRISM_REQUIRE_SHARED(path);
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    int mirrors = 0;
    for (const MaterialDesc &m : d.materials) mirrors += m.type == "mirror";
    EXPECT_EQ(mirrors, 1);
    EXPECT_EQ(d.areaLights.size(), 1u);
    EXPECT_TRUE(d.lights.empty());  // the Ke light is enough
}

TEST(SharedSceneDetails, SpiderTexturesAndDamagedHelmetImages) {
    std::string spider = Shared("obj-spider/spider.obj");
    std::string helmet = Shared("gltf-damagedhelmet/DamagedHelmet.glb");
    PRISM_REQUIRE_SHARED(spider);
    PRISM_REQUIRE_SHARED(helmet);
    Diagnostics diag;
    SceneDescription s = LoadScene(spider, diag);
    EXPECT_EQ(s.textures.size(), 5u);
    for (const TextureDesc &t : s.textures)
        EXPECT_EQ(t.params.GetString("filename", "").find('\\'), std::string::npos);
    EXPECT_EQ(s.lights.size(), 3u);  // the studio rig: key, fill, environment

    SceneDescription h = LoadScene(helmet, diag);
    ASSERT_EQ(h.materials.size(), 1u);
    // The glTF metallic-roughness material with its four material maps and the normal map.
    EXPECT_EQ(h.materials[0].type, "gltf");
    for (const char *map : {"basecolormap", "metallicroughnessmap", "occlusionmap"})
        EXPECT_FALSE(h.materials[0].params.GetTexture(map).empty()) << map;
    // The emissive texture makes the helmet's shapes a textured area light (and, being only
    // an emissive texture, leaves the studio rig on).
    ASSERT_FALSE(h.shapes.empty());
    ASSERT_GE(h.shapes[0].areaLight, 0);
    EXPECT_FALSE(
        h.areaLights[size_t(h.shapes[0].areaLight)].params.GetTexture("emissionmap").empty());
    EXPECT_EQ(h.lights.size(), 3u);
    // Base colour, metallic-roughness, emissive, occlusion and normal-map images.
    EXPECT_EQ(h.embeddedImages.size(), 5u);
    EXPECT_FALSE(h.materials[0].params.GetString("normalmap", "").empty());
    for (const EmbeddedImage &img : h.embeddedImages) {
        EXPECT_EQ(img.mimeType, "image/jpeg");
        ASSERT_GE(img.bytes.size(), 2u);
        EXPECT_EQ(img.bytes[0], 0xFF);  // JPEG SOI marker
        EXPECT_EQ(img.bytes[1], 0xD8);
    }
}

TEST(SharedSceneDetails, ShadowsSpotLightAndCamera) {
    std::string path = Shared("gltf-shadows-spot/shadows-spot.gltf");
    PRISM_REQUIRE_SHARED(path);
    Diagnostics diag;
    SceneDescription d = LoadScene(path, diag);
    ASSERT_EQ(d.lights.size(), 1u);
    EXPECT_EQ(d.lights[0].type, "spot");
    EXPECT_NEAR(d.lights[0].params.GetFloat("coneangle", 0), 0.393 * 180 / Pi, 0.1);
    EXPECT_EQ(d.film.params.GetInt("xresolution", 0), 1280);
    EXPECT_EQ(d.film.params.GetInt("yresolution", 0), 720);
    // The file lists KHR_lights_punctual as required; it is supported, so no warning.
    for (const Warning &w : diag.Warnings())
        EXPECT_EQ(w.message.find("KHR_lights_punctual"), std::string::npos) << w.message;
}

}  // namespace
}  // namespace prism
