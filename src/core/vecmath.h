// Small value types for geometry: Vec2/Vec3 over float or double, free-function algebra.
// Points, vectors and normals share Vec3; transforms apply them through separately named
// functions (Transform::Point/Vector/Normal), which keeps the algebra small while making
// the transform rule explicit at every call site.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace prism {

inline constexpr double Pi = 3.14159265358979323846;
inline constexpr double InvPi = 0.31830988618379067154;
inline constexpr float Infinity = std::numeric_limits<float>::infinity();

template <typename T>
struct Vec2 {
    T x{}, y{};
    constexpr Vec2() = default;
    constexpr Vec2(T x_, T y_) : x(x_), y(y_) {}
    T operator[](int i) const { return i == 0 ? x : y; }
    T &operator[](int i) { return i == 0 ? x : y; }
    Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    Vec2 operator*(T s) const { return {x * s, y * s}; }
    bool operator==(const Vec2 &) const = default;
};

template <typename T>
struct Vec3 {
    T x{}, y{}, z{};
    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <typename U>
    explicit constexpr Vec3(const Vec3<U> &v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}

    T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    T &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 operator+(const Vec3 &o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vec3 operator-(const Vec3 &o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
    Vec3 operator/(T s) const {
        T inv = T(1) / s;
        return {x * inv, y * inv, z * inv};
    }
    Vec3 &operator+=(const Vec3 &o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    Vec3 &operator-=(const Vec3 &o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    Vec3 &operator*=(T s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    bool operator==(const Vec3 &) const = default;
    bool HasNaN() const { return std::isnan(x) || std::isnan(y) || std::isnan(z); }
};

template <typename T>
inline Vec3<T> operator*(T s, const Vec3<T> &v) {
    return v * s;
}

using Vec2f = Vec2<float>;
using Vec2d = Vec2<double>;
using Vec2i = Vec2<int>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

template <typename T>
inline T Dot(const Vec3<T> &a, const Vec3<T> &b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
inline T AbsDot(const Vec3<T> &a, const Vec3<T> &b) {
    return std::abs(Dot(a, b));
}
template <typename T>
inline Vec3<T> Cross(const Vec3<T> &a, const Vec3<T> &b) {
    // Computed in double for float inputs: products of two floats are exact in double,
    // which removes the catastrophic cancellation of a*b - c*d.
    using D = std::conditional_t<std::is_same_v<T, float>, double, T>;
    return {T(D(a.y) * b.z - D(a.z) * b.y), T(D(a.z) * b.x - D(a.x) * b.z),
            T(D(a.x) * b.y - D(a.y) * b.x)};
}
template <typename T>
inline T LengthSquared(const Vec3<T> &v) {
    return Dot(v, v);
}
template <typename T>
inline T Length(const Vec3<T> &v) {
    return std::sqrt(Dot(v, v));
}
template <typename T>
inline Vec3<T> Normalize(const Vec3<T> &v) {
    return v / Length(v);
}
template <typename T>
inline Vec3<T> Abs(const Vec3<T> &v) {
    return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}
template <typename T>
inline Vec3<T> Min(const Vec3<T> &a, const Vec3<T> &b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
inline Vec3<T> Max(const Vec3<T> &a, const Vec3<T> &b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T>
inline T MaxComponent(const Vec3<T> &v) {
    return std::max(v.x, std::max(v.y, v.z));
}
template <typename T>
inline Vec3<T> FaceForward(const Vec3<T> &n, const Vec3<T> &v) {
    return Dot(n, v) < T(0) ? -n : n;
}
template <typename T>
inline T Distance(const Vec3<T> &a, const Vec3<T> &b) {
    return Length(a - b);
}

// Builds an orthonormal basis (v2, v3) around unit v1 (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited").
template <typename T>
inline void CoordinateSystem(const Vec3<T> &v1, Vec3<T> *v2, Vec3<T> *v3) {
    T sign = std::copysign(T(1), v1.z);
    T a = T(-1) / (sign + v1.z);
    T b = v1.x * v1.y * a;
    *v2 = Vec3<T>(T(1) + sign * v1.x * v1.x * a, sign * b, -sign * v1.x);
    *v3 = Vec3<T>(b, sign + v1.y * v1.y * a, -v1.y);
}

template <typename T>
struct Bounds3 {
    Vec3<T> pMin{std::numeric_limits<T>::max(), std::numeric_limits<T>::max(),
                 std::numeric_limits<T>::max()};
    Vec3<T> pMax{std::numeric_limits<T>::lowest(), std::numeric_limits<T>::lowest(),
                 std::numeric_limits<T>::lowest()};
    Bounds3() = default;
    Bounds3(const Vec3<T> &a, const Vec3<T> &b) : pMin(Min(a, b)), pMax(Max(a, b)) {}
    bool IsEmpty() const { return pMin.x > pMax.x || pMin.y > pMax.y || pMin.z > pMax.z; }
    Vec3<T> Corner(int i) const {
        return {(i & 1) ? pMax.x : pMin.x, (i & 2) ? pMax.y : pMin.y, (i & 4) ? pMax.z : pMin.z};
    }
    Vec3<T> Diagonal() const { return pMax - pMin; }
    Vec3<T> Center() const { return (pMin + pMax) * T(0.5); }
    void Expand(const Vec3<T> &p) {
        pMin = Min(pMin, p);
        pMax = Max(pMax, p);
    }
    void Expand(const Bounds3 &b) {
        pMin = Min(pMin, b.pMin);
        pMax = Max(pMax, b.pMax);
    }
};
using Bounds3f = Bounds3<float>;
using Bounds3d = Bounds3<double>;

// Floating-point helpers for conservative error bounds (pbrt-v3 §3.9 conventions).
template <typename T>
constexpr T MachineEpsilon() {
    return std::numeric_limits<T>::epsilon() * T(0.5);
}
template <typename T>
constexpr T Gamma(int n) {
    return (n * MachineEpsilon<T>()) / (1 - n * MachineEpsilon<T>());
}

// float(v), kept as a float: the optimizer cannot fold double(OpaqueFloat(v)) back into v.
// GCC 12 (Debian 12's compiler) does that at -O2 and above when its SLP vectorizer packs such
// conversions in pairs (cvtpd2ps with no cvtps2pd back), so |double(float(v)) - v|, the
// rounding error an error bound adds, came out as 0 (tests/geometry/sphere_test.cpp checks the
// bound of an analytic hit point).
inline float OpaqueFloat(double v) {
    float f = float(v);
#if defined(__GNUC__)
    __asm__("" : "+g"(f));
#endif
    return f;
}
inline Vec3f OpaqueFloat(const Vec3d &v) {
    return {OpaqueFloat(v.x), OpaqueFloat(v.y), OpaqueFloat(v.z)};
}

// std::nextafter(v, +-Infinity) without the library call (three per spawned ray): the
// neighbouring float by one step of its bit pattern; both zeros step to the smallest denormal
// of the direction; infinities toward themselves and NaN stay.
inline float NextFloatUp(float v) {
    if (!(v < Infinity)) return v;
    if (v == 0.f) return std::numeric_limits<float>::denorm_min();
    const uint32_t bits = std::bit_cast<uint32_t>(v);
    return std::bit_cast<float>(v > 0 ? bits + 1 : bits - 1);
}
inline float NextFloatDown(float v) {
    if (!(v > -Infinity)) return v;
    if (v == 0.f) return -std::numeric_limits<float>::denorm_min();
    const uint32_t bits = std::bit_cast<uint32_t>(v);
    return std::bit_cast<float>(v > 0 ? bits - 1 : bits + 1);
}

template <typename T>
inline T Clamp(T v, T lo, T hi) {
    return v < lo ? lo : (v > hi ? hi : v);
}
template <typename T>
inline T Lerp(T t, T a, T b) {
    return (1 - t) * a + t * b;
}
inline double Radians(double deg) { return deg * (Pi / 180.0); }
inline double Degrees(double rad) { return rad * (180.0 / Pi); }
template <typename T>
inline T SafeSqrt(T x) {
    return std::sqrt(std::max(T(0), x));
}
template <typename T>
inline T SafeACos(T x) {
    return std::acos(Clamp(x, T(-1), T(1)));
}

std::string ToString(const Vec3f &v);
std::string ToString(const Vec3d &v);

}  // namespace prism
