// Specular ray differentials with the surface's curvature (render/differentials.h): the
// differentials reflected and refracted by a sphere and an ellipsoid against the neighbour
// rays actually traced, reflected and refracted at their own hits (and far from them without
// the curvature term), and a fine checkerboard seen in a mirror sphere at 1 spp against a
// supersampled reference.
#include "render/differentials.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "assembly/build_scene.h"
#include "geometry/accel.h"
#include "geometry/sphere.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

Vec3f Reflect(const Vec3f &wo, const Vec3f &n) { return -wo + n * (2 * Dot(wo, n)); }

// Refraction of wo (unit, away from the surface) through the outward normal n of an interface
// with inside-over-outside index eta, as BxDFLobes' eta: false for total internal reflection.
bool Refract(const Vec3f &wo, Vec3f n, float eta, Vec3f *wt) {
    float e = 1 / eta;
    if (Dot(wo, n) < 0) {
        e = eta;
        n = -n;
    }
    const float c = Dot(wo, n), s2 = e * e * (1 - c * c);
    if (s2 >= 1) return false;
    *wt = -wo * e + n * (e * c - std::sqrt(1 - s2));
    return true;
}

// What one specular bounce does to a ray and its offset rays.
struct Bounce {
    SurfaceInteraction si;
    Vec3f wi;
    RayDifferential rd;
};

enum class Kind { Reflect, Refract };

// The bounce at the first hit of `ray` (with differentials rd), with or without curvature.
bool BounceAt(const Accel &accel, const Ray &ray, const RayDifferential &rd, Kind kind,
              bool curvature, Bounce *b) {
    if (!accel.Intersect(ray, &b->si)) return false;
    const SurfaceInteraction &si = b->si;
    TextureContext tc{si.uv, si.p, si.uv1};
    ComputeDifferentials(si, rd, &tc);
    NormalDifferentials dn;
    if (curvature) dn = FootprintNormalDifferentials(accel, si, tc, si.ns);
    if (kind == Kind::Reflect) {
        b->wi = Reflect(si.wo, si.ns);
        b->rd = ReflectDifferential(si, tc, rd, si.ns, dn, b->wi);
        return true;
    }
    if (!Refract(si.wo, si.ns, 1.5f, &b->wi)) return false;
    b->rd = RefractDifferential(si, tc, rd, si.ns, dn, b->wi, 1.5f);
    return true;
}

// The neighbour ray through the offset ray's origin and direction, bounced at its own hit.
// *ray becomes the bounced ray.
bool NeighbourBounce(const Accel &accel, Ray *ray, Kind kind, Vec3f *p, Vec3f *wi) {
    SurfaceInteraction si;
    if (!accel.Intersect(*ray, &si)) return false;
    *p = si.p;
    if (kind == Kind::Reflect)
        *wi = Reflect(si.wo, si.ns);
    else if (!Refract(si.wo, si.ns, 1.5f, wi))
        return false;
    *ray = si.SpawnRay(*wi);
    return true;
}

// Relative errors of the bounced x and y differentials (directions and the footprint's points)
// against the bounced neighbour rays, after `bounces` specular bounces (refraction: into the
// solid and out again).
struct Errors {
    double direction = 0, origin = 0;
};
Errors CompareWithNeighbours(const Accel &accel, const Camera &cam, Vec2f pFilm, Kind kind,
                             bool curvature, int bounces) {
    const Vec2f lens(0.5f, 0.5f);
    // A twentieth of a pixel: small enough that the neighbour rays' second-order terms stay
    // well below the first-order ones the differentials stand for.
    const float scale = 0.05f;
    Ray ray = cam.GenerateRay(pFilm, lens);
    RayDifferential rd = cam.GenerateDifferential(ray, pFilm, lens, 0, scale);
    Ray rx{rd.rxOrigin, rd.rxDirection, Infinity}, ry{rd.ryOrigin, rd.ryDirection, Infinity};
    Errors e;
    for (int k = 0; k < bounces; ++k) {
        Bounce b;
        EXPECT_TRUE(BounceAt(accel, ray, rd, kind, curvature, &b)) << k;
        Vec3f px, wx, py, wy;
        EXPECT_TRUE(NeighbourBounce(accel, &rx, kind, &px, &wx)) << k;
        EXPECT_TRUE(NeighbourBounce(accel, &ry, kind, &py, &wy)) << k;
        // The footprint's points lie in the tangent plane, the neighbours' hits on the
        // surface: apart by second-order terms. Directions relative to the change of the
        // direction, or (where a lens nearly focuses the neighbours, so that the change is
        // small) to the incoming one's.
        auto rel = [](const Vec3f &got, const Vec3f &want, const Vec3f &base, float floor = 0) {
            return double(Length(got - want)) / (double(Length(want - base)) + floor);
        };
        const float inX = Length(rd.rxDirection - ray.d / Length(ray.d)),
                    inY = Length(rd.ryDirection - ray.d / Length(ray.d));
        e.origin =
            std::max({e.origin, rel(b.rd.rxOrigin, px, b.si.p), rel(b.rd.ryOrigin, py, b.si.p)});
        e.direction = std::max({e.direction, rel(b.rd.rxDirection, wx, b.wi, 0.2f * inX),
                                rel(b.rd.ryDirection, wy, b.wi, 0.2f * inY)});
        // On to the next bounce (the neighbours continue from their own hits).
        ray = b.si.SpawnRay(b.wi);
        rd = b.rd;
    }
    return e;
}

Camera TestCamera() {
    CameraParams p;
    p.fovDeg = 30;
    // From (0, 0.3, -4) toward the origin.
    const Transform cameraToWorld = Translate(Vec3d(0, 0.3, -4)) * RotateX(4.29);
    return Camera(p, cameraToWorld, Vec2i(64, 48), 64.0 / 48);
}

