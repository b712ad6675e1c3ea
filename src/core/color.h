// Linear RGB radiance/reflectance value type.
#pragma once

#include <algorithm>
#include <cmath>

namespace prism {

struct RGB {
    float r = 0, g = 0, b = 0;
    constexpr RGB() = default;
    constexpr RGB(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    explicit constexpr RGB(float v) : r(v), g(v), b(v) {}

    float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    float &operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    RGB operator+(const RGB &o) const { return {r + o.r, g + o.g, b + o.b}; }
    RGB operator-(const RGB &o) const { return {r - o.r, g - o.g, b - o.b}; }
    RGB operator*(const RGB &o) const { return {r * o.r, g * o.g, b * o.b}; }
    RGB operator/(const RGB &o) const { return {r / o.r, g / o.g, b / o.b}; }
    RGB operator*(float s) const { return {r * s, g * s, b * s}; }
    RGB operator/(float s) const { return {r / s, g / s, b / s}; }
    RGB &operator+=(const RGB &o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    RGB &operator*=(const RGB &o) {
        r *= o.r;
        g *= o.g;
        b *= o.b;
        return *this;
    }
    RGB &operator*=(float s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    bool operator==(const RGB &) const = default;

    bool IsBlack() const { return r == 0 && g == 0 && b == 0; }
    float MaxComponent() const { return std::max(r, std::max(g, b)); }
    float Average() const { return (r + g + b) / 3.f; }
    float Luminance() const { return 0.212671f * r + 0.715160f * g + 0.072169f * b; }
    bool IsFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
    RGB Clamped(float lo = 0.f, float hi = INFINITY) const {
        return {std::clamp(r, lo, hi), std::clamp(g, lo, hi), std::clamp(b, lo, hi)};
    }
};

inline RGB operator*(float s, const RGB &c) { return c * s; }
// m (row-major 3x3, as std::array<float, 9> or a float[9]) times c.
template <class M>
RGB ApplyColorMatrix(const M &m, const RGB &c) {
    return {m[0] * c.r + m[1] * c.g + m[2] * c.b, m[3] * c.r + m[4] * c.g + m[5] * c.b,
            m[6] * c.r + m[7] * c.g + m[8] * c.b};
}
inline RGB Sqrt(const RGB &c) { return {std::sqrt(c.r), std::sqrt(c.g), std::sqrt(c.b)}; }

}  // namespace prism
