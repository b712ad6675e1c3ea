// AnimatedTransform: decomposition, interpolation (translation, slerp, scale), clamping,
// bounds over time and the Embree time steps chosen for a motion.
#include "core/animated_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace prism {
namespace {

double MaxDiff(const Matrix4 &a, const Matrix4 &b) {
    double d = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) d = std::max(d, std::abs(a.m[i][j] - b.m[i][j]));
    return d;
}

TEST(AnimatedTransform, DecomposeRebuildsTheMatrix) {
    for (const Transform &m :
         {Translate({1, -2, 3}) * Rotate(37, {1, 2, 3}) * Scale(2, 3, 0.5),
          Rotate(170, {0, 1, 0}) * Scale(-1, 1, 1),  // a reflection
          Translate({5, 0, 0}), Rotate(90, {0, 0, 1}) * Scale(1, 1, 4) * Rotate(30, {1, 0, 0})}) {
        Vec3d T;
        Quaternion R;
        Matrix4 S;
        ASSERT_TRUE(Decompose(m.Matrix(), &T, &R, &S));
        EXPECT_NEAR(Dot(R, R), 1.0, 1e-12);
        Matrix4 back = QuaternionToMatrix(R) * S;
        for (int i = 0; i < 3; ++i) back.m[i][3] = T[i];
        EXPECT_LT(MaxDiff(back, m.Matrix()), 1e-12) << m.ToString();
        EXPECT_GT(QuaternionToMatrix(R).Determinant3x3(), 0);  // a proper rotation
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(S.m[i][j], S.m[j][i], 1e-12);  // symmetric
    }
}

TEST(AnimatedTransform, QuaternionRoundTrip) {
    for (double deg : {0.0, 10.0, 90.0, 179.0, 180.0})
        for (Vec3d axis : {Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, 0, 1), Vec3d(1, -2, 0.5)}) {
            Matrix4 r = Rotate(deg, axis).Matrix();
            EXPECT_LT(MaxDiff(QuaternionToMatrix(QuaternionFromMatrix(r)), r), 1e-12)
                << deg << " " << ToString(axis);
        }
}

TEST(AnimatedTransform, EndpointsAreExactAndTimesClamp) {
    Transform a = Translate({1, 2, 3}) * RotateX(20), b = Translate({-4, 0, 1}) * RotateY(70);
    AnimatedTransform m(a, 2, b, 5);
    EXPECT_TRUE(m.IsAnimated());
    EXPECT_EQ(m.Interpolate(2).Matrix(), a.Matrix());
    EXPECT_EQ(m.Interpolate(-10).Matrix(), a.Matrix());
    EXPECT_EQ(m.Interpolate(5).Matrix(), b.Matrix());
    EXPECT_EQ(m.Interpolate(99).Matrix(), b.Matrix());
    EXPECT_FALSE(m.MovesDuring(-3, 2));
    EXPECT_FALSE(m.MovesDuring(5, 8));
    EXPECT_TRUE(m.MovesDuring(4, 8));
    AnimatedTransform still(a, 0, a, 1);
    EXPECT_FALSE(still.IsAnimated());
    EXPECT_EQ(still.Interpolate(0.5).Matrix(), a.Matrix());
}

TEST(AnimatedTransform, InterpolatesTranslationRotationAndScale) {
    AnimatedTransform t(Translate({0, 0, 0}), 0, Translate({2, 4, -6}), 1);
    EXPECT_LT(Length(t.Interpolate(0.25).Point(Vec3d(0, 0, 0)) - Vec3d(0.5, 1, -1.5)), 1e-12);
    EXPECT_FALSE(t.HasRotation());
    // Slerp: constant angular speed about the fixed axis.
    AnimatedTransform r(RotateZ(0), 0, RotateZ(90), 1);
    EXPECT_NEAR(Degrees(r.RotationAngle()), 90, 1e-9);
    for (double f : {0.1, 0.5, 0.8})
        EXPECT_LT(MaxDiff(r.Interpolate(f).Matrix(), RotateZ(90 * f).Matrix()), 1e-12) << f;
    // The shorter arc: 350 degrees about z is -10.
    AnimatedTransform s(RotateZ(0), 0, RotateZ(350), 1);
    EXPECT_LT(MaxDiff(s.Interpolate(0.5).Matrix(), RotateZ(-5).Matrix()), 1e-12);
    // Scale interpolates linearly, under the rotation.
    AnimatedTransform k(Scale(1, 1, 1), 0, RotateY(60) * Scale(3, 1, 2), 1);
    EXPECT_LT(MaxDiff(k.Interpolate(0.5).Matrix(), (RotateY(30) * Scale(2, 1, 1.5)).Matrix()),
              1e-12);
    // Times other than 0..1.
    AnimatedTransform late(Translate({0, 0, 0}), 10, Translate({10, 0, 0}), 20);
    EXPECT_NEAR(late.Interpolate(13).Point(Vec3d(0, 0, 0)).x, 3, 1e-12);
    // Remapped to a shutter [12, 16]: 0 is time 12, 1 is time 16.
    AnimatedTransform sh = late.Remapped(12, 16);
    EXPECT_NEAR(sh.Interpolate(0).Point(Vec3d(0, 0, 0)).x, 2, 1e-12);
    EXPECT_NEAR(sh.Interpolate(1).Point(Vec3d(0, 0, 0)).x, 6, 1e-12);
}

