#include "render/texture.h"

#include <algorithm>
#include <cmath>

#include "image/image.h"
#include "render/mipmap.h"
#include "render/noise.h"

namespace prism {

Vec2f TextureMapping::Map(const TextureContext &ctx) const {
    switch (kind) {
        case Kind::UV:
            return {su * ctx.uv.x + du, sv * ctx.uv.y + dv};
        case Kind::Spherical: {
            Vec3d v = Normalize(textureFromRender.Point(Vec3d(ctx.p)));
            double theta = SafeACos(v.z), phi = std::atan2(v.y, v.x);
            if (phi < 0) phi += 2 * Pi;
            return {float(theta * InvPi), float(phi * (0.5 * InvPi))};
        }
        case Kind::Cylindrical: {
            Vec3d v = textureFromRender.Point(Vec3d(ctx.p));
            return {float((Pi + std::atan2(v.y, v.x)) * (0.5 * InvPi)), float(v.z)};
        }
        case Kind::Planar: {
            Vec3f v = Vec3f(textureFromRender.Point(Vec3d(ctx.p)));
            return {du + Dot(v, v1), dv + Dot(v, v2)};
        }
    }
    return ctx.uv;
}

Vec2f TextureMapping::Map(const TextureContext &ctx, Vec2f *dstdx, Vec2f *dstdy) const {
    switch (kind) {
        case Kind::UV:
            *dstdx = {su * ctx.dudx, sv * ctx.dvdx};
            *dstdy = {su * ctx.dudy, sv * ctx.dvdy};
            return Map(ctx);
        case Kind::Planar: {
            Vec3f dx = Vec3f(textureFromRender.Vector(Vec3d(ctx.dpdx)));
            Vec3f dy = Vec3f(textureFromRender.Vector(Vec3d(ctx.dpdy)));
            *dstdx = {Dot(dx, v1), Dot(dx, v2)};
            *dstdy = {Dot(dy, v1), Dot(dy, v2)};
            return Map(ctx);
        }
        case Kind::Spherical:
        case Kind::Cylindrical: {
            // pbrt-v3: forward differences a tenth of the footprint away, unwrapped across
            // the seam of the periodic coordinate (t for spherical, s for cylindrical).
            const float delta = .1f;
            const Vec2f st = Map(ctx);
            const int periodic = kind == Kind::Spherical ? 1 : 0;
            auto diff = [&](const Vec3f &dp) {
                TextureContext c = ctx;
                c.p = ctx.p + dp * delta;
                Vec2f d = (Map(c) - st) * (1 / delta);
                float &w = periodic == 1 ? d.y : d.x;
                if (w > .5f / delta)
                    w -= 1 / delta;
                else if (w < -.5f / delta)
                    w += 1 / delta;
                return d;
            };
            *dstdx = diff(ctx.dpdx);
            *dstdy = diff(ctx.dpdy);
            return st;
        }
    }
    *dstdx = *dstdy = Vec2f();
    return Map(ctx);
}

const char *TextureFilterName(TextureFilter f) {
    switch (f) {
        case TextureFilter::Point:
            return "point";
        case TextureFilter::Bilinear:
            return "bilinear";
        case TextureFilter::Trilinear:
            return "trilinear";
        case TextureFilter::EWA:
            return "ewa";
    }
    return "?";
}

namespace {

// The integral of the odd-square indicator of one axis from 0 to x (pbrt-v3's bumpInt): the
// length of [0, x] covered by squares with odd floor.
float BumpInt(float x) {
    const float h = std::floor(x / 2);
    return h + 2 * std::max(x / 2 - h - .5f, 0.f);
}

}  // namespace

float CheckerboardTexture::OddFraction(float s, float t, float ds, float dt) {
    // Per axis, the fraction of [x - d, x + d] on odd squares (the indicator itself for d = 0).
    auto axis = [](float x, float d) {
        if (!(d > 0)) return (long(std::floor(x)) & 1) ? 1.f : 0.f;
        return (BumpInt(x + d) - BumpInt(x - d)) / (2 * d);
    };
    const float sint = axis(s, ds), tint = axis(t, dt);
    // A square is odd where exactly one of the two axes is.
    return sint + tint - 2 * sint * tint;
}

RGB CheckerboardTexture::Evaluate(const TextureContext &c) const {
    if (dim_ == 3) {
        Vec3d p = mapping_.textureFromRender.Point(Vec3d(c.p));
        long s = long(std::floor(p.x)) + long(std::floor(p.y)) + long(std::floor(p.z));
        return (s % 2 == 0) ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
    }
    if (aa_ == AAMode::ClosedForm) {
        Vec2f dstdx, dstdy;
        const Vec2f st = mapping_.Map(c, &dstdx, &dstdy);
        // The box the sample's footprint spans: half a differential to either side (pbrt-v3
        // takes a whole one, a box twice as wide).
        const float ds = 0.5f * std::max(std::abs(dstdx.x), std::abs(dstdy.x));
        const float dt = 0.5f * std::max(std::abs(dstdx.y), std::abs(dstdy.y));
        // The box [s - ds, s + ds] x [t - dt, t + dt] inside one square: point sample (below).
        if (std::isfinite(ds) && std::isfinite(dt) &&
            (std::floor(st.x - ds) != std::floor(st.x + ds) ||
             std::floor(st.y - dt) != std::floor(st.y + dt))) {
            const float odd = OddFraction(st.x, st.y, ds, dt);
            return tex1_->Evaluate(c) * (1 - odd) + tex2_->Evaluate(c) * odd;
        }
    }
    Vec2f st = mapping_.Map(c);
    long s = long(std::floor(st.x)) + long(std::floor(st.y));
    return (s % 2 == 0) ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
}

ImageTexture::ImageTexture(TextureMapping mapping, std::shared_ptr<const Image> image,
                           WrapMode wrap, float scale, bool invert, TextureFilter filter,
                           std::shared_ptr<const MIPMap> mip, float maxAnisotropy)
    : mapping_(mapping),
      image_(std::move(image)),
      wrap_(wrap),
      scale_(scale),
      invert_(invert),
      filter_(filter),
      mip_(filter == TextureFilter::Trilinear || filter == TextureFilter::EWA ? std::move(mip)
                                                                              : nullptr),
      maxAnisotropy_(maxAnisotropy) {}

RGB ImageTexture::Texel(int x, int y) const {
    int w = image_->width, h = image_->height;
    switch (wrap_) {
        case WrapMode::Repeat:
            x = ((x % w) + w) % w;
            y = ((y % h) + h) % h;
            break;
        case WrapMode::Clamp:
            x = Clamp(x, 0, w - 1);
            y = Clamp(y, 0, h - 1);
            break;
        case WrapMode::Black:
            if (x < 0 || x >= w || y < 0 || y >= h) return RGB(0);
            break;
    }
    // Texture t runs upward; image rows run downward.
    return image_->GetRGB(x, h - 1 - y);
}

RGB ImageTexture::Evaluate(const TextureContext &c) const {
    RGB v;
    if (mip_) {
        Vec2f dstdx, dstdy;
        const Vec2f st = mapping_.Map(c, &dstdx, &dstdy);
        // The sample's footprint spans half a differential to either side (pbrt-v3 filters
        // over a whole differential to either side: twice as wide, so blurrier).
        const Vec2f h0 = dstdx * 0.5f, h1 = dstdy * 0.5f;
        if (filter_ == TextureFilter::EWA) {
            v = mip_->EWA(st, h0, h1, maxAnisotropy_);
        } else {
            const float width = 2 * std::max(std::max(std::abs(h0.x), std::abs(h0.y)),
                                             std::max(std::abs(h1.x), std::abs(h1.y)));
            v = mip_->Trilinear(st, std::isfinite(width) ? width : 0.f);
        }
    } else {
        Vec2f st = mapping_.Map(c);
        float s = st.x * image_->width, t = st.y * image_->height;
        if (!std::isfinite(s) || !std::isfinite(t)) return RGB(0);
        if (filter_ == TextureFilter::Point) {
            v = Texel(int(std::floor(s)), int(std::floor(t)));
        } else {
            // Bilinear at the finest level (pbrt MIPMap::Bilerp: texel centres at +0.5).
            s -= 0.5f;
            t -= 0.5f;
            int s0 = int(std::floor(s)), t0 = int(std::floor(t));
            float ds = s - s0, dt = t - t0;
            v = Texel(s0, t0) * ((1 - ds) * (1 - dt)) + Texel(s0, t0 + 1) * ((1 - ds) * dt) +
                Texel(s0 + 1, t0) * (ds * (1 - dt)) + Texel(s0 + 1, t0 + 1) * (ds * dt);
        }
    }
    v *= scale_;
    if (invert_) v = (RGB(1) - v).Clamped(0.f);
    return v;
}

Vec3f TextureMapping3D::Map(const TextureContext &ctx) const {
    return Vec3f(textureFromRender.Point(Vec3d(ctx.p)));
}

RGB BilerpTexture::Evaluate(const TextureContext &c) const {
    Vec2f st = mapping_.Map(c);
    float s = st.x, t = st.y;
    return v00_ * ((1 - s) * (1 - t)) + v01_ * ((1 - s) * t) + v10_ * (s * (1 - t)) +
           v11_ * (s * t);
}

RGB UVTexture::Evaluate(const TextureContext &c) const {
    Vec2f st = mapping_.Map(c);
    if (!std::isfinite(st.x) || !std::isfinite(st.y)) return RGB(0);
    return RGB(st.x - std::floor(st.x), st.y - std::floor(st.y), 0);
}

RGB DotsTexture::Evaluate(const TextureContext &c) const {
    Vec2f st = mapping_.Map(c);
    if (!std::isfinite(st.x) || !std::isfinite(st.y)) return outside_->Evaluate(c);
    // Cells are centred on integer (s, t); noise at fixed offsets in the cell decides whether
    // it has a dot and where, so the pattern is deterministic.
    float sCell = std::floor(st.x + .5f), tCell = std::floor(st.y + .5f);
    if (PerlinNoise(sCell + .5f, tCell + .5f, .5f) > 0) {
        const float radius = .35f, maxShift = 0.5f - radius;
        float sCenter = sCell + maxShift * PerlinNoise(sCell + 1.5f, tCell + 2.8f, .5f);
        float tCenter = tCell + maxShift * PerlinNoise(sCell + 4.5f, tCell + 9.8f, .5f);
        float ds = st.x - sCenter, dt = st.y - tCenter;
        if (ds * ds + dt * dt < radius * radius) return inside_->Evaluate(c);
    }
    return outside_->Evaluate(c);
}

RGB NoiseTexture::Evaluate(const TextureContext &c) const {
    Vec3f p = mapping_.Map(c);
    switch (kind_) {
        case Kind::FBm:
            return RGB(FBm(p, omega_, octaves_));
        case Kind::Wrinkled:
            return RGB(Turbulence(p, omega_, octaves_));
        case Kind::Windy: {
            // Low-frequency wind strength modulating higher-frequency waves (pbrt-v3 WindyTexture).
            float windStrength = FBm(p * .1f, .5f, 3);
            float waveHeight = FBm(p, .5f, 6);
            return RGB(std::abs(windStrength) * waveHeight);
        }
    }
    return RGB(0);
}

RGB MarbleTexture::Evaluate(const TextureContext &c) const {
    Vec3f p = mapping_.Map(c) * scale_;
    float marble = p.y + variation_ * FBm(p, omega_, octaves_);
    float t = .5f + .5f * std::sin(marble);
    // pbrt-v3's marble colour spline (linear RGB control points).
    static const RGB colors[] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                 {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                 {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    const int nSeg = int(sizeof(colors) / sizeof(colors[0])) - 3;
    // The segment under t, as pbrt-v4 picks it. (pbrt-v3's min(1, floor(t·nSeg)) only ever
    // used the first two segments and extrapolated the second to t = 5, giving values near 40.)
    float seg = std::floor(t * nSeg);
    int first = seg >= 0 ? std::min(int(seg), nSeg - 1) : 0;  // also NaN-safe
    t = t * nSeg - float(first);
    const RGB &c0 = colors[first], &c1 = colors[first + 1], &c2 = colors[first + 2],
              &c3 = colors[first + 3];
    // Cubic Bézier by de Casteljau's algorithm.
    RGB s0 = c0 * (1 - t) + c1 * t, s1 = c1 * (1 - t) + c2 * t, s2 = c2 * (1 - t) + c3 * t;
    s0 = s0 * (1 - t) + s1 * t;
    s1 = s1 * (1 - t) + s2 * t;
    return (s0 * (1 - t) + s1 * t) * 1.5f;  // pbrt's extra 1.5 widens the colour range
}

}  // namespace prism
