// The thin-lens camera (depth of field): a point in the focal plane stays sharp, and an
// out-of-focus point spreads into a blur circle of the diameter the thin-lens formula gives.
#include "render/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

// Distance from point p to the line through the ray.
double DistanceToRay(const Ray &r, const Vec3d &p) {
    Vec3d o(r.o), d = Normalize(Vec3d(r.d));
    Vec3d v = p - o;
    return Length(v - d * Dot(v, d));
}

TEST(ThinLens, PointInTheFocalPlaneStaysSharp) {
    CameraParams p;
    p.fovDeg = 40;
    p.lensRadius = 0.3;
    p.focalDistance = 4;
    const Vec2i res(64, 48);
    Camera lens(p, Transform(), res, 64.0 / 48);
    p.lensRadius = 0;
    Camera pinhole(p, Transform(), res, 64.0 / 48);
    for (Vec2f pFilm : {Vec2f(20.3f, 41.7f), Vec2f(32, 24), Vec2f(0.5f, 3.25f)}) {
        // The pinhole ray through pFilm meets the focal plane (z = 4) at P.
        Ray r0 = pinhole.GenerateRay(pFilm, Vec2f(0.5f, 0.5f));
        Vec3d d0(r0.d);
        Vec3d P = Vec3d(r0.o) + d0 * (4 / d0.z);
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j) {
                Ray r = lens.GenerateRay(pFilm, Vec2f((i + 0.5f) / 8, (j + 0.3f) / 8));
                EXPECT_LT(DistanceToRay(r, P), 1e-5 * Length(P));
                // The ray leaves the lens disk (z = 0, radius 0.3).
                EXPECT_LE(std::hypot(double(r.o.x), double(r.o.y)), 0.3 + 1e-6);
            }
    }
}

// A self-luminous sphere (radiance 1) of radius `radius` on the axis at depth z, seen by a
// 64 x 64 camera (fov 30) with a lens of radius 0.5 focused at 5, 256 samples per pixel.
Image RenderBall(double z, double radius, double lensRadius = 0.5) {
    std::string text =
        "LookAt 0 0 0  0 0 1  0 1 0\n"
        "Camera \"perspective\" \"float fov\" [ 30 ] \"float lensradius\" [ " +
        std::to_string(lensRadius) +
        " ] \"float focaldistance\" [ 5 ]\n"
        "Film \"image\" \"integer xresolution\" [ 64 ] \"integer yresolution\" [ 64 ]\n"
        "Sampler \"stratified\" \"integer xsamples\" [ 16 ] \"integer ysamples\" [ 16 ]\n"
        "PixelFilter \"box\"\nWorldBegin\nAttributeBegin\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\nTranslate 0 0 " +
        std::to_string(z) + "\nShape \"sphere\" \"float radius\" [ " + std::to_string(radius) +
        " ]\nAttributeEnd\nWorldEnd\n";
    fs::path dir = fs::path(::testing::TempDir()) / "prism_camera";
    fs::create_directories(dir);
    fs::path file = dir / "ball.pbrt";
    std::ofstream(file) << text;
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(file.string(), diag);
    RenderScene scene = BuildRenderScene(desc, BuildSettings{}, diag);
    return Render(scene, nullptr);
}

// The diameter of the ball's image, from its energy and its plateau: the image is the ball's
// sharp image (diameter d0) convolved with the normalized blur disk (diameter D), so its sum
// over the plateau value is the blur disk's area when D > d0.
double BlurDiameter(const Image &img, double d0, double D) {
    double sum = 0, cx = 0, cy = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            double v = img.pixels[img.PixelOffset(x, y)];
            sum += v;
            cx += v * (x + 0.5);
            cy += v * (y + 0.5);
        }
    cx /= sum;
    cy /= sum;
    double plateau = 0;
    int n = 0;
    const double r = std::max(0.5, (D - d0) / 2 - 1.5);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r) {
                plateau += img.pixels[img.PixelOffset(x, y)];
                ++n;
            }
    plateau /= n;
    return 2 * std::sqrt(sum / plateau / Pi);
}

