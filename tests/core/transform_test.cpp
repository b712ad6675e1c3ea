#include "core/transform.h"

#include <gtest/gtest.h>

namespace prism {

TEST(Transform, InverseRoundTrip) {
    Transform t = Translate({1, 2, 3}) * Rotate(33, {1, 1, 0}) * Scale(2, -3, 0.5);
    Vec3d p(0.3, -7, 11);
    Vec3d q = t.Inverse().Point(t.Point(p));
    EXPECT_NEAR(q.x, p.x, 1e-12);
    EXPECT_NEAR(q.y, p.y, 1e-12);
    EXPECT_NEAR(q.z, p.z, 1e-12);
    EXPECT_TRUE(t.SwapsHandedness());
}

TEST(Transform, NormalsStayPerpendicular) {
    Transform t = Scale(1, 4, 1) * RotateZ(30);
    Vec3d v(1, 1, 0), n(-1, 1, 0);  // n ⟂ v
    EXPECT_NEAR(Dot(t.Vector(v), t.Normal(n)), 0.0, 1e-12);
}

TEST(Transform, PbrtMatrixIsColumnMajor) {
    double v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    Vec3d p = FromPbrtMatrix(v).Point(Vec3d(0, 0, 0));
    EXPECT_EQ(p, Vec3d(5, 6, 7));
}

TEST(Transform, LookAtMatchesPbrtConvention) {
    // Camera at origin looking down +z with +y up: camera space equals world space.
    Transform camFromWorld = LookAt({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    EXPECT_TRUE(camFromWorld.IsIdentity());
    // Looking down -z: world +x maps to camera -x (left-handed camera frame).
    Transform t = LookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    EXPECT_NEAR(t.Point(Vec3d(1, 0, 0)).x, -1.0, 1e-12);
    EXPECT_THROW(LookAt({0, 0, 0}, {0, 1, 0}, {0, 1, 0}), std::invalid_argument);
}

TEST(Transform, SingularMatrixThrows) { EXPECT_THROW(Scale(1, 0, 1), std::invalid_argument); }

}  // namespace prism
