// Whole-scene render tests: no NaNs on the quadric showcase, precision far from the origin
// (S5), area-light irradiance and penumbra against closed forms, instancing against the
// flattened scene, the shared external scenes, and "simulate only what the scene calls for".
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "assembly/build_scene.h"
#include "image/image_compare.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

Rendered RenderFile(const std::string &path, BuildSettings opts = {}) {
    if (opts.defaultIntegrator.empty()) opts.defaultIntegrator = "whitted";  // closed forms
    return RenderSceneFile(path, opts);
}

Rendered RenderText(const std::string &name, const std::string &text, BuildSettings opts = {}) {
    return RenderFile(WriteSceneText("prism_scene_render", name, text), opts);
}

TEST(SceneRender, QuadricsShowcaseHasNoNaN) {
    BuildSettings opts;
    opts.resolution = {200, 125};
    opts.spp = 4;
    for (Precision p : {Precision::Double, Precision::Float}) {
        opts.precision = p;
        Rendered r = RenderFile(Source + "/scenes/quadrics.pbrt", opts);
        EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
        for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
        EXPECT_TRUE(r.warnings.empty()) << r.warnings[0].ToString();
        EXPECT_GT(r.stats.rays.refraction, 0u);
    }
}

// A Whitted-style scene whose every coordinate is shifted by `offset`.
std::string ShiftedScene(double offset) {
    auto p = [&](double x, double y, double z) {
        std::ostringstream s;
        s.precision(17);
        s << x + offset << " " << y + offset << " " << z + offset;
        return s.str();
    };
    std::ostringstream s;
    s.precision(17);
    s << "LookAt " << p(0, 2, -6) << " " << p(0, 1, 0) << " 0 1 0\n"
      << "Camera \"perspective\" \"float fov\" 40\n"
      << "Film \"image\" \"integer xresolution\" 96 \"integer yresolution\" 72\n"
      << "Sampler \"stratified\" \"integer xsamples\" 1 \"integer ysamples\" 1\n"
      << "WorldBegin\n"
      << "LightSource \"point\" \"point3 from\" [" << p(-3, 6, -4) << "] \"rgb I\" [60 60 60]\n"
      << "Texture \"c\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [0.8 0.1 0.1] \"rgb tex2\" [0.9 "
         "0.8 0.1]\n"
      << "AttributeBegin Material \"matte\" \"texture Kd\" \"c\"\n"
      << "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point3 P\" [" << p(-20, 0, -20)
      << " " << p(20, 0, -20) << " " << p(20, 0, 20) << " " << p(-20, 0, 20) << "]\n"
      << "\"point2 uv\" [-20 -20 20 -20 20 20 -20 20]\nAttributeEnd\n"
      << "AttributeBegin Translate " << p(-0.8, 1, 1) << " Material \"mirror\"\n"
      << "Shape \"sphere\" \"float radius\" 0.9\nAttributeEnd\n"
      << "AttributeBegin Translate " << p(0.9, 0.8, -0.5) << " Material \"glass\"\n"
      << "Shape \"sphere\" \"float radius\" 0.7\nAttributeEnd\n"
      << "AttributeBegin Translate " << p(2.2, 0, 1) << " Rotate -90 1 0 0 Material \"plastic\"\n"
      << "Shape \"cylinder\" \"float radius\" 0.4 \"float zmin\" 0 \"float zmax\" "
         "1.5\nAttributeEnd\n";
    return s.str();
}

TEST(SceneRender, CameraFarFromOriginS5) {
    // docs/SHAPES.md S5: the same scene 1e6 units from the origin renders like the original
    // (≤ 1% of pixels differ, mean |dRGB| ≤ 1/255), thanks to camera-centred render space and
    // double-precision object transforms.
    Rendered a = RenderText("near", ShiftedScene(0));
    Rendered b = RenderText("far", ShiftedScene(1e6));
    ImageDiff d = CompareImages(a.image, b.image, 1.f / 255);
    EXPECT_LE(d.meanAbs, 1.0 / 255);
    EXPECT_LE(double(d.badPixels), 0.01 * a.image.width * a.image.height);
}

TEST(SceneRender, DiskLightIrradianceMatchesClosedForm) {
    // A one-sided disk light (radius R, radiance L) facing down at height h over a matte
    // floor; on the axis, E = pi L R^2 / (h^2 + R^2) and the floor's radiance is Kd E / pi.
    const double R = 1, h = 2, L = 5, kd = 0.5;
    std::ostringstream s;
    s << "LookAt 0 0.5 -0.5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 1\n"
      << "Film \"image\" \"integer xresolution\" 1 \"integer yresolution\" 1\n"
      << "Sampler \"stratified\" \"integer xsamples\" 1 \"integer ysamples\" 1\nWorldBegin\n"
      << "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [" << L << " " << L << " " << L
      << "] \"integer nsamples\" 64\n"
      << "Translate 0 " << h << " 0 Rotate 90 1 0 0\n"  // object +z → world -y
      << "Shape \"disk\" \"float radius\" " << R << "\nAttributeEnd\n"
      << "Material \"matte\" \"rgb Kd\" [" << kd << " " << kd << " " << kd << "]\n"
      << "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point3 P\" "
         "[-10 0 -10 10 0 -10 10 0 10 -10 0 10]\n";
    Rendered r = RenderText("disk_light", s.str());
    double want = kd * L * R * R / (h * h + R * R);
    EXPECT_NEAR(r.image.GetRGB(0, 0).g, want, 0.01 * want);
    EXPECT_EQ(r.stats.rays.shadow, 64u);
}