TEST(ThinLens, BlurCircleMatchesTheThinLensFormula) {
    const double tanHalf = std::tan(Radians(15.0)), pixelsPerUnit = 64 / (2 * tanHalf);
    const double lensRadius = 0.5, focus = 5;
    // Behind the focal plane and in front of it.
    for (auto [z, radius] : {std::pair{10.0, 0.25}, std::pair{2.5, 0.1}}) {
        // Rays through the lens disk that meet at the ball's centre cross the focal plane in a
        // disk of radius lensRadius |1 - focus / z|, which the film sees at scale 1 / focus.
        const double D = 2 * lensRadius * std::abs(1 - focus / z) / focus * pixelsPerUnit;
        const double d0 = 2 * radius / z * pixelsPerUnit;
        ASSERT_GT(D, d0 + 4);
        Image img = RenderBall(z, radius);
        EXPECT_NEAR(BlurDiameter(img, d0, D), D, 1.0) << "ball at depth " << z;
    }
    // In the focal plane the ball is as sharp as through a pinhole: the same pixels are lit.
    Image lens = RenderBall(5, 0.3), pinhole = RenderBall(5, 0.3, 0);
    int differ = 0, lit = 0;
    for (size_t i = 0; i < lens.pixels.size(); i += 3) {
        lit += pinhole.pixels[i] > 0.5f;
        differ += (lens.pixels[i] > 0.5f) != (pinhole.pixels[i] > 0.5f);
    }
    EXPECT_GT(lit, 40);
    EXPECT_LE(differ, 2);
}

// pbrt-v3's environment camera, as its render of coloured spheres around the camera shows
// (scenes/pbrt3-reference/envcamera.pbrt): the left edge looks along +x, a quarter across
// along +z, the centre along -x, three quarters along -z; the top row up (+y), the bottom
// row down.
TEST(EnvironmentCamera, PixelsLookWherePbrtV3Looks) {
    CameraParams p;
    p.environment = true;
    p.fovDeg = 30;  // ignored
    const Vec2i res(200, 100);
    const Camera cam(p, Transform(), res, 2.0);
    struct Case {
        Vec2f pFilm;
        Vec3f d;
    } cases[] = {{{0, 50}, {1, 0, 0}},    {{50, 50}, {0, 0, 1}},  {{100, 50}, {-1, 0, 0}},
                 {{150, 50}, {0, 0, -1}}, {{200, 50}, {1, 0, 0}}, {{37, 0}, {0, 1, 0}},
                 {{137, 100}, {0, -1, 0}}};
    for (const Case &c : cases) {
        const Ray r = cam.GenerateRay(c.pFilm, Vec2f(0.5f, 0.5f));
        EXPECT_LT(Length(r.d - c.d), 1e-5f) << c.pFilm.x << " " << c.pFilm.y;
        EXPECT_EQ(r.o, Vec3f(0, 0, 0));
    }
    // Halfway up, a quarter across: between +y and +z.
    const Ray r = cam.GenerateRay(Vec2f(50, 25), Vec2f(0.5f, 0.5f));
    EXPECT_LT(Length(r.d - Normalize(Vec3f(0, 1, 1))), 1e-5f);
    // Not a projection: bidirectional light tracing has no importance for it.
    EXPECT_TRUE(cam.GetProjection().environment);
}

// The scene assembly makes Camera "environment" a lat-long camera under the file's LookAt (and
// no longer a perspective one), and reports the fov it does not read.
TEST(EnvironmentCamera, TheAssemblyBuildsItUnderTheCameraTransform) {
    const fs::path dir = fs::path(::testing::TempDir()) / "envcamera";
    fs::create_directories(dir);
    const std::string file = (dir / "e.pbrt").string();
    std::ofstream(file) << "LookAt 1 2 3  1 2 4  1 0 0\n"  // looks along +z, camera +y is +x
                           "Camera \"environment\" \"float fov\" [ 40 ]\n"
                           "Film \"image\" \"integer xresolution\" [ 64 ] "
                           "\"integer yresolution\" [ 32 ]\n"
                           "WorldBegin\nShape \"sphere\"\nWorldEnd\n";
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(file, diag);
    BuildSettings settings;
    settings.cameraRelative = false;
    RenderScene scene = BuildRenderScene(desc, settings, diag);
    // LookAt makes camera +x world -y, +y world +x (up), +z world +z: the top row looks
    // along world +x, a quarter across along +z, the left edge along -y.
    const Ray top = scene.camera->GenerateRay(Vec2f(10, 0), Vec2f(0.5f, 0.5f));
    EXPECT_LT(Length(top.d - Vec3f(1, 0, 0)), 1e-5f);
    EXPECT_LT(Length(top.o - Vec3f(1, 2, 3)), 1e-5f);
    const Ray quarter = scene.camera->GenerateRay(Vec2f(16, 16), Vec2f(0.5f, 0.5f));
    EXPECT_LT(Length(quarter.d - Vec3f(0, 0, 1)), 1e-5f);
    const Ray left = scene.camera->GenerateRay(Vec2f(0, 16), Vec2f(0.5f, 0.5f));
    EXPECT_LT(Length(left.d - Vec3f(0, -1, 0)), 1e-5f);
    bool unused = false;
    for (const Warning &w : diag.Warnings()) unused |= w.message.find("fov") != std::string::npos;
    EXPECT_TRUE(unused);
}

