// The lights of render/light_list.inc, created by their own Create (render/light.h): the
// registry, and what the scene assembly does with a LightSource it lacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "assembly/build_scene.h"
#include "image/image.h"
#include "image/image_io.h"
#include "render/goniometric_light.h"
#include "render/infinite_light.h"
#include "render/projection_light.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

TEST(Light, TheRegistryNamesEachLightOnce) {
    const std::vector<std::string> &names = LightNames();
    for (const char *n : {"point", "spot", "distant", "infinite", "goniometric", "projection"})
        EXPECT_EQ(std::count(names.begin(), names.end(), n), 1) << n;
    EXPECT_EQ(names.size(), 6u);
}

TEST(Light, EachLightSourceIsItsClassAndAnUnknownOneIsIgnoredWithAWarning) {
    Diagnostics diag(false);
    SceneDescription desc =
        LoadScene(test::WriteTestFile(test::ScratchDir("light") / "l.pbrt",
                                      "WorldBegin\nLightSource \"point\" \"rgb I\" [1 2 3]\n"
                                      "LightSource \"spot\"\nLightSource \"distant\"\n"
                                      "LightSource \"infinite\" \"integer nsamples\" 4\n"
                                      "LightSource \"lantern\"\nLightSource \"lantern\"\n"
                                      "Shape \"sphere\"\nWorldEnd\n"),
                  diag);
    BuildSettings s;
    s.resolution = Vec2i(4, 4);
    RenderScene scene = BuildRenderScene(desc, s, diag);
    ASSERT_EQ(scene.lights.size(), 4u);
    const char *want[] = {"point", "spot", "distant", "infinite"};
    for (size_t i = 0; i < 4; ++i) EXPECT_STREQ(scene.lights[i]->Name(), want[i]);
    EXPECT_EQ(scene.lights[3]->NumSamples(), 4);
    EXPECT_TRUE(scene.features.environment);
    int warned = 0;
    for (const Warning &w : diag.Warnings())
        warned +=
            w.loc.line == 6 && w.message.find("\"lantern\" is not supported") != std::string::npos;
    EXPECT_EQ(warned, 1);  // once per type
}

// A w x h map of value `base`, with value `bright` in the top-left quadrant.
std::shared_ptr<const Image> QuadrantMap(int w, int h, float base, float bright) {
    auto img = std::make_shared<Image>(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img->SetRGB(x, y, RGB(x < w / 2 && y < h / 2 ? bright : base));
    return img;
}

SurfaceInteraction At(const Vec3f &p) {
    SurfaceInteraction si;
    si.p = p;
    si.n = si.ns = Vec3f(0, 1, 0);
    return si;
}

// Monte Carlo estimate of the emitted power's luminance from SampleLe: the mean of
// Le / pdfDir over stratified direction samples (the integral of the intensity).
double PowerFromEmission(const Light &light) {
    const int n = 256;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            LightLeSample le;
            if (!light.SampleLe(Vec2f(0.5f, 0.5f), Vec2f((i + 0.5f) / n, (j + 0.5f) / n),
                                SceneSphere{}, &le))
                continue;
            float pdfPos, pdfDir;
            light.PdfLe(le.ray.o, le.n, le.ray.d, SceneSphere{}, &pdfPos, &pdfDir);
            EXPECT_FLOAT_EQ(pdfDir, le.pdfDir);
            sum += double(le.Le.Luminance()) / le.pdfDir;
        }
    return sum / (double(n) * n);
}

// A goniometric light with a constant map is a point light of I times the map's value: its
// power is 4 pi I c, and every point receives what the point light gives it.
TEST(GoniometricLight, AConstantMapIsAPointLightOfTheScaledIntensity) {
    const Transform renderFromLight = Translate(Vec3d(1, 2, 3)) * RotateX(30);
    const GoniometricLight gonio(renderFromLight, RGB(2, 3, 4), QuadrantMap(64, 32, 0.5f, 0.5f));
    const PointLight point(Vec3f(1, 2, 3), RGB(1, 1.5f, 2));
    EXPECT_NEAR(gonio.Power(1), 4 * Pi * RGB(1, 1.5f, 2).Luminance(), 1e-5);
    EXPECT_NEAR(PowerFromEmission(gonio), gonio.Power(1), 1e-4 * gonio.Power(1));
    for (Vec3f p : {Vec3f(0, 0, 0), Vec3f(4, -1, 2), Vec3f(1, 7, 3.5f), Vec3f(-3, 2, -9)}) {
        LightSample a, b;
        ASSERT_TRUE(gonio.SampleLi(At(p), Vec2f(0.5f, 0.5f), &a));
        ASSERT_TRUE(point.SampleLi(At(p), Vec2f(0.5f, 0.5f), &b));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.Li[c], b.Li[c], 1e-6f * b.Li[c]);
        EXPECT_LT(Length(a.wi - b.wi), 1e-6f);
        EXPECT_EQ(a.pLight, b.pLight);
    }
}

