// 4x4 affine/projective transform in double precision with its cached inverse.
// Named destFromSource by convention (worldFromObject). Double storage keeps object-space
// math exact enough for far-from-origin scenes (docs/SHAPES.md S5).
#pragma once

#include <array>
#include <string>

#include "core/vecmath.h"

namespace prism {

struct Matrix4 {
    std::array<std::array<double, 4>, 4> m{};
    static Matrix4 Identity();
    Matrix4 operator*(const Matrix4 &o) const;
    bool operator==(const Matrix4 &) const = default;
    bool IsIdentity() const;
    double Determinant3x3() const;
    // Returns false if the matrix is singular.
    bool Inverse(Matrix4 *out) const;
    Matrix4 Transposed() const;
};

class Transform {
  public:
    Transform() : m_(Matrix4::Identity()), mInv_(Matrix4::Identity()) {}
    // Throws std::invalid_argument if m is singular.
    explicit Transform(const Matrix4 &m);
    Transform(const Matrix4 &m, const Matrix4 &mInv) : m_(m), mInv_(mInv) {}

    const Matrix4 &Matrix() const { return m_; }
    const Matrix4 &InverseMatrix() const { return mInv_; }
    Transform Inverse() const { return Transform(mInv_, m_); }
    Transform operator*(const Transform &o) const { return {m_ * o.m_, o.mInv_ * mInv_}; }
    bool operator==(const Transform &o) const { return m_ == o.m_; }
    bool IsIdentity() const { return m_.IsIdentity(); }
    bool SwapsHandedness() const { return m_.Determinant3x3() < 0; }

    // Apply to points (with homogeneous divide), vectors and normals (inverse transpose).
    Vec3d Point(const Vec3d &p) const;
    Vec3d Vector(const Vec3d &v) const;
    Vec3d Normal(const Vec3d &n) const;
    Vec3f Point(const Vec3f &p) const { return Vec3f(Point(Vec3d(p))); }
    Vec3f Vector(const Vec3f &v) const { return Vec3f(Vector(Vec3d(v))); }
    Vec3f Normal(const Vec3f &n) const { return Vec3f(Normal(Vec3d(n))); }
    Bounds3d Bounds(const Bounds3d &b) const;

    // Conservative absolute error of Point(p) when p itself carries |error| <= pErr,
    // evaluated in arithmetic of epsilon eps (pbrt-v3 transform.h, generalized).
    Vec3d PointError(const Vec3d &p, const Vec3d &pErr, double eps) const;

    std::string ToString() const;

  private:
    Matrix4 m_, mInv_;
};

Transform Translate(const Vec3d &delta);
Transform Scale(double x, double y, double z);
Transform RotateX(double deg);
Transform RotateY(double deg);
Transform RotateZ(double deg);
Transform Rotate(double deg, const Vec3d &axis);
// pbrt-v3 LookAt: returns camera-from-world. Throws std::invalid_argument on degenerate input.
Transform LookAt(const Vec3d &eye, const Vec3d &look, const Vec3d &up);
// 16 numbers in pbrt's order (column-major: translation in elements 12..14).
Transform FromPbrtMatrix(const double v[16]);

}  // namespace prism
