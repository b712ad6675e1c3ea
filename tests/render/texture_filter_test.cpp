// Texture filtering (docs/MATERIALS.md): camera ray differentials against finite differences of
// GenerateRay, reflection differentials off a flat mirror against the mirrored camera, the
// closed-form checkerboard against a numerical box average, image lookups at one texel per
// pixel (unchanged by filtering), and a plane at grazing angles at 1 spp against a
// supersampled reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "assembly/build_scene.h"
#include "image/image_io.h"
#include "render/camera.h"
#include "render/differentials.h"
#include "render/mipmap.h"
#include "render/renderer.h"
#include "render/texture.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

double Dist(const Vec3f &a, const Vec3f &b) { return double(Length(a - b)); }

Transform LookAtTransform() {
    // Camera at (0, 2, -4) looking at the origin, y up (the inverse of pbrt's LookAt).
    return Translate(Vec3d(0, 2, -4)) * RotateX(26.565);
}

TEST(RayDifferentials, CameraMatchesFiniteDifferences) {
    for (int kind = 0; kind < 3; ++kind) {
        CameraParams p;
        p.fovDeg = 50;
        p.orthographic = kind == 1;
        if (kind == 2) {
            p.lensRadius = 0.2;
            p.focalDistance = 3;
        }
        const Vec2i res(64, 48);
        Camera cam(p, LookAtTransform(), res, 64.0 / 48);
        for (Vec2f pFilm : {Vec2f(10.3f, 5.5f), Vec2f(32, 24), Vec2f(60.1f, 44.9f)}) {
            const Vec2f uLens(0.3f, 0.8f);
            const Ray r = cam.GenerateRay(pFilm, uLens);
            for (float scale : {1.f, 0.25f}) {
                const RayDifferential rd = cam.GenerateDifferential(r, pFilm, uLens, 0, scale);
                // Central differences of GenerateRay, a hundredth of a pixel wide, times the
                // step the differential stands for (scale pixels).
                const float h = 0.01f;
                for (int axis = 0; axis < 2; ++axis) {
                    Vec2f e = axis == 0 ? Vec2f(h, 0) : Vec2f(0, h);
                    Ray a = cam.GenerateRay(pFilm + e, uLens),
                        b = cam.GenerateRay(pFilm - e, uLens);
                    Vec3f dO = (a.o - b.o) * (scale / (2 * h)),
                          dD = (a.d - b.d) * (scale / (2 * h));
                    const Vec3f &o = axis == 0 ? rd.rxOrigin : rd.ryOrigin;
                    const Vec3f &d = axis == 0 ? rd.rxDirection : rd.ryDirection;
                    EXPECT_LT(Dist(o - r.o, dO), 2e-4 * scale) << kind << " axis " << axis;
                    // A pixel is a small step: the linearization holds to ~1e-4 of it.
                    EXPECT_LT(Dist(d - r.d, dD), 3e-4 + 2e-3 * Length(dD))
                        << kind << " axis " << axis;
                    if (kind != 1) EXPECT_GT(Length(dD), 1e-3f);
                }
            }
        }
    }
}

// A hit on the plane y = 0 (normal +y, u along x, v along z) of a ray.
SurfaceInteraction PlaneHit(const Ray &r) {
    EXPECT_LT(r.d.y, 0);
    SurfaceInteraction si;
    const float t = -r.o.y / r.d.y;
    si.p = r.At(t);
    si.n = si.ns = Vec3f(0, 1, 0);
    si.dpdu = Vec3f(1, 0, 0);
    si.dpdv = Vec3f(0, 0, 1);
    si.uv = Vec2f(si.p.x, si.p.z);
    si.wo = -r.d;
    si.t = t;
    return si;
}

