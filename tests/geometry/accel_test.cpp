#include "geometry/accel.h"

#include <gtest/gtest.h>

#include "core/rng.h"
#include "geometry/sphere.h"

namespace prism {
namespace {

TEST(Accel, MeshAndSphereClosestHit) {
    Accel accel;
    // A unit quad at z = 5 and a sphere of radius 1 at z = 2.
    std::vector<Vec3f> P = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
    int mesh = accel.AddMesh(std::make_unique<TriangleMesh>(Transform(), false, P,
                                                            std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    int sphere = accel.AddAnalytic(
        std::make_unique<Sphere>(Translate(Vec3d(0, 0, 2)), false, 1, -1, 1, 360));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0, 0, 0}, {0, 0, 1}, Infinity}, &si));
    EXPECT_EQ(si.shape, sphere);
    EXPECT_NEAR(si.t, 1.0f, 1e-6f);
    EXPECT_NEAR(si.n.z, -1.f, 1e-6f);
    ASSERT_TRUE(accel.Intersect(Ray{{0.9f, 0.9f, 0}, {0, 0, 1}, Infinity}, &si));
    EXPECT_EQ(si.shape, mesh);
    EXPECT_NEAR(si.t, 5.0f, 1e-6f);
    // Triangle geometric normal: (p1-p0) x (p2-p0) = +z for this winding.
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);
    EXPECT_FALSE(accel.Intersect(Ray{{5, 5, 0}, {0, 0, 1}, Infinity}, &si));
    // tMax limits the query.
    EXPECT_FALSE(accel.Occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0.5f}));
    EXPECT_TRUE(accel.Occluded(Ray{{0, 0, 0}, {0, 0, 1}, 1.5f}));
}

TEST(Accel, IntersectAndOccludedAgree) {
    for (Precision prec : {Precision::Double, Precision::Float}) {
        AccelOptions opts;
        opts.precision = prec;
        Accel accel(opts);
        PCG32 rng(21);
        for (int i = 0; i < 20; ++i) {
            Vec3d c(10 * rng.UniformDouble(), 10 * rng.UniformDouble(), 10 * rng.UniformDouble());
            accel.AddAnalytic(std::make_unique<Sphere>(Translate(c), rng.Uniform() < 0.5f,
                                                       0.2 + rng.UniformDouble(), -0.5, 1, 300));
        }
        accel.Commit();
        for (int i = 0; i < 20000; ++i) {
            Vec3f o(float(20 * rng.UniformDouble() - 5), float(20 * rng.UniformDouble() - 5), -10);
            Vec3f d = Normalize(Vec3f(float(rng.UniformDouble() - 0.5), float(rng.UniformDouble() - 0.5), 1));
            float tMax = float(40 * rng.UniformDouble());
            SurfaceInteraction si;
            bool hit = accel.Intersect(Ray{o, d, tMax}, &si);
            EXPECT_EQ(hit, accel.Occluded(Ray{o, d, tMax})) << i;
            if (hit) {
                EXPECT_LT(si.t, tMax);
            }
        }
    }
}

TEST(Accel, ReverseOrientationFlipsNormals) {
    Accel accel;
    accel.AddAnalytic(std::make_unique<Sphere>(Transform(), true, 1, -1, 1, 360));
    accel.AddAnalytic(std::make_unique<Sphere>(Translate(Vec3d(5, 0, 0)) * Scale(-1, 1, 1), false, 1, -1, 1, 360));
    accel.Commit();
    SurfaceInteraction si;
    ASSERT_TRUE(accel.Intersect(Ray{{0, 0, -5}, {0, 0, 1}, Infinity}, &si));
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);  // flipped: points inward
    ASSERT_TRUE(accel.Intersect(Ray{{5, 0, -5}, {0, 0, 1}, Infinity}, &si));
    EXPECT_NEAR(si.n.z, 1.f, 1e-6f);  // handedness swap flips too
}

}  // namespace
}  // namespace prism