TEST(SceneRender, SphereOccluderCastsPredictedUmbraAndPenumbra) {
    // Disk light radius Rl at height H, sphere occluder radius r centred at height hs, floor at
    // y = 0. For a disk-like occluder the umbra radius on the floor is (r H - Rl hs)/(H - hs)
    // and the penumbra's outer radius (r H + Rl hs)/(H - hs).
    const double Rl = 0.5, H = 4, r = 0.5, hs = 1.5;
    const double umbra = (r * H - Rl * hs) / (H - hs), outer = (r * H + Rl * hs) / (H - hs);
    // Sample the floor along x with an orthographic camera looking straight down.
    const int W = 200;
    const double half = 2.0;
    std::ostringstream s;
    s << "LookAt 0 3 0  0 0 0  0 0 1\nCamera \"orthographic\" \"float screenwindow\" [" << -half
      << " " << half << " -0.01 0.01]\n"
      << "Film \"image\" \"integer xresolution\" " << W << " \"integer yresolution\" 1\n"
      << "Sampler \"stratified\" \"integer xsamples\" 1 \"integer ysamples\" 1\nWorldBegin\n"
      << "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [4 4 4] \"integer nsamples\" 256\n"
      << "Translate 0 " << H << " 0 Rotate 90 1 0 0\nShape \"disk\" \"float radius\" " << Rl
      << "\nAttributeEnd\n"
      << "AttributeBegin Translate 0 " << hs << " 0 Material \"matte\" \"rgb Kd\" [0 0 0]\n"
      << "Shape \"sphere\" \"float radius\" " << r << "\nAttributeEnd\n"
      << "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"
      << "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point3 P\" "
         "[-10 0 -10 10 0 -10 10 0 10 -10 0 10]\n";
    Rendered img = RenderText("penumbra", s.str());
    // Unoccluded reference: same scene without the sphere would be smooth; compare against the
    // brightest value near the edges of the penumbra instead (the lit floor falls off slowly).
    for (int x = 0; x < W; ++x) {
        // The camera looks down with +z up in the image, so image x runs along world -x.
        double wx = std::abs(-half + (x + 0.5) * (2 * half / W));
        float v = img.image.GetRGB(x, 0).g;
        if (wx < 0.9 * umbra) {
            EXPECT_EQ(v, 0.f) << "inside the umbra at |x| = " << wx;
        } else if (wx > 1.1 * outer) {
            // Fully lit: irradiance from the whole disk at horizontal offset wx.
            double d2 = H * H + wx * wx;
            double approx = 0.5 / Pi * 4 * Pi * Rl * Rl * (H * H / d2) / d2;  // small-disk limit
            EXPECT_NEAR(v, approx, 0.05 * approx) << "lit at |x| = " << wx;
        } else if (wx > 1.1 * umbra && wx < 0.9 * outer) {
            EXPECT_GT(v, 0.f) << "penumbra at |x| = " << wx;
        }
    }
}

const char *InstanceBody = R"(
AttributeBegin Material "glass" Shape "sphere" "float radius" 0.5 AttributeEnd
AttributeBegin Translate 0 -0.5 0 Material "plastic" "rgb Kd" [0.2 0.6 0.3]
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3] "point3 P" [-0.7 0 -0.7 0.7 0 -0.7 0.7 0 0.7 -0.7 0 0.7]
AttributeEnd
)";

std::string InstanceScene(bool instanced) {
    std::ostringstream s;
    s << "LookAt 0 2 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
      << "Film \"image\" \"integer xresolution\" 96 \"integer yresolution\" 64\n"
      << "Sampler \"stratified\" \"integer xsamples\" 1 \"integer ysamples\" 1\nWorldBegin\n"
      << "LightSource \"point\" \"point3 from\" [2 5 -3] \"rgb I\" [40 40 40]\n";
    const char *xforms[] = {"Translate -1.5 0 0", "Translate 1.5 0.2 0 Scale -1 1 1",
                            "Translate 0 0.3 1.5 Rotate 30 0 1 0 Scale 1.2 0.8 1.2"};
    if (instanced) s << "ObjectBegin \"thing\"" << InstanceBody << "ObjectEnd\n";
    for (const char *x : xforms) {
        s << "AttributeBegin " << x << "\n";
        if (instanced)
            s << "ObjectInstance \"thing\"\n";
        else
            s << InstanceBody;
        s << "AttributeEnd\n";
    }
    return s.str();
}