RenderScene BuildSpherical(const std::string &name, const std::string &camera, int w, int h,
                           Diagnostics &diag) {
    const fs::path dir = fs::path(::testing::TempDir()) / "spherical";
    fs::create_directories(dir);
    const std::string file = (dir / (name + ".pbrt")).string();
    std::ofstream(file) << camera << "\nFilm \"rgb\" \"integer xresolution\" [ " << w
                        << " ] \"integer yresolution\" [ " << h << " ]\n"
                        << "WorldBegin\nLightSource \"point\"\nShape \"sphere\"\n";
    SceneDescription desc = LoadScene(file, diag);
    BuildSettings settings;
    settings.cameraRelative = false;
    return BuildRenderScene(desc, settings, diag);
}

// pbrt-v4's Camera "spherical": by default the equal-area map of a square film, its pole at
// camera +y (the centre looks up, the corners down, the right edge's middle along +x, the
// bottom edge's middle forward along +z); "equirectangular" is the environment camera.
TEST(SphericalCamera, EqualAreaPixelsLookWherePbrtV4Looks) {
    Diagnostics diag(false);
    RenderScene scene = BuildSpherical("ea", "Camera \"spherical\"", 64, 64, diag);
    EXPECT_EQ(diag.Warnings().size(), 0u);
    const struct {
        Vec2f pFilm;
        Vec3f d;
    } cases[] = {{{32, 32}, {0, 1, 0}},  {{0, 0}, {0, -1, 0}},
                 {{64, 64}, {0, -1, 0}}, {{64, 32}, {1, 0, 0}},
                 {{0, 32}, {-1, 0, 0}},  {{32, 64}, {0, 0, 1}},
                 {{32, 0}, {0, 0, -1}},  {{48, 48}, Normalize(Vec3f(1, 0, 1))}};
    for (const auto &c : cases) {
        const Ray r = scene.camera->GenerateRay(c.pFilm, Vec2f(0.5f, 0.5f));
        EXPECT_LT(Length(r.d - c.d), 1e-5f) << c.pFilm.x << " " << c.pFilm.y;
    }
    // Past an edge the map continues across it, mirrored: just right of the right edge is
    // just below the horizon on the mirrored row.
    const Ray in = scene.camera->GenerateRay(Vec2f(63.9f, 20), Vec2f(0.5f, 0.5f));
    const Ray out = scene.camera->GenerateRay(Vec2f(64.1f, 44), Vec2f(0.5f, 0.5f));
    EXPECT_LT(Length(in.d - out.d), 0.02f);
    EXPECT_TRUE(scene.camera->GetProjection().environment);

    Diagnostics d2(false);
    RenderScene eq = BuildSpherical(
        "eq", "Camera \"spherical\" \"string mapping\" \"equirectangular\"", 64, 32, d2);
    EXPECT_EQ(d2.Warnings().size(), 0u);
    EXPECT_LT(Length(eq.camera->GenerateRay(Vec2f(16, 16), Vec2f(0.5f, 0.5f)).d - Vec3f(0, 0, 1)),
              1e-5f);
}

TEST(SphericalCamera, AnUnknownMappingIsAnErrorAndANonSquareFilmAWarning) {
    Diagnostics diag(false);
    try {
        BuildSpherical("bad", "Camera \"spherical\"\n  \"string mapping\" \"cube\"", 8, 8, diag);
        ADD_FAILURE() << "no error";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("bad.pbrt:2:3:"), std::string::npos) << e.what();
    }
    Diagnostics d2(false);
    BuildSpherical("wide", "Camera \"spherical\"", 16, 8, d2);
    ASSERT_EQ(d2.Warnings().size(), 1u);
    EXPECT_NE(d2.Warnings()[0].message.find("16x8"), std::string::npos);
}

}  // namespace
}  // namespace prism