// The map's rows run from the light's +y (row 0) to -y and its columns from +x toward +z
// (pbrt-v3's render of scenes/pbrt3-reference/goniometric.pbrt shows the same): a bright
// top-left quadrant lights the directions with y > 0 and z > 0 only, also under a rotation.
TEST(GoniometricLight, TheTopLeftQuadrantLightsUpAndTowardPlusZ) {
    for (double angle : {0.0, 90.0}) {
        const Transform rot = RotateY(angle);  // light +z to render +x at 90 degrees
        const GoniometricLight l(rot, RGB(1), QuadrantMap(64, 32, 0, 1));
        auto scale = [&](Vec3d wLight) { return l.Scale(Vec3f(rot.Vector(wLight))).r; };
        EXPECT_NEAR(scale(Vec3d(0.3, 0.8, 0.5)), 1, 1e-6) << angle;
        EXPECT_NEAR(scale(Vec3d(-0.3, 0.8, 0.5)), 1, 1e-6) << angle;
        EXPECT_EQ(scale(Vec3d(0.3, 0.8, -0.5)), 0) << angle;
        EXPECT_EQ(scale(Vec3d(0.3, -0.8, 0.5)), 0) << angle;
        EXPECT_EQ(scale(Vec3d(-0.3, -0.8, -0.5)), 0) << angle;
    }
    // The quadrant covers a quarter of the sphere.
    const GoniometricLight l(Transform(), RGB(1), QuadrantMap(64, 32, 0, 1));
    EXPECT_NEAR(l.Power(1), Pi, 1e-9);
    EXPECT_NEAR(PowerFromEmission(l), Pi, 2e-3 * Pi);
}

// pbrt-v4's equal-area goniometric map ("filename"): the light's +y at the map's centre (its y
// and z swapped, as pbrt-v4 does), -y at its corners, +x at the middle of the right edge and
// +z at the middle of the bottom edge (rows from the top, core/equal_area.h); the nearest
// texel, its R, G and B averaged; power over the plain mean of the texels.
TEST(GoniometricLight, PbrtV4EqualAreaMapsPutPlusYAtTheirCentre) {
    auto map = std::make_shared<Image>(8, 8, 3);
    map->SetRGB(3, 3, RGB(3, 0, 0));    // next to the centre: averages to 1
    map->SetRGB(7, 3, RGB(0, 6, 0));    // right edge, just above its middle: +x
    map->SetRGB(3, 7, RGB(0, 0, 9));    // bottom edge, just left of its middle: +z
    map->SetRGB(0, 0, RGB(12, 0, 0));   // a corner: -y
    const Transform rot = RotateY(90);  // light +z to render +x
    const GoniometricLight l(rot, RGB(1), map, true);
    auto scale = [&](Vec3d wLight) { return l.Scale(Vec3f(rot.Vector(Normalize(wLight)))).r; };
    EXPECT_FLOAT_EQ(scale(Vec3d(-0.01, 1, -0.01)), 1);
    EXPECT_FLOAT_EQ(scale(Vec3d(1, 0.01, -0.01)), 2);
    EXPECT_FLOAT_EQ(scale(Vec3d(-0.01, 0.01, 1)), 3);
    EXPECT_FLOAT_EQ(scale(Vec3d(-0.3, -1, -0.3)), 4);
    EXPECT_EQ(scale(Vec3d(0.3, 1, 0.3)), 0);
    EXPECT_EQ(scale(Vec3d(-1, 0.01, -0.01)), 0);
    EXPECT_NEAR(l.MapAverage(), 10.0 / 64, 1e-9);
    EXPECT_NEAR(l.Power(1), 4 * Pi * 10.0 / 64, 1e-9);
    EXPECT_NEAR(PowerFromEmission(l), l.Power(1), 5e-3 * l.Power(1));
}