TEST(RayDifferentials, PlaneFootprintMatchesNeighbourRays) {
    CameraParams p;
    const Vec2i res(64, 48);
    Camera cam(p, LookAtTransform(), res, 64.0 / 48);
    const Vec2f pFilm(30.5f, 40.5f);
    const Ray r = cam.GenerateRay(pFilm, Vec2f(0.5f, 0.5f));
    const RayDifferential rd = cam.GenerateDifferential(r, pFilm, Vec2f(0.5f, 0.5f), 0, 1);
    const SurfaceInteraction si = PlaneHit(r);
    TextureContext tc{si.uv, si.p};
    ComputeDifferentials(si, rd, &tc);
    // On a plane the footprint is exactly where the neighbouring pixels' rays land.
    const SurfaceInteraction sx = PlaneHit(cam.GenerateRay(pFilm + Vec2f(1, 0), Vec2f(.5f, .5f)));
    const SurfaceInteraction sy = PlaneHit(cam.GenerateRay(pFilm + Vec2f(0, 1), Vec2f(.5f, .5f)));
    EXPECT_LT(Dist(tc.dpdx, sx.p - si.p), 1e-4);
    EXPECT_LT(Dist(tc.dpdy, sy.p - si.p), 1e-4);
    EXPECT_NEAR(tc.dudx, sx.uv.x - si.uv.x, 1e-4);
    EXPECT_NEAR(tc.dvdx, sx.uv.y - si.uv.y, 1e-4);
    EXPECT_NEAR(tc.dudy, sy.uv.x - si.uv.x, 1e-4);
    EXPECT_NEAR(tc.dvdy, sy.uv.y - si.uv.y, 1e-4);
}

Vec3f MirrorY(const Vec3f &v) { return {v.x, -v.y, v.z}; }

TEST(RayDifferentials, FlatMirrorReflectsLikeTheMirroredCamera) {
    CameraParams p;
    const Vec2i res(64, 48);
    Camera cam(p, LookAtTransform(), res, 64.0 / 48);
    for (Vec2f pFilm : {Vec2f(30.5f, 40.5f), Vec2f(5.2f, 30.7f), Vec2f(60.1f, 47.1f)}) {
        const Ray r = cam.GenerateRay(pFilm, Vec2f(0.5f, 0.5f));
        const RayDifferential rd = cam.GenerateDifferential(r, pFilm, Vec2f(0.5f, 0.5f), 0, 1);
        const SurfaceInteraction si = PlaneHit(r);
        TextureContext tc{si.uv, si.p};
        ComputeDifferentials(si, rd, &tc);
        const Vec3f wi = MirrorY(r.d);
        const RayDifferential refl = ReflectDifferential(si, tc, rd, si.ns, {}, wi);
        // The mirrored camera (eye below the plane) sends its offset rays along the mirrored
        // directions through the mirrored origins: the same lines as the reflected ones.
        for (int axis = 0; axis < 2; ++axis) {
            const Vec3f o = MirrorY(axis == 0 ? rd.rxOrigin : rd.ryOrigin);
            const Vec3f d = MirrorY(axis == 0 ? rd.rxDirection : rd.ryDirection);
            const Vec3f &ro = axis == 0 ? refl.rxOrigin : refl.ryOrigin;
            const Vec3f &rdir = axis == 0 ? refl.rxDirection : refl.ryDirection;
            EXPECT_LT(Dist(rdir, d), 1e-5) << axis;
            // ro lies on the mirrored camera's ray.
            const Vec3f v = ro - o;
            EXPECT_LT(double(Length(Cross(v, Normalize(d)))), 1e-4 * (1 + Length(v))) << axis;
        }
    }
}

TEST(RayDifferentials, StraightThroughRefractionKeepsTheRays) {
    CameraParams p;
    Camera cam(p, LookAtTransform(), Vec2i(64, 48), 64.0 / 48);
    const Vec2f pFilm(30.5f, 40.5f);
    const Ray r = cam.GenerateRay(pFilm, Vec2f(0.5f, 0.5f));
    const RayDifferential rd = cam.GenerateDifferential(r, pFilm, Vec2f(0.5f, 0.5f), 0, 1);
    const SurfaceInteraction si = PlaneHit(r);
    TextureContext tc{si.uv, si.p};
    ComputeDifferentials(si, rd, &tc);
    const RayDifferential t = RefractDifferential(si, tc, rd, si.ns, {}, r.d, 1.f);
    EXPECT_LT(Dist(t.rxDirection, rd.rxDirection), 1e-6);
    EXPECT_LT(Dist(t.ryDirection, rd.ryDirection), 1e-6);
    // Into glass the refracted differentials match refracting the neighbouring rays.
    const float eta = 1.5f;
    auto refract = [&](const Vec3f &d) {
        Vec3f wo = -Normalize(d);
        float cosI = wo.y, e = 1 / eta;
        float cosT = std::sqrt(1 - e * e * (1 - cosI * cosI));
        return -wo * e + Vec3f(0, 1, 0) * (e * cosI - cosT);
    };
    const RayDifferential g = RefractDifferential(si, tc, rd, si.ns, {}, refract(r.d), eta);
    EXPECT_LT(Dist(g.rxDirection, refract(rd.rxDirection)), 2e-3 * Dist(rd.rxDirection, r.d));
    EXPECT_LT(Dist(g.ryDirection, refract(rd.ryDirection)), 2e-3 * Dist(rd.ryDirection, r.d));
}

