#include "render/noise.h"

#include <cmath>

namespace prism {

namespace {

// The permutation of 0..255 published with Perlin's improved-noise reference implementation
// (the same table pbrt-v3 uses, so patterns match it).
constexpr int PermSize = 256;
constexpr unsigned char Perm[PermSize] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103,
    30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,
    197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174,
    20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231,
    83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143,
    54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196,
    135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124,
    123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,
    182, 189, 28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101,
    155, 167, 43,  172, 9,   129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185,
    112, 104, 218, 246, 97,  228, 251, 34,  242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,
    51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176,
    115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243,
    141, 128, 195, 78,  66,  215, 61,  156, 180,
};

inline int P(int i) { return Perm[i & (PermSize - 1)]; }

// Dot product of the offset with one of 12 cube-edge gradients (plus 4 repeats) picked by
// hashing the lattice point, as in Perlin (2002).
float Grad(int x, int y, int z, float dx, float dy, float dz) {
    int h = P(P(P(x) + y) + z) & 15;
    float u = h < 8 || h == 12 || h == 13 ? dx : dy;
    float v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// The quintic fade 6t^5 - 15t^4 + 10t^3: C2-continuous across cells.
float Fade(float t) {
    float t3 = t * t * t;
    return t3 * (t * (t * 6 - 15) + 10);
}

float Mix(float t, float a, float b) { return (1 - t) * a + t * b; }

}  // namespace

float PerlinNoise(float x, float y, float z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0;
    float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    float dx = x - fx, dy = y - fy, dz = z - fz;
    // Wrap the cell in float first: the lattice is periodic, and huge coordinates must not
    // overflow the int conversion.
    int ix = int(std::fmod(fx, float(PermSize))), iy = int(std::fmod(fy, float(PermSize))),
        iz = int(std::fmod(fz, float(PermSize)));
    ix &= PermSize - 1;
    iy &= PermSize - 1;
    iz &= PermSize - 1;
    float w000 = Grad(ix, iy, iz, dx, dy, dz);
    float w100 = Grad(ix + 1, iy, iz, dx - 1, dy, dz);
    float w010 = Grad(ix, iy + 1, iz, dx, dy - 1, dz);
    float w110 = Grad(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
    float w001 = Grad(ix, iy, iz + 1, dx, dy, dz - 1);
    float w101 = Grad(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
    float w011 = Grad(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
    float w111 = Grad(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);
    float wx = Fade(dx), wy = Fade(dy), wz = Fade(dz);
    float y0 = Mix(wy, Mix(wx, w000, w100), Mix(wx, w010, w110));
    float y1 = Mix(wy, Mix(wx, w001, w101), Mix(wx, w011, w111));
    return Mix(wz, y0, y1);
}

Vec3f PerlinNoiseSlope(const Vec3f &p) {
    constexpr float delta = .01f;
    const float n = PerlinNoise(p);
    return Vec3f(PerlinNoise(p.x + delta, p.y, p.z) - n, PerlinNoise(p.x, p.y + delta, p.z) - n,
                 PerlinNoise(p.x, p.y, p.z + delta) - n) /
           delta;
}

float FBm(const Vec3f &p, float omega, int octaves) {
    float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * PerlinNoise(p * lambda);
        lambda *= 1.99f;
        o *= omega;
    }
    return sum;
}

float Turbulence(const Vec3f &p, float omega, int octaves) {
    float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * std::abs(PerlinNoise(p * lambda));
        lambda *= 1.99f;
        o *= omega;
    }
    // pbrt-v3 adds the clamped octaves' average |noise| of 0.2 for the partial octave; with a
    // zero footprint that term is exactly 0.2·omega^octaves.
    return sum + o * 0.2f;
}

}  // namespace prism
