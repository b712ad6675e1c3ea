#include "core/animated_transform.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace prism {

namespace {

// The inverse of m's upper-left 3x3 part (cofactors), as a Matrix4 with an identity last row
// and column. A singular part (a decomposition never yields one) gives the general inverse.
Matrix4 Inverse3x3(const Matrix4 &m) {
    const auto &a = m.m;
    double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    Matrix4 r = Matrix4::Identity();
    if (!(det != 0) || !std::isfinite(det)) {
        Matrix4 inv;
        return m.Inverse(&inv) ? inv : r;
    }
    double s = 1 / det;
    r.m[0][0] = c00 * s;
    r.m[1][0] = c01 * s;
    r.m[2][0] = c02 * s;
    r.m[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * s;
    r.m[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * s;
    r.m[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * s;
    r.m[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * s;
    r.m[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * s;
    r.m[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * s;
    return r;
}

}  // namespace

double Dot(const Quaternion &a, const Quaternion &b) { return Dot(a.v, b.v) + a.w * b.w; }

Quaternion Normalize(const Quaternion &q) {
    double len = std::sqrt(Dot(q, q));
    return {q.v / len, q.w / len};
}

Quaternion QuaternionFromMatrix(const Matrix4 &m) {
    // Shoemake: take the largest of 4w^2, 4x^2, 4y^2, 4z^2 for the square root.
    const auto &a = m.m;
    double trace = a[0][0] + a[1][1] + a[2][2];
    Quaternion q;
    if (trace > 0) {
        double s = 2 * std::sqrt(trace + 1);  // 4w
        q.w = s / 4;
        q.v = Vec3d(a[2][1] - a[1][2], a[0][2] - a[2][0], a[1][0] - a[0][1]) / s;
    } else if (a[0][0] >= a[1][1] && a[0][0] >= a[2][2]) {
        double s = 2 * std::sqrt(1 + a[0][0] - a[1][1] - a[2][2]);  // 4x
        q.w = (a[2][1] - a[1][2]) / s;
        q.v = Vec3d(s / 4, (a[0][1] + a[1][0]) / s, (a[0][2] + a[2][0]) / s);
    } else if (a[1][1] >= a[2][2]) {
        double s = 2 * std::sqrt(1 + a[1][1] - a[0][0] - a[2][2]);  // 4y
        q.w = (a[0][2] - a[2][0]) / s;
        q.v = Vec3d((a[0][1] + a[1][0]) / s, s / 4, (a[1][2] + a[2][1]) / s);
    } else {
        double s = 2 * std::sqrt(1 + a[2][2] - a[0][0] - a[1][1]);  // 4z
        q.w = (a[1][0] - a[0][1]) / s;
        q.v = Vec3d((a[0][2] + a[2][0]) / s, (a[1][2] + a[2][1]) / s, s / 4);
    }
    return Normalize(q);
}

Matrix4 QuaternionToMatrix(const Quaternion &q) {
    const double x = q.v.x, y = q.v.y, z = q.v.z, w = q.w;
    Matrix4 r = Matrix4::Identity();
    r.m[0][0] = 1 - 2 * (y * y + z * z);
    r.m[0][1] = 2 * (x * y - w * z);
    r.m[0][2] = 2 * (x * z + w * y);
    r.m[1][0] = 2 * (x * y + w * z);
    r.m[1][1] = 1 - 2 * (x * x + z * z);
    r.m[1][2] = 2 * (y * z - w * x);
    r.m[2][0] = 2 * (x * z - w * y);
    r.m[2][1] = 2 * (y * z + w * x);
    r.m[2][2] = 1 - 2 * (x * x + y * y);
    return r;
}

double RotationAngle(const Quaternion &a, const Quaternion &b) {
    // The quaternions' angle theta (b's sign chosen for the shorter arc) is half the rotation
    // angle; atan2 of |a - b| and |a + b| gives theta / 2 without acos's loss near 0.
    double s = Dot(a, b) < 0 ? -1 : 1;
    Vec3d dv = a.v - b.v * s, sv = a.v + b.v * s;
    double dw = a.w - b.w * s, sw = a.w + b.w * s;
    double diff = std::sqrt(Dot(dv, dv) + dw * dw), sum = std::sqrt(Dot(sv, sv) + sw * sw);
    return 4 * std::atan2(diff, sum);
}

Quaternion Slerp(double t, const Quaternion &a, const Quaternion &b) {
    double cosTheta = Clamp(Dot(a, b), -1.0, 1.0);
    double theta = std::acos(cosTheta);
    double sinTheta = std::sin(theta);
    if (sinTheta < 1e-9) {  // (nearly) the same rotation: lerp is exact enough
        Quaternion q{a.v * (1 - t) + b.v * t, a.w * (1 - t) + b.w * t};
        return Normalize(q);
    }
    double wa = std::sin((1 - t) * theta) / sinTheta, wb = std::sin(t * theta) / sinTheta;
    return Normalize(Quaternion{a.v * wa + b.v * wb, a.w * wa + b.w * wb});
}

bool Decompose(const Matrix4 &m, Vec3d *T, Quaternion *R, Matrix4 *S) {
    *T = Vec3d(m.m[0][3], m.m[1][3], m.m[2][3]);
    Matrix4 M = Matrix4::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) M.m[i][j] = m.m[i][j];
    // Polar decomposition by Newton's iteration R <- (R + R^-T) / 2, which converges
    // quadratically to the orthogonal factor.
    Matrix4 rot = M;
    bool converged = false;
    for (int iter = 0; iter < 100; ++iter) {
        Matrix4 inv;
        if (!rot.Transposed().Inverse(&inv)) return false;
        Matrix4 next;
        double change = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                next.m[i][j] = 0.5 * (rot.m[i][j] + inv.m[i][j]);
                change = std::max(change, std::abs(next.m[i][j] - rot.m[i][j]));
            }
        rot = next;
        if (change < 1e-14) {
            converged = true;
            break;
        }
    }
    if (!converged) return false;
    if (rot.Determinant3x3() < 0) {  // a reflection: R proper, S takes the sign
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) rot.m[i][j] = -rot.m[i][j];
    }
    *S = rot.Transposed() * M;
    *R = QuaternionFromMatrix(rot);
    return true;
}

AnimatedTransform::AnimatedTransform(const Transform &start, double startTime, const Transform &end,
                                     double endTime)
    : start_(start), end_(end), startTime_(startTime), endTime_(endTime) {
    if (!(endTime >= startTime))
        throw std::invalid_argument("end time " + std::to_string(endTime) +
                                    " is before the start time " + std::to_string(startTime));
    animated_ = !(start.Matrix() == end.Matrix());
    if (!animated_) return;
    if (!Decompose(start.Matrix(), &T_[0], &R_[0], &S_[0]) ||
        !Decompose(end.Matrix(), &T_[1], &R_[1], &S_[1]))
        throw std::invalid_argument("a moving transform cannot be decomposed (singular)");
    if (Dot(R_[0], R_[1]) < 0) R_[1] = Quaternion{-R_[1].v, -R_[1].w};  // shorter arc
    rotationAngle_ = prism::RotationAngle(R_[0], R_[1]);
    if (rotationAngle_ < 1e-12) rotationAngle_ = 0;
    sameR_ = R_[0].v == R_[1].v && R_[0].w == R_[1].w;
    sameS_ = S_[0] == S_[1];
    Rt0_ = QuaternionToMatrix(R_[0]).Transposed();
    Sinv0_ = Inverse3x3(S_[0]);
    L0_ = Sinv0_ * Rt0_;
}

AnimatedTransform AnimatedTransform::Remapped(double t0, double t1) const {
    AnimatedTransform a = *this;
    a.startTime_ = (startTime_ - t0) / (t1 - t0);
    a.endTime_ = (endTime_ - t0) / (t1 - t0);
    return a;
}

double AnimatedTransform::Fraction(double t) const {
    if (!(t > startTime_)) return 0;
    if (t >= endTime_) return 1;
    return (t - startTime_) / (endTime_ - startTime_);
}

AnimatedTransform::Parts AnimatedTransform::PartsAt(double f) const {
    Parts p;
    p.T = T_[0] * (1 - f) + T_[1] * f;
    p.R = Slerp(f, R_[0], R_[1]);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) p.S.m[i][j] = S_[0].m[i][j] * (1 - f) + S_[1].m[i][j] * f;
    return p;
}

Matrix4 AnimatedTransform::InterpolateMatrix(double t) const {
    if (!animated_ || !(t > startTime_)) return start_.Matrix();
    if (t >= endTime_) return end_.Matrix();
    Parts p = PartsAt(Fraction(t));
    Matrix4 m = QuaternionToMatrix(p.R) * p.S;
    for (int i = 0; i < 3; ++i) m.m[i][3] = p.T[i];
    return m;
}

Matrix4 AnimatedTransform::InterpolateInverseMatrix(double t) const {
    if (!animated_ || !(t > startTime_)) return start_.InverseMatrix();
    if (t >= endTime_) return end_.InverseMatrix();
    const double f = Fraction(t);
    const Vec3d T = T_[0] * (1 - f) + T_[1] * f;
    if (sameR_ && sameS_) {
        Matrix4 L = L0_;
        for (int i = 0; i < 3; ++i)
            L.m[i][3] = -(L.m[i][0] * T.x + L.m[i][1] * T.y + L.m[i][2] * T.z);
        return L;
    }
    const Matrix4 Rt = sameR_ ? Rt0_ : QuaternionToMatrix(Slerp(f, R_[0], R_[1])).Transposed();
    Matrix4 Sinv = Sinv0_;
    if (!sameS_) {
        Matrix4 S;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) S.m[i][j] = S_[0].m[i][j] * (1 - f) + S_[1].m[i][j] * f;
        Sinv = Inverse3x3(S);
    }
    // (T R S)^-1 = S^-1 R^T T^-1: the 3x3 part L = S^-1 R^T, the translation -L T.
    Matrix4 L = Sinv * Rt;
    for (int i = 0; i < 3; ++i) L.m[i][3] = -(L.m[i][0] * T.x + L.m[i][1] * T.y + L.m[i][2] * T.z);
    return L;
}

Transform AnimatedTransform::Interpolate(double t) const {
    if (!animated_ || !(t > startTime_)) return start_;
    if (t >= endTime_) return end_;
    return Transform(InterpolateMatrix(t), InterpolateInverseMatrix(t));
}

Bounds3d AnimatedTransform::MotionBounds(const Bounds3d &b, double t0, double t1) const {
    double f0 = Fraction(t0), f1 = Fraction(t1);
    if (!animated_ || f0 == f1) return Interpolate(t0).Bounds(b);
    // A point p moves to T(t) + R(t) S(t) p. Over [t0, t1]: T(t) stays on the segment
    // T(f0) T(f1); S(t) p lies in the hull of S(f0) c and S(f1) c over b's corners c; and R(t)
    // differs from R(f0) by a rotation of at most phi (slerp is monotonic along its arc),
    // which moves a vector v by at most 2 sin(phi / 2) |v|.
    Parts p0 = PartsAt(f0), p1 = PartsAt(f1);
    Transform r0(QuaternionToMatrix(p0.R), QuaternionToMatrix(p0.R).Transposed());
    Bounds3d out;
    double rho = 0;
    for (const Parts *p : {&p0, &p1}) {
        Transform s(p->S, Matrix4::Identity());  // only its forward part is used
        for (int c = 0; c < 8; ++c) {
            Vec3d v = s.Vector(b.Corner(c));
            rho = std::max(rho, Length(v));
            out.Expand(r0.Vector(v));
        }
    }
    double phi = std::min(prism::RotationAngle(p0.R, p1.R), Pi);
    double pad = 2 * std::sin(phi / 2) * rho;
    Vec3d tMin = Min(p0.T, p1.T), tMax = Max(p0.T, p1.T);
    out.pMin = out.pMin + tMin - Vec3d(pad, pad, pad);
    out.pMax = out.pMax + tMax + Vec3d(pad, pad, pad);
    // Rounding of the above: a relative margin.
    double scale = std::max(MaxComponent(Abs(out.pMin)), MaxComponent(Abs(out.pMax)));
    Vec3d eps(1e-12 * scale, 1e-12 * scale, 1e-12 * scale);
    out.pMin = out.pMin - eps;
    out.pMax = out.pMax + eps;
    return out;
}

int MotionTimeSteps(const AnimatedTransform &m, bool *linear) {
    bool kink = (m.StartTime() > 0 && m.StartTime() < 1) || (m.EndTime() > 0 && m.EndTime() < 1);
    double degrees = Degrees(m.RotationDuring(0, 1));
    bool lin = !kink && degrees == 0;
    if (linear) *linear = lin;
    if (lin) return 2;
    int segments = int(std::ceil(degrees / MaxStepRotationDegrees));
    if (kink) segments = std::max(segments, 32);
    return 1 + std::clamp(segments, 1, 128);
}

}  // namespace prism