// A projection light with a constant map is the point light of I times the map's value inside
// its frustum (fov across the image's shorter side, aspect the image's) and dark outside; its
// power is I c times the frustum's solid angle, 4 asin(sin a sin b) for half angles a, b.
TEST(ProjectionLight, AConstantMapIsAPointLightInsideItsFrustum) {
    const double fov = 40;
    const Transform renderFromLight = Translate(Vec3d(0, 1, 0)) * RotateX(20);
    const ProjectionLight proj(renderFromLight, RGB(2), QuadrantMap(64, 32, 0.25f, 0.25f), fov);
    const double ty = std::tan(Radians(fov / 2)), tx = 2 * ty;
    const double omega = 4 * std::asin(std::sin(std::atan(tx)) * std::sin(std::atan(ty)));
    EXPECT_NEAR(proj.Power(1), 0.5 * omega, 1e-6);
    EXPECT_NEAR(PowerFromEmission(proj), proj.Power(1), 2e-3 * proj.Power(1));
    const PointLight point(Vec3f(0, 1, 0), RGB(0.5f));
    for (double fx : {-0.99, -0.5, 0.0, 0.7, 0.99, 1.01, -1.02})
        for (double fy : {-0.98, 0.0, 0.6, 1.03}) {
            const double dist = 3;
            const Vec3d wl = Normalize(Vec3d(fx * tx, fy * ty, 1));
            const Vec3f p = Vec3f(renderFromLight.Point(wl * dist));
            LightSample a, b;
            const bool lit = proj.SampleLi(At(p), Vec2f(0.5f, 0.5f), &a);
            ASSERT_TRUE(point.SampleLi(At(p), Vec2f(0.5f, 0.5f), &b));
            const bool inside = std::abs(fx) <= 1 && std::abs(fy) <= 1;
            EXPECT_EQ(lit, inside) << fx << " " << fy;
            if (lit) EXPECT_NEAR(a.Li.g, b.Li.g, 1e-5f * b.Li.g) << fx << " " << fy;
        }
    // Behind the light: dark.
    LightSample s;
    EXPECT_FALSE(proj.SampleLi(At(Vec3f(renderFromLight.Point(Vec3d(0, 0, -2)))), Vec2f(), &s));
}

// pbrt-v3 throws the image's top-left quadrant to the frustum's -x, -y corner (its render of
// scenes/pbrt3-reference/projection.pbrt: the image lands upside down on the wall it faces).
TEST(ProjectionLight, TheTopLeftQuadrantLandsAtMinusXMinusY) {
    const ProjectionLight l(Transform(), RGB(1), QuadrantMap(64, 32, 0, 1), 45);
    auto proj = [&](double x, double y) {
        return l.Projection(Vec3f(Normalize(Vec3d(x, y, 1)))).r;
    };
    EXPECT_NEAR(proj(-0.3, -0.1), 1, 1e-6);
    EXPECT_EQ(proj(0.3, -0.1), 0);
    EXPECT_EQ(proj(-0.3, 0.1), 0);
    EXPECT_EQ(proj(0.3, 0.1), 0);
    // A quarter of the frustum's solid angle by symmetry.
    const ProjectionLight full(Transform(), RGB(1), QuadrantMap(64, 32, 1, 1), 45);
    EXPECT_NEAR(l.Power(1), full.Power(1) / 4, 1e-9);
}

// pbrt-v4 throws "filename" upright: the top-left quadrant to the frustum's -x, +y corner, at
// the nearest texel (pbrt-v4's render of scenes/pbrt4-reference/projection-upright.pbrt).
TEST(ProjectionLight, PbrtV4ThrowsTheTopLeftQuadrantToMinusXPlusY) {
    auto map = std::make_shared<Image>(4, 2, 3);
    map->SetRGB(0, 0, RGB(1));
    map->SetRGB(1, 0, RGB(3));
    const ProjectionLight l(Transform(), RGB(1), map, 45, true);
    auto proj = [&](double x, double y) {
        return l.Projection(Vec3f(Normalize(Vec3d(x, y, 1)))).r;
    };
    EXPECT_EQ(proj(-0.6, 0.1), 1);
    EXPECT_EQ(proj(-0.1, 0.1), 3);  // nearest: no blend across the texel's edge at x = -0.41
    EXPECT_EQ(proj(-0.3, -0.1), 0);
    EXPECT_EQ(proj(0.3, 0.1), 0);
    const ProjectionLight v3(Transform(), RGB(1), map, 45);
    EXPECT_NEAR(l.Power(1), v3.Power(1), 1e-9);  // the mirror image: the same power
}