// The fraction of [s - ds, s + ds] x [t - dt, t + dt] on odd squares, by midpoint sums.
double NumericOdd(double s, double t, double ds, double dt) {
    const int n = 1000;
    double odd = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double x = s - ds + 2 * ds * (i + 0.5) / n, y = t - dt + 2 * dt * (j + 0.5) / n;
            odd += (long(std::floor(x)) + long(std::floor(y))) & 1;
        }
    return odd / (double(n) * n);
}

TEST(Checkerboard, ClosedFormIsTheBoxFilteredAverage) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-5, 5), width(0.05f, 3);
    for (int k = 0; k < 40; ++k) {
        float s = pos(rng), t = pos(rng), ds = width(rng), dt = width(rng);
        EXPECT_NEAR(CheckerboardTexture::OddFraction(s, t, ds, dt), NumericOdd(s, t, ds, dt), 4e-3)
            << s << " " << t << " " << ds << " " << dt;
    }
    // Through the texture: tex1 = 0, tex2 = 1 gives the odd fraction of the footprint's box
    // (half a differential to either side).
    auto zero = std::make_shared<ConstantTexture>(RGB(0));
    auto one = std::make_shared<ConstantTexture>(RGB(1));
    CheckerboardTexture aa(TextureMapping{}, zero, one, 2, CheckerboardTexture::AAMode::ClosedForm);
    CheckerboardTexture none(TextureMapping{}, zero, one, 2, CheckerboardTexture::AAMode::None);
    TextureContext tc{{2.3f, -1.6f}, {}};
    tc.dudx = 1.2f;
    tc.dvdx = 0.3f;
    tc.dudy = -0.4f;
    tc.dvdy = 2.5f;
    EXPECT_NEAR(aa.Evaluate(tc).r, NumericOdd(2.3, -1.6, 0.6, 1.25), 4e-3);
    EXPECT_TRUE(aa.UsesDifferentials());
    EXPECT_FALSE(none.UsesDifferentials());
    // Inside one square, or without a footprint, both point-sample.
    for (TextureContext c : {TextureContext{{2.5f, 0.5f}, {}}, TextureContext{{1.5f, 0.5f}, {}}})
        EXPECT_EQ(aa.Evaluate(c), none.Evaluate(c));
    EXPECT_EQ(none.Evaluate(tc), RGB(0));  // floor(2.3) + floor(-1.6) = 0: an even square
}

std::shared_ptr<Image> NoiseImage(int w, int h, uint32_t seed) {
    auto img = std::make_shared<Image>(w, h, 3);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    for (float &v : img->pixels) v = u(rng);
    return img;
}

TEST(MIPMap, LevelsAverageAndLookupsWithoutFootprintAreBilinear) {
    auto img = NoiseImage(8, 4, 1);
    MIPMap mip(img, WrapMode::Repeat);
    ASSERT_EQ(mip.Levels(), 4);  // 8x4, 4x2, 2x1, 1x1
    double mean = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) mean += img->GetRGB(x, y).r;
    EXPECT_NEAR(mip.Texel(3, 0, 0).r, mean / 32, 1e-5);
    // No footprint: exactly the unfiltered texture's bilinear value.
    ImageTexture plain(TextureMapping{}, img, WrapMode::Repeat, 1, false);
    auto m = std::make_shared<MIPMap>(img, WrapMode::Repeat);
    ImageTexture ewa(TextureMapping{}, img, WrapMode::Repeat, 1, false, TextureFilter::EWA, m);
    for (Vec2f uv : {Vec2f(0.13f, 0.77f), Vec2f(0.5f, 0.5f), Vec2f(-0.2f, 1.3f)}) {
        TextureContext c{uv, {}};
        EXPECT_EQ(ewa.Evaluate(c), plain.Evaluate(c));
        EXPECT_EQ(mip.EWA(uv, {}, {}, 8), plain.Evaluate(c));
    }
    // A footprint covering the whole texture reads its mean.
    EXPECT_NEAR(mip.Trilinear(Vec2f(0.3f, 0.6f), 4.f).r, mean / 32, 1e-5);
    EXPECT_NEAR(mip.EWA(Vec2f(0.3f, 0.6f), {4, 0}, {0, 4}, 8).r, mean / 32, 1e-5);
}