TEST(CurvedDifferentials, MatchTheNeighbourRaysOffSpheresAndEllipsoids) {
    const Camera cam = TestCamera();
    const Transform shapes[] = {Scale(0.8, 0.8, 0.8),
                                Rotate(30, Vec3d(1, 2, 0)) * Scale(1.2, 0.6, 0.9)};
    for (const Transform &xf : shapes) {
        Accel accel;
        accel.AddAnalytic(std::make_unique<Sphere>(xf, false, 1, -1, 1, 360));
        accel.Commit();
        for (Vec2f pFilm : {Vec2f(32.5f, 24.5f), Vec2f(22.3f, 18.6f), Vec2f(40.2f, 30.1f)}) {
            // Reflection off the outside.
            const Errors r = CompareWithNeighbours(accel, cam, pFilm, Kind::Reflect, true, 1);
            const Errors rFlat = CompareWithNeighbours(accel, cam, pFilm, Kind::Reflect, false, 1);
            EXPECT_LT(r.direction, 0.03) << pFilm.x << " " << pFilm.y;
            EXPECT_LT(r.origin, 0.03);
            // Without the curvature term the reflected rays diverge far too little.
            EXPECT_GT(rFlat.direction, 0.5) << pFilm.x << " " << pFilm.y;
            // Refraction into the solid and out of it again (the second with wo inside, the
            // normal turned around).
            const Errors t = CompareWithNeighbours(accel, cam, pFilm, Kind::Refract, true, 2);
            const Errors tFlat = CompareWithNeighbours(accel, cam, pFilm, Kind::Refract, false, 2);
            EXPECT_LT(t.direction, 0.03) << pFilm.x << " " << pFilm.y;
            EXPECT_LT(t.origin, 0.03);
            EXPECT_GT(tFlat.direction, 0.3) << pFilm.x << " " << pFilm.y;
            std::printf(
                "film (%.1f, %.1f): reflect %.4f (flat %.3f), refract twice %.4f (flat "
                "%.3f)\n",
                pFilm.x, pFilm.y, r.direction, rFlat.direction, t.direction, tFlat.direction);
        }
    }
}

// A mirror sphere in front of the camera, inside a large matte sphere with a fine
// checkerboard: the camera's pixels see the checks through the mirror, whose curvature
// spreads each pixel's rays over several checks.
std::string MirrorSphereScene() {
    return "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 20 ]\n"
           "Film \"image\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 36 ]\n"
           "Sampler \"stratified\" \"integer xsamples\" [ 1 ] \"integer ysamples\" [ 1 ]\n"
           "PixelFilter \"box\"\nIntegrator \"whitted\" \"integer maxdepth\" [ 5 ]\n"
           "WorldBegin\n"
           "LightSource \"point\" \"point3 from\" [ 0 0 -4 ] \"rgb I\" [ 1000 1000 1000 ]\n"
           "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" [ 300 ]\n"
           "  \"float vscale\" [ 150 ] \"rgb tex1\" [ 0 0 0 ] \"rgb tex2\" [ 1 1 1 ]\n"
           "AttributeBegin\n  Rotate 90 1 0 0\n  Material \"matte\" \"texture Kd\" \"checks\"\n"
           "  Shape \"sphere\" \"float radius\" [ 20 ]\nAttributeEnd\n"
           "Material \"mirror\"\nShape \"sphere\" \"float radius\" [ 1 ]\nWorldEnd\n";
}

Image RenderMirror(int spp, const std::string &textureFilter) {
    const std::string path =
        test::WriteTestFile(test::ScratchDir("curvature") / "mirror.pbrt", MirrorSphereScene());
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(path, diag);
    BuildSettings s;
    s.spp = spp;
    s.textureFilter = textureFilter;
    RenderScene scene = BuildRenderScene(desc, s, diag);
    return Render(scene, nullptr);
}

// Mean |a - b| over the image's central 24 x 24 pixels (all inside the mirror's disc, which is
// about 27 pixels in radius).
double CentreMeanAbs(const Image &a, const Image &b) {
    double s = 0;
    int n = 0;
    for (int y = 6; y < 30; ++y)
        for (int x = 12; x < 36; ++x)
            for (int c = 0; c < 3; ++c, ++n) s += std::abs(double(a.At(x, y, c) - b.At(x, y, c)));
    return s / n;
}

TEST(CurvedDifferentials, CheckerboardInAMirrorSphereIsFiltered) {
    // The reference: point-sampled checks, 1024 samples per pixel (the pixel's box average).
    const Image ref = RenderMirror(1024, "none");
    const Image unfiltered = RenderMirror(1, "none");
    const Image filtered = RenderMirror(1, "");
    const double eU = CentreMeanAbs(unfiltered, ref), eF = CentreMeanAbs(filtered, ref);
    double mean = 0;
    for (int y = 6; y < 30; ++y)
        for (int x = 12; x < 36; ++x) mean += ref.At(x, y, 0) / (24.0 * 24.0);
    std::printf(
        "mirror sphere, mean |1 spp - 1024 spp| (reference mean %.3f): unfiltered %.4f, "
        "filtered %.4f\n",
        mean, eU, eF);
    RecordProperty("mean_abs_unfiltered", std::to_string(eU));
    RecordProperty("mean_abs_filtered", std::to_string(eF));
    ASSERT_GT(mean, 0.1);
    // The footprint the curvature gives covers the pixel's spread of checks. Without the term
    // (a flat mirror's footprint, under half a check) the filtered render is hardly better
    // than the unfiltered one.
    EXPECT_LT(eF, 0.3 * eU);
}

}  // namespace
}  // namespace prism
