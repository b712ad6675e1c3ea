#include "render/mipmap.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "image/image.h"

namespace prism {

namespace {

// pbrt-v3's EWA weights: exp(-alpha r^2) - exp(-alpha) over r^2 in [0, 1], alpha = 2.
constexpr int WeightLUTSize = 128;
const std::array<float, WeightLUTSize> &WeightLUT() {
    static const std::array<float, WeightLUTSize> lut = [] {
        std::array<float, WeightLUTSize> w{};
        const float alpha = 2;
        for (int i = 0; i < WeightLUTSize; ++i) {
            float r2 = float(i) / float(WeightLUTSize - 1);
            w[size_t(i)] = std::exp(-alpha * r2) - std::exp(-alpha);
        }
        return w;
    }();
    return lut;
}

bool Finite(Vec2f v) { return std::isfinite(v.x) && std::isfinite(v.y); }

}  // namespace

MIPMap::MIPMap(std::shared_ptr<const Image> image, TextureWrap wrap)
    : image_(std::move(image)), wrap_(wrap) {
    maxRes_ = float(std::max(image_->width, image_->height));
    int w = image_->width, h = image_->height;
    while (w > 1 || h > 1) {
        const int level = Levels() - 1;  // the level the next one halves
        Level next;
        next.width = std::max(1, (w + 1) / 2);
        next.height = std::max(1, (h + 1) / 2);
        next.texels.resize(size_t(next.width) * size_t(next.height));
        for (int y = 0; y < next.height; ++y)
            for (int x = 0; x < next.width; ++x) {
                // 2x2 box (odd sides: the last texel counts twice).
                int x0 = 2 * x, x1 = std::min(2 * x + 1, w - 1);
                int y0 = 2 * y, y1 = std::min(2 * y + 1, h - 1);
                auto at = [&](int xx, int yy) {
                    if (level == 0) return image_->GetRGB(xx, h - 1 - yy);
                    return levels_.back().texels[size_t(yy) * size_t(w) + size_t(xx)];
                };
                next.texels[size_t(y) * size_t(next.width) + size_t(x)] =
                    (at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1)) * 0.25f;
            }
        w = next.width;
        h = next.height;
        levels_.push_back(std::move(next));
    }
}

size_t MIPMap::Bytes() const {
    size_t n = 0;
    for (const Level &l : levels_) n += l.texels.size() * sizeof(RGB);
    return n;
}

int MIPMap::Width(int level) const {
    return level == 0 ? image_->width : levels_[size_t(level - 1)].width;
}
int MIPMap::Height(int level) const {
    return level == 0 ? image_->height : levels_[size_t(level - 1)].height;
}

RGB MIPMap::Texel(int level, int x, int y) const {
    const int w = Width(level), h = Height(level);
    bool black = false;
    x = WrapTexel(x, w, wrap_.s, &black);
    y = WrapTexel(y, h, wrap_.t, &black);
    if (black) return RGB(0);
    if (level == 0) return image_->GetRGB(x, h - 1 - y);
    return levels_[size_t(level - 1)].texels[size_t(y) * size_t(w) + size_t(x)];
}

RGB MIPMap::Bilerp(int level, Vec2f st) const {
    level = Clamp(level, 0, Levels() - 1);
    // The same operations as the unfiltered ImageTexture lookup.
    float s = st.x * Width(level) - 0.5f, t = st.y * Height(level) - 0.5f;
    if (!std::isfinite(s) || !std::isfinite(t)) return RGB(0);
    s = ClampTexelCoord(s);
    t = ClampTexelCoord(t);
    int s0 = int(std::floor(s)), t0 = int(std::floor(t));
    float ds = s - s0, dt = t - t0;
    return Texel(level, s0, t0) * ((1 - ds) * (1 - dt)) +
           Texel(level, s0, t0 + 1) * ((1 - ds) * dt) + Texel(level, s0 + 1, t0) * (ds * (1 - dt)) +
           Texel(level, s0 + 1, t0 + 1) * (ds * dt);
}

RGB MIPMap::Nearest(Vec2f st) const {
    float s = st.x * Width(0), t = st.y * Height(0);
    if (!std::isfinite(s) || !std::isfinite(t)) return RGB(0);
    return Texel(0, int(std::floor(ClampTexelCoord(s))), int(std::floor(ClampTexelCoord(t))));
}

RGB MIPMap::Trilinear(Vec2f st, float width) const {
    // pbrt-v3: level = Levels() - 1 + log2(width) for a power-of-two pyramid, i.e. the level
    // where one texel is `width` wide.
    float level = std::log2(std::max(width * maxRes_, 1e-8f));
    if (!(level > 0)) return Bilerp(0, st);
    if (level >= float(Levels() - 1)) return Texel(Levels() - 1, 0, 0);
    int i = int(std::floor(level));
    float delta = level - float(i);
    return Bilerp(i, st) * (1 - delta) + Bilerp(i + 1, st) * delta;
}