// Both lights read their image through the assembly (relative to the scene file), and a bad
// fov is an error at its location.
TEST(ImageLights, TheSceneAssemblyReadsTheirMapsBesideTheScene) {
    const std::filesystem::path dir = test::ScratchDir("imagelights");
    Image map(8, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) map.SetRGB(x, y, RGB(y < 2 ? 1.f : 0.f));
    WriteImage((dir / "map.exr").string(), map);
    Diagnostics diag(false);
    SceneDescription desc =
        LoadScene(test::WriteTestFile(
                      dir / "l.pbrt",
                      "WorldBegin\nLightSource \"goniometric\" \"string mapname\" \"map.exr\"\n"
                      "LightSource \"projection\" \"string mapname\" \"map.exr\"\n"
                      "Shape \"sphere\"\nWorldEnd\n"),
                  diag);
    BuildSettings s;
    s.resolution = Vec2i(4, 4);
    s.cameraRelative = false;
    RenderScene scene = BuildRenderScene(desc, s, diag);
    ASSERT_EQ(scene.lights.size(), 2u);
    const auto &g = dynamic_cast<const GoniometricLight &>(*scene.lights[0]);
    EXPECT_NEAR(g.Scale(Vec3f(0, 1, 0)).r, 1, 1e-6);
    EXPECT_EQ(g.Scale(Vec3f(0, -1, 0)).r, 0);
    const auto &p = dynamic_cast<const ProjectionLight &>(*scene.lights[1]);
    EXPECT_EQ(p.Projection(Normalize(Vec3f(0, 0.3f, 1))).r, 0);
    EXPECT_NEAR(p.Projection(Normalize(Vec3f(0, -0.3f, 1))).r, 1, 1e-6);
    EXPECT_FALSE(scene.features.environment);
    for (const Warning &w : diag.Warnings())
        EXPECT_EQ(w.message.find("light"), std::string::npos) << w.message;

    SceneDescription bad = LoadScene(
        test::WriteTestFile(dir / "bad.pbrt",
                            "WorldBegin\nLightSource \"projection\"\n  \"float fov\" [ 180 ]\n"
                            "WorldEnd\n"),
        diag);
    try {
        BuildRenderScene(bad, s, diag);
        ADD_FAILURE() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().line, 3) << e.what();
    }
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

// The lights of `lights` (LightSource and AreaLightSource lines, then a sphere), built.
RenderScene BuildLights(const std::string &name, const std::string &lights) {
    const std::filesystem::path dir = test::ScratchDir("photometric");
    Image white(16, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) white.SetRGB(x, y, RGB(1));
    WriteImage((dir / "white.exr").string(), white);
    Image square(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) square.SetRGB(x, y, RGB(1));
    WriteImage((dir / "square.exr").string(), square);
    Image half(16, 8, 3);  // 2 on its left half, 0 on its right: mean 1
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) half.SetRGB(x, y, RGB(x < 8 ? 2.f : 0.f));
    WriteImage((dir / "half.exr").string(), half);
    // A quad (one pbrt-v4 bilinear patch) and a triangle.
    test::WriteTestFile(dir / "quadtri.ply",
                        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 2\n"
                        "property list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n3 0 0\n3 2 0\n0 2 0\n5 0 0\n4 0 1 2 3\n3 1 4 2\n");
    Diagnostics diag(false);
    SceneDescription desc =
        LoadScene(test::WriteTestFile(dir / (name + ".pbrt"),
                                      "WorldBegin\n" + lights + "\nShape \"sphere\"\nWorldEnd\n"),
                  diag);
    BuildSettings s;
    s.resolution = Vec2i(4, 4);
    s.cameraRelative = false;
    RenderScene scene = BuildRenderScene(desc, s, diag);
    for (const Warning &w : diag.Warnings()) ADD_FAILURE() << w.ToString();
    return scene;
}

