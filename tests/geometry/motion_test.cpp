// Moving geometry in Accel (motion blur): an analytic sphere, a mesh and an instance moving
// along x are hit where they are at the ray's time, by single rays, packets and shadow rays;
// the interaction (point, normal) is at that time and spawned rays inherit it.
#include <gtest/gtest.h>

#include "core/animated_transform.h"
#include "geometry/accel.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace prism {
namespace {

// Something of radius 1 moving from x = 0 (time 0) to x = 4 (time 1), its front at z =
// zFront: a ray along +z at x = 4 t hits it at time t, and misses it half a shutter away.
void ExpectFollowsMotion(const Accel &accel, float zFront) {
    for (float t : {0.f, 0.25f, 0.5f, 0.9f, 1.f}) {
        Ray r{{4 * t, 0, -5}, {0, 0, 1}, Infinity, 0, t};
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(r, &si)) << t;
        EXPECT_NEAR(si.t, 5 + zFront, 1e-4f) << t;
        EXPECT_NEAR(si.p.x, 4 * t, 1e-4f) << t;
        EXPECT_NEAR(si.n.z, -1, 1e-3f) << t;
        EXPECT_EQ(si.time, t);
        EXPECT_EQ(si.SpawnRay(Vec3f(0, 0, -1)).time, t);
        EXPECT_TRUE(accel.Occluded(r));
        // Two units away the object is not there at this time (but is at another).
        Ray away = r;
        away.time = t < 0.5f ? t + 0.5f : t - 0.5f;
        EXPECT_FALSE(accel.Intersect(away, &si)) << t;
        EXPECT_FALSE(accel.Occluded(away)) << t;
    }
    // The packet path carries each ray's time.
    Ray rays[16];
    for (int i = 0; i < 16; ++i) {
        float t = float(i) / 15;
        rays[i] = Ray{{4 * t, 0, -5}, {0, 0, 1}, Infinity, 0, i % 2 ? t : 1 - t};
    }
    RawHit hits[16];
    bool occluded[16];
    accel.IntersectPacket(rays, 16, hits, occluded);
    for (int i = 0; i < 16; ++i) {
        float t = float(i) / 15;
        bool there = (i % 2) || std::abs(4 * t - 4 * (1 - t)) < 1;
        EXPECT_EQ(hits[i].shape >= 0, there) << i;
        EXPECT_EQ(occluded[i], there) << i;
    }
}

const AnimatedTransform Motion(Transform(), 0, Translate({4, 0, 0}), 1);

TEST(Motion, AnalyticShapeFollowsTheRayTime) {
    Accel accel;
    auto s = std::make_unique<Sphere>(Transform(), false, 1, -1, 1, 360);
    s->SetMotion(Motion);
    EXPECT_EQ(s->MotionTimeSteps(), 2);
    accel.AddAnalytic(std::move(s));
    accel.Commit();
    ExpectFollowsMotion(accel, -1);
}

TEST(Motion, RotatingAnalyticShapeHasConservativeStepBounds) {
    // A sphere at x = 3 turning 170 degrees about z (with pbrt-v3's decomposition its centre
    // moves along the chord while it turns about itself, its box's corners sweeping arcs):
    // the per-step bounds must let Embree find it all along.
    Accel accel;
    AnimatedTransform turn(Translate({3, 0, 0}), 0, RotateZ(170) * Translate({3, 0, 0}), 1);
    auto s = std::make_unique<Sphere>(Translate({3, 0, 0}), false, 0.5, -0.5, 0.5, 360);
    s->SetMotion(turn);
    EXPECT_EQ(s->MotionTimeSteps(), 58);
    accel.AddAnalytic(std::move(s));
    accel.Commit();
    for (int k = 0; k <= 100; ++k) {
        float t = k / 100.f;
        const double a = Radians(170.0);
        Vec3d c = Vec3d(3, 0, 0) * (1 - t) + Vec3d(3 * std::cos(a), 3 * std::sin(a), 0) * t;
        Ray r{{float(c.x), float(c.y), -5}, {0, 0, 1}, Infinity, 0, t};
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(r, &si)) << t;
        EXPECT_NEAR(si.t, 4.5f, 1e-3f) << t;
    }
}

TEST(Motion, MeshFollowsTheRayTime) {
    Accel accel;
    std::vector<Vec3f> P = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
    auto m = std::make_unique<TriangleMesh>(Transform(), false, P,
                                            std::vector<uint32_t>{0, 2, 1, 0, 3, 2});
    m->SetMotionSteps({Translate({4, 0, 0})});
    EXPECT_EQ(m->NumTimeSteps(), 2);
    accel.AddMesh(std::move(m));
    accel.Commit();
    ExpectFollowsMotion(accel, -1);
}

TEST(Motion, InstanceFollowsTheRayTime) {
    auto proto = std::make_shared<Accel>();
    proto->AddAnalytic(std::make_unique<Sphere>(Transform(), false, 1, -1, 1, 360));
    proto->Commit();
    Accel accel;
    accel.AddInstance(proto, Motion);
    accel.Commit();
    ExpectFollowsMotion(accel, -1);
}

}  // namespace
}  // namespace prism
