// Cut-outs (geometry/alpha.h) through Embree: a checkerboard alpha on a mesh (filter functions)
// and on an analytic disk and sphere (user-geometry callbacks) lets exactly the cut-out half of
// the camera rays and of the shadow rays through, single and in packets.
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <cmath>

#include "geometry/accel.h"
#include "geometry/disk.h"
#include "geometry/sphere.h"

namespace prism {
namespace {

// 1 on the "white" squares of a 4 x 4 checkerboard over [0, 1]^2 in uv, 0 on the others.
std::shared_ptr<AlphaTest> Checker() {
    auto a = std::make_shared<AlphaTest>();
    a->alpha = [](const Vec2f &uv, const Vec3f &) {
        int i = int(std::floor(uv.x * 4)), j = int(std::floor(uv.y * 4));
        return ((i + j) & 1) ? 1.f : 0.f;
    };
    return a;
}

std::unique_ptr<TriangleMesh> Quad() {
    std::vector<Vec3f> P = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<Vec2f> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return std::make_unique<TriangleMesh>(
        Transform(), false, P, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, std::vector<Vec3f>{}, uv);
}

struct Counts {
    int camera = 0, shadow = 0, packetCamera = 0, packetShadow = 0, total = 0;
};

// A 32 x 32 grid of rays straight down through [x0, x0 + size]^2 (cell centres, never on a
// checker boundary), from z = 2.
Counts Shoot(const Accel &accel, float x0, float size) {
    Counts c;
    const int n = 32;
    std::vector<Ray> rays;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Vec3f o(x0 + size * (float(i) + 0.5f) / n, x0 + size * (float(j) + 0.5f) / n, 2);
            rays.push_back({o, Vec3f(0, 0, -1), Infinity, 0, 0});
        }
    for (const Ray &r : rays) {
        RawHit h;
        c.camera += accel.IntersectRaw(r, &h);
        c.shadow += accel.Occluded(r);
    }
    for (size_t k = 0; k < rays.size(); k += 16) {
        RawHit hits[16];
        bool occ[16];
        accel.IntersectPacket(&rays[k], 16, hits, occ);
        for (int i = 0; i < 16; ++i) {
            c.packetCamera += hits[i].shape >= 0;
            c.packetShadow += occ[i];
        }
    }
    c.total = int(rays.size());
    return c;
}

TEST(Alpha, CheckerboardMeshLetsHalfTheCameraAndShadowRaysThrough) {
    Accel accel;
    accel.AddMesh(Quad(), AllRays, ShapeAlpha{Checker(), Checker()});
    accel.Commit();
    Counts c = Shoot(accel, 0, 1);
    EXPECT_EQ(c.camera, c.total / 2);
    EXPECT_EQ(c.shadow, c.total / 2);
    EXPECT_EQ(c.packetCamera, c.total / 2);
    EXPECT_EQ(c.packetShadow, c.total / 2);
}

TEST(Alpha, ZeroIsCutOutWithDenormalsFlushedToZero) {
    // Embree's render threads run with FTZ/DAZ: pbrt's "cut out where alpha is 0" must not
    // rest on a denormal threshold, which reads as 0 there.
    const unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040);  // FTZ | DAZ
    AlphaTest a;
    a.alpha = [](const Vec2f &uv, const Vec3f &) { return uv.x; };
    const bool zeroKept = a.Keeps(Vec2f(0, 0), {}, {}, {}, 0);
    const bool smallKept = a.Keeps(Vec2f(1e-3f, 0), {}, {}, {}, 0);
    _mm_setcsr(csr);
    EXPECT_FALSE(zeroKept);
    EXPECT_TRUE(smallKept);
}

TEST(Alpha, CameraAndShadowTestsAreSeparate) {
    // Cut out for camera rays only: every shadow ray is blocked, half the camera rays pass.
    Accel accel;
    accel.AddMesh(Quad(), AllRays, ShapeAlpha{Checker(), nullptr});
    accel.Commit();
    Counts c = Shoot(accel, 0, 1);
    EXPECT_EQ(c.camera, c.total / 2);
    EXPECT_EQ(c.shadow, c.total);
    EXPECT_EQ(c.packetShadow, c.total);
}