TEST(SceneRender, InstancingMatchesFlattenedScene) {
    Rendered a = RenderText("flat", InstanceScene(false));
    Rendered b = RenderText("instanced", InstanceScene(true));
    EXPECT_TRUE(b.warnings.empty()) << b.warnings[0].ToString();
    ImageDiff d = CompareImages(a.image, b.image, 1.f / 255);
    // Embree applies instance transforms in float; the flattened scene transforms in double.
    EXPECT_LE(d.badPixels, 3) << "max " << d.maxAbs;
    EXPECT_LT(d.meanAbs, 1e-3);
    EXPECT_GT(b.stats.rays.refraction, 0u);
}

TEST(SceneRender, SimulatesOnlyWhatTheSceneCallsFor) {
    // No glass → no refraction rays; no mirror → no reflection rays; no area light → one
    // shadow ray per light per hit.
    Rendered r = RenderText("plain", R"(
LookAt 0 2 -5  0 0 0  0 1 0
Camera "perspective"
Film "image" "integer xresolution" 32 "integer yresolution" 32
Sampler "stratified" "integer xsamples" 1 "integer ysamples" 1
WorldBegin
LightSource "point" "point3 from" [0 5 0] "rgb I" [10 10 10]
Material "plastic"
Shape "sphere"
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3] "point3 P" [-5 -1 -5 5 -1 -5 5 -1 5 -5 -1 5]
)");
    EXPECT_EQ(r.stats.rays.refraction, 0u);
    EXPECT_EQ(r.stats.rays.reflection, 0u);
    EXPECT_EQ(r.stats.rays.camera, 32u * 32u);
    EXPECT_LE(r.stats.rays.shadow, r.stats.rays.camera);
}

// Every external scene renders small without errors. Scenes that use only supported
// features warn about nothing but the integrator and sampler substitutions (a non-Whitted
// integrator and a sampler other than "stratified" are always named, by design: every pbrt
// scene here names one); pbrt-all-shapes warns once per unsupported feature.
TEST(SceneRender, SharedScenesRender) {
    fs::path shared = PRISM_SHARED_DIR;
    PRISM_REQUIRE_SHARED(shared / "scenes");
    const std::vector<std::string> scenes = {
        "pbrt-spheres-differentials-texfilt/spheres-differentials-texfilt.pbrt",
        "pbrt-teapot-area-light/teapot-area-light.pbrt",
        "pbrt-cornell-box-bitterli/scene.pbrt",
        "pbrt-veach-mis/mis.pbrt",
        "pbrt-simple-room/simple_room.pbrt",
        "pbrt-spot-light/lights/spot.pbrt",
        "pbrt-all-shapes/shapes/all-shapes.pbrt",
        "obj-cornellbox-original/CornellBox-Original.obj",
        "obj-cornellbox-mirror/CornellBox-Mirror.obj",
        "obj-spider/spider.obj",
        "gltf-boxtextured/BoxTextured.gltf",
        "gltf-duck/Duck.gltf",
        "gltf-damagedhelmet/DamagedHelmet.glb",
        "gltf-2cylinderengine/2CylinderEngine.glb",
        "gltf-shadows-spot/shadows-spot.gltf",
    };
    BuildSettings opts;
    opts.resolution = {160, 120};
    opts.spp = 1;
    opts.lightSamples = 1;
    for (const std::string &name : scenes) {
        SCOPED_TRACE(name);
        Rendered r;
        ASSERT_NO_THROW(r = RenderFile((shared / "scenes" / name).string(), opts));
        EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
        std::set<std::string> kinds;
        for (const Warning &w : r.warnings) {
            if (w.message.find("is rendered with Whitted") != std::string::npos) continue;
            if (w.message.find("is replaced by Prism's stratified sampler") != std::string::npos)
                continue;
            // Known, documented gaps in specific files:
            if (name.find("all-shapes") != std::string::npos) {
                EXPECT_TRUE(kinds.insert(w.message).second) << "repeated: " << w.ToString();
                EXPECT_NE(w.message.find("not supported"), std::string::npos) << w.ToString();
                continue;
            }
            if (name.find("spot.pbrt") != std::string::npos &&
                w.message.find("\"conedelta\"") != std::string::npos)
                continue;  // a misspelt parameter in the file itself (pbrt warns too)
            if (name.find("teapot-area-light") != std::string::npos &&
                w.message == "Accelerator \"kdtree\" is replaced by Embree's BVH")
                continue;  // the file names pbrt's kd-tree; Prism always builds Embree's BVH
            ADD_FAILURE() << "unexpected warning: " << w.ToString();
        }
    }
}

}  // namespace
}  // namespace prism
