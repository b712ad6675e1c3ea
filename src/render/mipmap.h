// A MIP pyramid over a linear-RGB image and pbrt-v3's filtered lookups in it (pbrt-v3 §10.4
// MIPMap): trilinear interpolation between the two levels around an isotropic width, and EWA,
// the elliptically weighted average with pbrt's Gaussian weight table over the ellipse that
// the footprint's two axes span, at the two levels around its minor axis.
//
// Level 0 is the image itself (read in place, so lookups without a footprint give exactly the
// bilinear values of the unfiltered texture); each further level halves the previous one
// (rounding up) with a 2x2 box filter. pbrt-v3 first resamples images whose sides are not
// powers of two up to the next power of two (Lanczos); Prism keeps the image as it is.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/vecmath.h"
#include "render/texture.h"

namespace prism {

struct Image;

// Texture coordinates are user data: a mapping's "uscale" 1e30 puts them far beyond the range
// of int, where converting floor(x) is undefined. Texel coordinates are clamped to +-2^30
// first (at that size a float is a multiple of 128, no texel is told from the next anyway):
// exact for every coordinate inside, any finite x gives a valid index.
inline float ClampTexelCoord(float x) {
    constexpr float limit = 1073741824.f;  // 2^30
    return x < -limit ? -limit : x > limit ? limit : x;
}
// The largest "maxanisotropy" an image texture takes (an EWA lookup reads about its square).
inline constexpr float kMaxAnisotropy = 64;
// Whether floor(x) is odd (checkerboard squares), for any x: beyond 2^53 every double is an
// even integer, and a value that is not finite counts as even.
inline bool OddFloor(double x) {
    if (!(std::abs(x) < 9007199254740992.0)) return false;  // 2^53; NaN too
    return (static_cast<int64_t>(std::floor(x)) & 1) != 0;
}

class MIPMap {
  public:
    MIPMap(std::shared_ptr<const Image> image, TextureWrap wrap);
    int Levels() const { return int(levels_.size()) + 1; }
    // The bytes the levels above 0 take (the memory budget).
    size_t Bytes() const;

    // Texel (x, y) of `level` (y = 0 is the bottom row), wrapped as the texture says.
    RGB Texel(int level, int x, int y) const;
    // pbrt-v3 MIPMap::triangle: bilinear interpolation at one level, texel centres at +0.5.
    RGB Bilerp(int level, Vec2f st) const;
    // The nearest texel of level 0.
    RGB Nearest(Vec2f st) const;
    // pbrt-v3 MIPMap::Lookup(st, width): trilinear between the levels around `width` (in st).
    RGB Trilinear(Vec2f st, float width) const;
    // pbrt-v3 MIPMap::Lookup(st, dst0, dst1) with EWA: the ellipse of axes dst0, dst1 (in st),
    // its eccentricity clamped to maxAnisotropy.
    RGB EWA(Vec2f st, Vec2f dst0, Vec2f dst1, float maxAnisotropy) const;

  private:
    struct Level {
        int width = 0, height = 0;
        std::vector<RGB> texels;  // row y = 0 is t = 0
    };
    int Width(int level) const;
    int Height(int level) const;
    RGB EWALevel(int level, Vec2f st, Vec2f dst0, Vec2f dst1) const;

    std::shared_ptr<const Image> image_;
    TextureWrap wrap_;
    std::vector<Level> levels_;  // levels 1, 2, ... down to 1 x 1
    float maxRes_;               // max(width, height) of level 0
};

}  // namespace prism