TEST(Alpha, OpaqueBehindACutOutIsFound) {
    // A cut-out quad above an opaque one: every ray hits something, and the camera rays
    // through the holes find the lower quad.
    Accel accel;
    int top = accel.AddMesh(Quad(), AllRays, ShapeAlpha{Checker(), Checker()});
    std::vector<Vec3f> P = {{0, 0, -1}, {1, 0, -1}, {1, 1, -1}, {0, 1, -1}};
    accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P,
                                                 std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    accel.Commit();
    int onTop = 0;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            RawHit h;
            Ray r{Vec3f((i + 0.5f) / 16, (j + 0.5f) / 16, 2), Vec3f(0, 0, -1), Infinity, 0, 0};
            ASSERT_TRUE(accel.IntersectRaw(r, &h));
            onTop += h.shape == top;
        }
    EXPECT_EQ(onTop, 128);
}

TEST(Alpha, CheckerboardOnADiskThroughTheUserGeometryCallbacks) {
    // The disk's u is phi / 2 pi: a checkerboard in 4 x 4 uv cells over a disk of radius 1
    // (v = 1 - r) keeps alternate quarter sectors in each ring, so a grid symmetric under
    // quarter turns about the centre sees exactly half of the disk's hits cut out.
    Accel plain, cut;
    plain.AddAnalytic(std::make_unique<Disk>(Transform(), false, 0, 1, 0, 360));
    cut.AddAnalytic(std::make_unique<Disk>(Transform(), false, 0, 1, 0, 360), AllRays,
                    ShapeAlpha{Checker(), Checker()});
    plain.Commit();
    cut.Commit();
    Counts all = Shoot(plain, -1, 2), c = Shoot(cut, -1, 2);
    ASSERT_GT(all.camera, 400);
    EXPECT_EQ(c.camera * 2, all.camera);
    EXPECT_EQ(c.shadow * 2, all.shadow);
    EXPECT_EQ(c.packetCamera * 2, all.packetCamera);
    EXPECT_EQ(c.packetShadow * 2, all.packetShadow);
}

TEST(Alpha, ACutOutSphereShowsItsFarSide) {
    // A sphere cut out where pbrt's v (1 at z = r, 0 at z = -r) exceeds 1/2: the near (upper)
    // half is gone for a ray from above, which hits the far half at z = -sqrt(1 - x^2 - y^2).
    auto upperCut = std::make_shared<AlphaTest>();
    upperCut->alpha = [](const Vec2f &uv, const Vec3f &) { return uv.y > 0.5f ? 0.f : 1.f; };
    Accel accel;
    accel.AddAnalytic(std::make_unique<Sphere>(Transform(), false, 1, -1, 1, 360), AllRays,
                      ShapeAlpha{upperCut, upperCut});
    accel.Commit();
    for (float x : {0.f, 0.3f, -0.6f}) {
        Ray r{Vec3f(x, 0.1f, 3), Vec3f(0, 0, -1), Infinity, 0, 0};
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(r, &si));
        EXPECT_NEAR(si.p.z, -std::sqrt(1 - x * x - 0.01f), 1e-4) << x;
        EXPECT_TRUE(accel.Occluded(r));
    }
}

TEST(Alpha, StochasticAlphaIsDeterministicAndProportional) {
    auto half = std::make_shared<AlphaTest>();
    half->alpha = [](const Vec2f &, const Vec3f &) { return 0.5f; };
    half->stochastic = true;
    Accel accel;
    accel.AddMesh(Quad(), AllRays, ShapeAlpha{half, half});
    accel.Commit();
    Counts a = Shoot(accel, 0, 1), b = Shoot(accel, 0, 1);
    EXPECT_EQ(a.camera, b.camera);
    EXPECT_EQ(a.camera, a.packetCamera);
    EXPECT_NEAR(double(a.camera) / a.total, 0.5, 0.05);
    EXPECT_NEAR(double(a.shadow) / a.total, 0.5, 0.05);
}

}  // namespace
}  // namespace prism
