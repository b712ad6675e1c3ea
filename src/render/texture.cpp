#include "render/texture.h"

#include <cmath>

#include "image/image.h"

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

RGB CheckerboardTexture::Evaluate(const TextureContext &c) const {
    if (dim_ == 3) {
        Vec3d p = mapping_.textureFromRender.Point(Vec3d(c.p));
        long s = long(std::floor(p.x)) + long(std::floor(p.y)) + long(std::floor(p.z));
        return (s % 2 == 0) ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
    }
    Vec2f st = mapping_.Map(c);
    long s = long(std::floor(st.x)) + long(std::floor(st.y));
    return (s % 2 == 0) ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
}

ImageTexture::ImageTexture(TextureMapping mapping, std::shared_ptr<const Image> image,
                           WrapMode wrap, float scale, bool invert)
    : mapping_(mapping), image_(std::move(image)), wrap_(wrap), scale_(scale), invert_(invert) {}

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
    Vec2f st = mapping_.Map(c);
    // Bilinear filter at the finest level (pbrt MIPMap::Bilerp convention: texel centres at +0.5).
    float s = st.x * image_->width - 0.5f, t = st.y * image_->height - 0.5f;
    if (!std::isfinite(s) || !std::isfinite(t)) return RGB(0);
    int s0 = int(std::floor(s)), t0 = int(std::floor(t));
    float ds = s - s0, dt = t - t0;
    RGB v = Texel(s0, t0) * ((1 - ds) * (1 - dt)) + Texel(s0, t0 + 1) * ((1 - ds) * dt) +
            Texel(s0 + 1, t0) * (ds * (1 - dt)) + Texel(s0 + 1, t0 + 1) * (ds * dt);
    v *= scale_;
    if (invert_) v = (RGB(1) - v).Clamped(0.f);
    return v;
}

}  // namespace prism
