// Transforms that move over time (pbrt-v3's AnimatedTransform semantics, written anew): two
// keyframe transforms at a start and an end time, each decomposed into a translation T, a
// rotation R (unit quaternion) and a symmetric stretch S (M = T R S, polar decomposition);
// in between, T and S are interpolated linearly and R by slerp along the shorter arc. Before
// the start time the start transform holds, after the end time the end transform.
#pragma once

#include "core/transform.h"
#include "core/vecmath.h"

namespace prism {

struct Quaternion {
    Vec3d v{0, 0, 0};
    double w = 1;
};

double Dot(const Quaternion &a, const Quaternion &b);
Quaternion Normalize(const Quaternion &q);
// Unit quaternion of a proper rotation matrix (upper-left 3x3 of m), and back.
Quaternion QuaternionFromMatrix(const Matrix4 &m);
Matrix4 QuaternionToMatrix(const Quaternion &q);
// Spherical interpolation from a (t = 0) to b (t = 1) at constant angular speed; the caller
// chooses the sign of b (AnimatedTransform takes the shorter arc).
Quaternion Slerp(double t, const Quaternion &a, const Quaternion &b);
// The angle (radians, in [0, pi]) of the rotation that takes a to b.
double RotationAngle(const Quaternion &a, const Quaternion &b);

// M = Translate(T) * R * S with R a proper rotation and S symmetric (the polar decomposition
// of M's 3x3 part; a reflection is carried by S). Returns false if the iteration does not
// converge (a singular M).
bool Decompose(const Matrix4 &m, Vec3d *T, Quaternion *R, Matrix4 *S);

class AnimatedTransform {
  public:
    AnimatedTransform() = default;
    // Static: the transform at every time.
    explicit AnimatedTransform(const Transform &t) : AnimatedTransform(t, 0, t, 1) {}
    // Throws std::invalid_argument when endTime < startTime or a keyframe cannot be decomposed.
    AnimatedTransform(const Transform &start, double startTime, const Transform &end,
                      double endTime);

    // Whether the two keyframes differ (a transform that moves at some time).
    bool IsAnimated() const { return animated_; }
    // Whether the rotation part changes between the keyframes.
    bool HasRotation() const { return rotationAngle_ > 0; }
    double RotationAngle() const { return rotationAngle_; }  // radians, in [0, pi]
    double StartTime() const { return startTime_; }
    double EndTime() const { return endTime_; }
    const Transform &Start() const { return start_; }
    const Transform &End() const { return end_; }

    // Whether the transform changes anywhere inside [t0, t1].
    bool MovesDuring(double t0, double t1) const {
        return animated_ && t1 > startTime_ && t0 < endTime_ && t1 > t0;
    }
    // The same motion with time remapped so that t0 becomes 0 and t1 becomes 1 (the shutter
    // interval, for rays whose time is their fraction of the shutter). Requires t1 > t0.
    AnimatedTransform Remapped(double t0, double t1) const;

    // The rotation angle (radians) swept during [t0, t1].
    double RotationDuring(double t0, double t1) const {
        return rotationAngle_ * (Fraction(t1) - Fraction(t0));
    }

    // The transform at time t: exactly Start() at or before the start time, exactly End() at
    // or after the end time.
    Transform Interpolate(double t) const;
    Matrix4 InterpolateMatrix(double t) const;
    // The inverse of InterpolateMatrix(t), from the parts (S^-1 R^T T^-1) rather than by a
    // general 4x4 inversion: moving analytic shapes need it for every ray they test. A stretch
    // or rotation that stays the same between the keyframes is inverted once, up front.
    Matrix4 InterpolateInverseMatrix(double t) const;
    // A conservative box around b (object space) transformed at every time in [t0, t1].
    Bounds3d MotionBounds(const Bounds3d &b, double t0, double t1) const;

  private:
    struct Parts {
        Vec3d T;
        Quaternion R;
        Matrix4 S;
    };
    double Fraction(double t) const;  // 0..1 along the keyframes, clamped
    Parts PartsAt(double f) const;

    Transform start_, end_;
    double startTime_ = 0, endTime_ = 1;
    bool animated_ = false;
    Vec3d T_[2];
    Quaternion R_[2];
    Matrix4 S_[2];
    // Precomputed for InterpolateInverseMatrix when the rotation or the stretch is the same in
    // both keyframes: R^T and S^-1 (3x3 parts).
    bool sameR_ = false, sameS_ = false;
    Matrix4 Rt0_, Sinv0_;
    Matrix4 L0_;  // S^-1 R^T when both stay the same (a pure translation): only T moves
    double rotationAngle_ = 0;
};

// Embree motion-blur time steps, evenly spaced over [0, 1], for a motion whose times are
// fractions of the shutter interval: 2 when everything moves linearly during the shutter (no
// rotation, no keyframe time strictly inside (0, 1)), else enough that a rotation turns at
// most MaxStepRotationDegrees per step (and at least 33 across a keyframe time inside the
// shutter), up to Embree's 129. *linear tells which.
inline constexpr double MaxStepRotationDegrees = 3;
int MotionTimeSteps(const AnimatedTransform &m, bool *linear = nullptr);

}  // namespace prism