// Wrap modes per axis (imagemap "wrap", "wraps", "wrapt"): repeat, clamp, black, and mirror
// (glTF's MIRRORED_REPEAT), in the unfiltered lookup and in every MIP level.
TEST(ImageTexture, WrapModesPerAxis) {
    bool black = false;
    const int mirror[] = {2, 1, 0, 0, 1, 2, 2, 1, 0};  // x = -3 .. 5 of a row of 3
    for (int x = -3; x <= 5; ++x)
        EXPECT_EQ(WrapTexel(x, 3, WrapMode::Mirror, &black), mirror[x + 3]);
    EXPECT_EQ(WrapTexel(-2147483647 - 1, 3, WrapMode::Mirror, &black), 1);  // 2n overflows no int
    EXPECT_EQ(WrapTexel(-1, 3, WrapMode::Repeat, &black), 2);
    EXPECT_EQ(WrapTexel(7, 3, WrapMode::Clamp, &black), 2);
    EXPECT_FALSE(black);
    EXPECT_EQ(WrapTexel(3, 3, WrapMode::Black, &black), 2);
    EXPECT_TRUE(black);

    auto img = NoiseImage(4, 4, 2);
    const TextureWrap wrap(WrapMode::Mirror, WrapMode::Clamp);
    ImageTexture point(TextureMapping{}, img, wrap, 1, false, TextureFilter::Point);
    // s in (1, 2) reads the row mirrored; t above 1 reads the top row.
    for (Vec2f uv : {Vec2f(1.1f, 0.3f), Vec2f(1.6f, 1.7f), Vec2f(-0.4f, -2.f)}) {
        const float s = uv.x < 0 ? -uv.x : uv.x < 1 ? uv.x : 2 - uv.x;
        const float t = std::clamp(uv.y, 0.f, 0x1.fffffep-1f);
        TextureContext mirrored{uv, {}}, inside{Vec2f(s, t), {}};
        EXPECT_EQ(point.Evaluate(mirrored), point.Evaluate(inside)) << uv.x << " " << uv.y;
    }
    MIPMap mip(img, wrap);
    for (int level = 0; level < mip.Levels(); ++level)
        EXPECT_EQ(mip.Texel(level, -1, 9), mip.Texel(level, 0, 9999)) << level;
}

// An orthographic camera looking straight at a 1 x 1 quad textured with `file`, a
// res x res image; filter is the imagemap's "filter".
std::string HeadOnScene(const std::string &file, int res, const std::string &filter) {
    return "LookAt 0.5 0.5 -1  0.5 0.5 0  0 1 0\n"
           "Camera \"orthographic\" \"float screenwindow\" [ -0.5 0.5 -0.5 0.5 ]\n"
           "Film \"image\" \"integer xresolution\" [ " +
           std::to_string(res) + " ] \"integer yresolution\" [ " + std::to_string(res) +
           " ]\nSampler \"stratified\" \"integer xsamples\" [ 1 ] \"integer ysamples\" [ 1 ] "
           "\"bool jitter\" false\nPixelFilter \"box\"\nWorldBegin\n"
           "LightSource \"distant\" \"point3 from\" [ 0 0 -1 ] \"point3 to\" [ 0 0 0 ] "
           "\"rgb L\" [ 3.14159265 3.14159265 3.14159265 ]\n"
           "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" +
           file + "\" \"string filter\" \"" + filter +
           "\"\nMaterial \"matte\" \"texture Kd\" \"t\"\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
           "  \"point3 P\" [ 0 0 0  1 0 0  1 1 0  0 1 0 ]\n"
           "  \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]\nWorldEnd\n";
}

Image RenderText(const std::string &name, const std::string &text, int spp = 0,
                 const std::string &textureFilter = "", const std::string &integrator = "") {
    BuildSettings s;
    s.spp = spp;
    s.textureFilter = textureFilter;
    s.integrator = integrator;
    return RenderSceneText("texfilt", name, text, s).image;
}

double MaxDiff(const Image &a, const Image &b) {
    double m = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        m = std::max(m, double(std::abs(a.pixels[i] - b.pixels[i])));
    return m;
}