// pbrt-v4's "power" and "illuminance" (render/light.h PhotometricScale): the light emits that
// much, an RGB spectrum keeping its magnitude (so Power(), which is luminance-weighted, is the
// power times the RGB's luminance) and a blackbody counting as luminance 1. The figures the
// light makes on a diffuse plane match pbrt-v4's within 0.5% (docs/USAGE.md "Light power").
TEST(PhotometricLights, PowerAndIlluminanceScaleTheEmission) {
    const double y = RGB(2, 1, 0.5f).Luminance();
    struct Case {
        const char *text;
        double power;  // Power(1) expected
    };
    const Case cases[] = {
        {"LightSource \"point\" \"rgb I\" [2 1 0.5] \"float power\" 100", 100 * y},
        {"LightSource \"point\" \"rgb I\" [2 1 0.5] \"float power\" 100 \"float scale\" 3",
         300 * y},
        {"LightSource \"point\" \"blackbody I\" 3000 \"float power\" 100", 100},
        {"LightSource \"goniometric\" \"string filename\" \"square.exr\" \"float power\" 100", 100},
        {"LightSource \"goniometric\" \"rgb I\" [2 1 0.5] \"float power\" 100", 100 * y},
        {"LightSource \"projection\" \"string filename\" \"white.exr\" \"float power\" 100", 100},
        {"LightSource \"projection\" \"string mapname\" \"white.exr\" \"float power\" 100 "
         "\"float scale\" 2",
         200},
        {"LightSource \"spot\" \"rgb I\" [2 1 0.5] \"float power\" 50 \"float coneangle\" 40",
         50 * y},
        {"LightSource \"distant\" \"rgb L\" [2 1 0.5] \"float illuminance\" 10", Pi * 10 * y},
        {"LightSource \"infinite\" \"rgb L\" [2 1 0.5] \"float illuminance\" 10", 10 * y},
        // The map's upper hemisphere gives pi per unit of L, up to its 8 rows.
        {"LightSource \"infinite\" \"string mapname\" \"white.exr\" \"float illuminance\" 10", 10},
        // pbrt-v4's equal-area map, normalised as pbrt-v4 does it (texel centres, half the
        // solid angle): a white diffuse plane under it has radiance 6.795 in pbrt-v4.
        {"LightSource \"infinite\" \"string filename\" \"square.exr\" \"float illuminance\" 10",
         Pi * 6.795},
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 1 0.5] \"float power\" 100\n"
         "Shape \"disk\" \"float radius\" 0.5\nAttributeEnd",
         100 * y},
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 1 0.5] \"float power\" 100 "
         "\"bool twosided\" true\nShape \"trianglemesh\" \"point3 P\" [0 0 0 2 0 0 2 2 0] "
         "\"integer indices\" [0 1 2]\nAttributeEnd",
         100 * y},
        // pbrt-v4 makes each triangle of a mesh its own light, each emitting the power: a quad
        // of two unequal triangles emits twice it.
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 1 0.5] \"float power\" 100\n"
         "Shape \"trianglemesh\" \"point3 P\" [0 0 0 3 0 0 3 2 0 0 2 0] "
         "\"integer indices\" [0 1 2 0 2 3]\nAttributeEnd",
         200 * y},
        // pbrt-v4's bilinear patches are a light each, however finely Prism tessellates them:
        // a flat patch and a saddle (hundreds of triangles) emit twice the power.
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 1 0.5] \"float power\" 100\n"
         "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 3 0 0 0 2 0 3 2 0  5 0 0 7 0 1 5 2 1 7 2 0] "
         "\"integer indices\" [0 1 2 3 4 5 6 7]\nAttributeEnd",
         200 * y},
        // So is each quad of a PLY file (pbrt-v4 reads it as a bilinear patch), beside a
        // triangle.
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 1 0.5] \"float power\" 100\n"
         "Shape \"plymesh\" \"string filename\" \"quadtri.ply\"\nAttributeEnd",
         200 * y},
        // pbrt-v4's image area light ("filename"): "power" measured by the image's mean.
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"half.exr\" "
         "\"float power\" 100\nShape \"trianglemesh\" \"point3 P\" [0 0 0 3 0 0 3 2 0 0 2 0] "
         "\"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 1 2 0 2 3]\nAttributeEnd",
         200},
        // Without "power" the image is the radiance: a mean of 1 over 6 square units, x "scale".
        {"AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"half.exr\" "
         "\"float scale\" 2\nShape \"trianglemesh\" \"point3 P\" [0 0 0 3 0 0 3 2 0 0 2 0] "
         "\"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 1 2 0 2 3]\nAttributeEnd",
         2 * Pi * 6},
    };
    int i = 0;
    for (const Case &c : cases) {
        SCOPED_TRACE(c.text);
        const RenderScene scene = BuildLights("power" + std::to_string(i++), c.text);
        ASSERT_GE(scene.lights.size(), 1u);
        const double tolerance =
            std::string(c.text).find("map") != std::string::npos ||
                    std::string(c.text).find("filename") != std::string::npos
                ? 2e-3 * c.power
                : (std::string(c.text).find("blackbody") != std::string::npos ? 1e-3 * c.power
                                                                              : 1e-4 * c.power);
        EXPECT_NEAR(scene.lights[0]->Power(1), c.power, tolerance);
    }
    // Without the parameter, I and L are as written.
    const RenderScene plain = BuildLights("plain", "LightSource \"point\" \"rgb I\" [2 1 0.5]");
    EXPECT_NEAR(plain.lights[0]->Power(1), 4 * Pi * y, 1e-4);
}