RGB MIPMap::EWA(Vec2f st, Vec2f dst0, Vec2f dst1, float maxAnisotropy) const {
    if (!Finite(dst0) || !Finite(dst1)) return Bilerp(0, st);
    auto len2 = [](Vec2f v) { return v.x * v.x + v.y * v.y; };
    if (len2(dst0) < len2(dst1)) std::swap(dst0, dst1);
    const float major = std::sqrt(len2(dst0));
    float minor = std::sqrt(len2(dst1));
    // Clamp the eccentricity: widen the minor axis (blurs rather than aliases).
    if (minor * maxAnisotropy < major && minor > 0) {
        float scale = major / (minor * maxAnisotropy);
        dst1 = dst1 * scale;
        minor *= scale;
    }
    if (minor == 0) return Bilerp(0, st);
    // Magnification: a footprint no wider than a texel of level 0 reads level 0 bilinearly
    // (so a texture seen at one texel per pixel is unchanged); from one to two texels wide
    // the EWA average fades in.
    const float texels = 2 * major * maxRes_;
    if (!(texels > 1)) return Bilerp(0, st);
    // At most the coarsest level (EWALevel reads its one texel): a footprint of 1e20 makes
    // minor infinite, whose floor is no int.
    float lod = std::min(std::max(0.f, std::log2(minor * maxRes_)), float(Levels()));
    int i = int(std::floor(lod));
    float delta = lod - float(i);
    RGB v = delta == 0 ? EWALevel(i, st, dst0, dst1)
                       : EWALevel(i, st, dst0, dst1) * (1 - delta) +
                             EWALevel(i + 1, st, dst0, dst1) * delta;
    if (texels < 2) {
        const float f = texels - 1;
        v = Bilerp(0, st) * (1 - f) + v * f;
    }
    return v;
}

RGB MIPMap::EWALevel(int level, Vec2f st, Vec2f dst0, Vec2f dst1) const {
    if (level >= Levels()) return Texel(Levels() - 1, 0, 0);
    const float w = float(Width(level)), h = float(Height(level));
    const float s = st.x * w - 0.5f, t = st.y * h - 0.5f;
    if (!std::isfinite(s) || !std::isfinite(t)) return RGB(0);
    dst0 = {dst0.x * w, dst0.y * h};
    dst1 = {dst1.x * w, dst1.y * h};
    // The ellipse A s^2 + B s t + C t^2 < 1 (pbrt-v3, with 1 added for the texel's own size).
    float A = dst0.y * dst0.y + dst1.y * dst1.y + 1;
    float B = -2 * (dst0.x * dst0.y + dst1.x * dst1.y);
    float C = dst0.x * dst0.x + dst1.x * dst1.x + 1;
    const float invF = 1 / (A * C - B * B * 0.25f);
    A *= invF;
    B *= invF;
    C *= invF;
    const float det = -B * B + 4 * A * C, invDet = 1 / det;
    const float uSqrt = std::sqrt(det * C), vSqrt = std::sqrt(A * det);
    const float su = 2 * invDet * uSqrt, sv = 2 * invDet * vSqrt;
    // The ellipse spans at most about maxanisotropy texels (the level is chosen for its minor
    // axis); anything wider (coordinates so large that s - su rounds) is read bilinearly.
    if (!std::isfinite(su) || !std::isfinite(sv) || !(std::abs(s) < 1073741824.f) ||
        !(std::abs(t) < 1073741824.f) || su > 4096 || sv > 4096)
        return Bilerp(level, st);
    const int s0 = int(std::ceil(s - su)), s1 = int(std::floor(s + su));
    const int t0 = int(std::ceil(t - sv)), t1 = int(std::floor(t + sv));
    const auto &lut = WeightLUT();
    RGB sum;
    float sumWts = 0;
    for (int it = t0; it <= t1; ++it) {
        const float tt = float(it) - t;
        for (int is = s0; is <= s1; ++is) {
            const float ss = float(is) - s;
            const float r2 = A * ss * ss + B * ss * tt + C * tt * tt;
            if (r2 < 1) {
                const float weight =
                    lut[size_t(std::min(int(r2 * WeightLUTSize), WeightLUTSize - 1))];
                sum += Texel(level, is, it) * weight;
                sumWts += weight;
            }
        }
    }
    if (!(sumWts > 0)) return Bilerp(level, st);
    return sum / sumWts;
}

}  // namespace prism