TEST(ImageTextureFilter, OneTexelPerPixelHeadOnIsUnchanged) {
    const int res = 32;
    auto img = NoiseImage(res, res, 3);
    std::string file = (ScratchDir("texfilt") / "noise32.exr").string();
    WriteImage(file, *img);
    Image point = RenderText("p.pbrt", HeadOnScene(file, res, "point"));
    Image bilinear = RenderText("b.pbrt", HeadOnScene(file, res, "bilinear"));
    Image trilinear = RenderText("t.pbrt", HeadOnScene(file, res, "trilinear"));
    Image ewa = RenderText("e.pbrt", HeadOnScene(file, res, "ewa"));
    ASSERT_EQ(point.width, res);
    // The quad fills the image; each pixel centre is a texel centre.
    double m = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
            m = std::max(m, double(std::abs(point.At(x, y, 0) - img->At(x, y, 0))));
    EXPECT_LT(m, 1e-3);
    EXPECT_LT(MaxDiff(bilinear, point), 1e-3);
    EXPECT_LT(MaxDiff(trilinear, point), 1e-3);
    EXPECT_LT(MaxDiff(ewa, point), 1e-3);
    // At a quarter of the resolution (4 texels per pixel) filtering does change the image.
    Image small = RenderText("e4.pbrt", HeadOnScene(file, res / 4, "ewa"));
    Image smallPoint = RenderText("p4.pbrt", HeadOnScene(file, res / 4, "point"));
    EXPECT_GT(MaxDiff(small, smallPoint), 0.05);
}

// A plane at a grazing angle under a camera, textured with a fine random image (128 x 128
// texels repeated 8 times over the plane's 40 units).
std::string GrazingScene(const std::string &file, int w, int h) {
    return "LookAt 0 0.6 0  0 0 8  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"image\" \"integer xresolution\" [ " +
           std::to_string(w) + " ] \"integer yresolution\" [ " + std::to_string(h) +
           " ]\nSampler \"stratified\" \"integer xsamples\" [ 1 ] \"integer ysamples\" [ 1 ]\n"
           "PixelFilter \"box\"\nWorldBegin\n"
           "LightSource \"distant\" \"point3 from\" [ 0 1 0 ] \"point3 to\" [ 0 0 0 ] "
           "\"rgb L\" [ 3.14159265 3.14159265 3.14159265 ]\n"
           "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" +
           file +
           "\" \"float uscale\" [ 8 ] \"float vscale\" [ 8 ]\n"
           "Material \"matte\" \"texture Kd\" \"t\"\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
           "  \"point3 P\" [ -20 0 0  20 0 0  20 0 40  -20 0 40 ]\n"
           "  \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]\nWorldEnd\n";
}

double Rmse(const Image &a, const Image &b) {
    double s = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        double d = a.pixels[i] - b.pixels[i];
        s += d * d;
    }
    return std::sqrt(s / double(a.pixels.size()));
}

TEST(ImageTextureFilter, GrazingPlaneAtOneSampleIsCloseToTheSupersampledReference) {
    auto img = NoiseImage(128, 128, 5);
    std::string file = (ScratchDir("texfilt") / "noise128.exr").string();
    WriteImage(file, *img);
    const std::string scene = GrazingScene(file, 48, 24);
    // The reference: unfiltered lookups at 1024 samples per pixel (the pixel's box average).
    Image ref = RenderText("g.pbrt", scene, 1024, "none");
    Image unfiltered = RenderText("g.pbrt", scene, 1, "none");
    Image ewa = RenderText("g.pbrt", scene, 1, "");
    Image trilinear = RenderText("g.pbrt", scene, 1, "trilinear");
    const double eU = Rmse(unfiltered, ref), eE = Rmse(ewa, ref), eT = Rmse(trilinear, ref);
    RecordProperty("rmse_unfiltered", std::to_string(eU));
    RecordProperty("rmse_ewa", std::to_string(eE));
    RecordProperty("rmse_trilinear", std::to_string(eT));
    std::printf("grazing plane RMSE vs 1024 spp: unfiltered %.4f  ewa %.4f  trilinear %.4f\n", eU,
                eE, eT);
    EXPECT_LT(eE, 0.5 * eU);
    EXPECT_LT(eT, 0.6 * eU);
    // The path and directlighting integrators filter the camera rays' first hits too (the
    // plane under a distant light and no sky: the same radiance as Whitted's).
    for (const char *integrator : {"path", "directlighting"}) {
        Image pU = RenderText("g.pbrt", scene, 1, "none", integrator);
        Image pE = RenderText("g.pbrt", scene, 1, "", integrator);
        EXPECT_LT(Rmse(pE, ref), 0.5 * Rmse(pU, ref)) << integrator;
    }
}

}  // namespace
}  // namespace prism