// The message of the SceneError building `text` throws, or "" (with a failure) if none.
std::string BuildError(const std::string &name, const std::string &text) {
    try {
        BuildLights(name, text);
    } catch (const SceneError &e) {
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

TEST(PhotometricLights, ANegativePowerIsAnErrorAtTheParameter) {
    const std::pair<const char *, const char *> cases[] = {
        {"LightSource \"point\"\n  \"float power\" -1", ":3:3:"},
        {"LightSource \"distant\"\n  \"float illuminance\" -1", ":3:3:"},
        {"AttributeBegin\nAreaLightSource \"diffuse\"\n  \"float power\" -1\nShape \"sphere\"\n"
         "AttributeEnd",
         ":4:3:"}};
    for (const auto &[text, at] : cases) {
        SCOPED_TRACE(text);
        const std::string what = BuildError("negative", text);
        EXPECT_NE(what.find(std::string("negative.pbrt") + at), std::string::npos) << what;
        EXPECT_NE(what.find("must be finite and not negative"), std::string::npos) << what;
    }
}

// An area light's image and its "L" (or "emissionmap") both give its radiance: an error at
// "filename".
TEST(PhotometricLights, AreaLightImageAndLAreAnError) {
    for (const char *other : {"\"rgb L\" [1 1 1]", "\"rgb emissionmap\" [1 1 1]"}) {
        const std::string message = BuildError(
            "imageandl", std::string("AttributeBegin\nAreaLightSource \"diffuse\" ") + other +
                             "\n  \"string filename\" \"half.exr\"\nShape \"trianglemesh\" "
                             "\"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\n"
                             "AttributeEnd");
        EXPECT_NE(message.find("imageandl.pbrt:4:3:"), std::string::npos) << message;
        EXPECT_NE(message.find("both give its radiance"), std::string::npos) << message;
    }
}

// pbrt-v4's "filename" is a square equal-area map: another shape, or "mapname" beside it, is
// an error at the parameter.
TEST(PhotometricLights, EqualAreaMapMustBeSquareAndAlone) {
    const std::pair<const char *, const char *> cases[] = {
        {"LightSource \"infinite\"\n  \"string filename\" \"white.exr\"", "is 16x8"},
        {"LightSource \"goniometric\"\n  \"string filename\" \"white.exr\"", "is 16x8"},
        {"LightSource \"goniometric\" \"string mapname\" \"white.exr\"\n"
         "  \"string filename\" \"square.exr\"",
         "not both"},
        {"LightSource \"infinite\" \"string mapname\" \"white.exr\"\n"
         "  \"string filename\" \"square.exr\"",
         "not both"}};
    for (const auto &[text, what] : cases) {
        SCOPED_TRACE(text);
        const std::string message = BuildError("equalarea", text);
        EXPECT_NE(message.find("equalarea.pbrt:3:3:"), std::string::npos) << message;
        EXPECT_NE(message.find(what), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace prism