// The inverse built from the parts (S^-1 R^T T^-1, what moving analytic shapes use for every
// ray) is the inverse of the interpolated matrix, for motions that translate, rotate, stretch
// and shear, with the rotation or the stretch held fixed or not.
TEST(AnimatedTransform, InverseFromThePartsInvertsTheMatrix) {
    Matrix4 shear = Matrix4::Identity();
    shear.m[0][1] = 0.4;
    shear.m[2][0] = -0.3;
    const AnimatedTransform motions[] = {
        {Translate({1, 2, 3}), 0, Translate({-4, 0, 2}), 1},
        {Translate({1, 2, 3}) * Scale(2, 0.5, 3), 0, Translate({-4, 0, 2}) * Scale(2, 0.5, 3), 1},
        {RotateZ(10) * Scale(1, 2, 3), 0, Translate({3, 1, 0}) * RotateX(120) * Scale(1, 2, 3), 1},
        {Translate({0, 1, 0}) * RotateY(20), 0, Translate({5, 1, 0}) * RotateY(20) * Scale(4, 1, 1),
         1},
        {Transform(shear) * Scale(0.001, 1000, 1), 0.25, RotateZ(170) * Transform(shear), 0.75},
    };
    for (const AnimatedTransform &m : motions)
        for (double t : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0}) {
            Matrix4 fwd = m.InterpolateMatrix(t), inv;
            ASSERT_TRUE(fwd.Inverse(&inv));
            Matrix4 parts = m.InterpolateInverseMatrix(t);
            double scale = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) scale = std::max(scale, std::abs(inv.m[i][j]));
            EXPECT_LT(MaxDiff(parts, inv), 1e-12 * scale) << t;
            EXPECT_LT(MaxDiff(m.Interpolate(t).InverseMatrix(), inv), 1e-12 * scale) << t;
        }
}

TEST(AnimatedTransform, EndBeforeStartIsRejected) {
    EXPECT_THROW(AnimatedTransform(Transform(), 1, Translate({1, 0, 0}), 0), std::invalid_argument);
    // Equal times are allowed (pbrt: the start transform up to that time, the end after).
    AnimatedTransform m(Transform(), 1, Translate({1, 0, 0}), 1);
    EXPECT_EQ(m.Interpolate(1).Point(Vec3d(0, 0, 0)).x, 0);
    EXPECT_EQ(m.Interpolate(1.5).Point(Vec3d(0, 0, 0)).x, 1);
}

// Every point of the box, at every time of the interval, lies inside MotionBounds.
TEST(AnimatedTransform, MotionBoundsAreConservative) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    Bounds3d box(Vec3d(-1, -0.5, 2), Vec3d(1.5, 0.5, 3));
    for (const AnimatedTransform &m :
         {AnimatedTransform(Translate({0, 0, 0}), 0, Translate({5, 1, 0}), 1),
          AnimatedTransform(RotateX(0), 0, RotateX(179), 1),
          AnimatedTransform(Translate({1, 2, 3}) * Scale(1, 2, 1), 0.2,
                            Translate({-3, 0, 1}) * RotateZ(120) * Scale(0.5, 1, 3), 0.7)}) {
        for (auto [t0, t1] : {std::pair{0.0, 1.0}, std::pair{0.1, 0.3}, std::pair{0.45, 0.5},
                              std::pair{0.6, 0.9}}) {
            Bounds3d b = m.MotionBounds(box, t0, t1);
            for (int i = 0; i < 2000; ++i) {
                Vec3d p(Lerp(u(rng), box.pMin.x, box.pMax.x), Lerp(u(rng), box.pMin.y, box.pMax.y),
                        Lerp(u(rng), box.pMin.z, box.pMax.z));
                if (i < 8) p = box.Corner(i);
                Vec3d q = m.Interpolate(Lerp(u(rng), t0, t1)).Point(p);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_GE(q[c], b.pMin[c]);
                    EXPECT_LE(q[c], b.pMax[c]);
                }
            }
        }
    }
    // A pure translation gets the exact swept box.
    AnimatedTransform t(Translate({0, 0, 0}), 0, Translate({5, 1, 0}), 1);
    Bounds3d b = t.MotionBounds(box, 0, 1);
    EXPECT_NEAR(b.pMin.x, -1, 1e-9);
    EXPECT_NEAR(b.pMax.x, 6.5, 1e-9);
    EXPECT_NEAR(b.pMax.y, 1.5, 1e-9);
}

TEST(AnimatedTransform, TimeStepsFollowTheRotation) {
    bool linear = false;
    EXPECT_EQ(MotionTimeSteps(AnimatedTransform(Transform(), 0, Translate({3, 0, 0}), 1), &linear),
              2);
    EXPECT_TRUE(linear);
    // 90 degrees at most 3 per step: 30 segments.
    EXPECT_EQ(MotionTimeSteps(AnimatedTransform(RotateZ(0), 0, RotateZ(90), 1), &linear), 31);
    EXPECT_FALSE(linear);
    // A keyframe time inside the shutter: the kink needs steps even for a translation.
    EXPECT_GE(MotionTimeSteps(AnimatedTransform(Transform(), 0, Translate({3, 0, 0}), 0.5)), 33);
    // The chord error of a step's linear interpolation, relative to the radius, is
    // 1 - cos(1.5 degrees) < 4e-4 (measured on a point at radius 1).
    AnimatedTransform r(RotateZ(0), 0, RotateZ(90), 1);
    const int n = MotionTimeSteps(r);
    double worst = 0;
    for (int k = 0; k + 1 < n; ++k) {
        double t0 = double(k) / (n - 1), t1 = double(k + 1) / (n - 1);
        Vec3d a = r.Interpolate(t0).Point(Vec3d(1, 0, 0)),
              b = r.Interpolate(t1).Point(Vec3d(1, 0, 0));
        Vec3d mid = r.Interpolate((t0 + t1) / 2).Point(Vec3d(1, 0, 0));
        worst = std::max(worst, Length(mid - (a + b) * 0.5));
    }
    EXPECT_LT(worst, 4e-4);
}

}  // namespace
}  // namespace prism
