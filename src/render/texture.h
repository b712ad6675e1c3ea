// Textures (pbrt-v3 §10): constant, scale, mix, checkerboard (2-D and 3-D) and imagemap, with
// the uv / spherical / cylindrical / planar mappings. Float textures are RGB textures whose
// channels are equal; materials read .r for float parameters.
#pragma once

#include <memory>
#include <string>

#include "core/color.h"
#include "core/transform.h"
#include "core/vecmath.h"

namespace prism {

struct Image;

struct TextureContext {
    Vec2f uv;
    Vec3f p;  // render-space hit point (for 3-D textures and non-uv mappings)
};

class Texture {
public:
    virtual ~Texture() = default;
    virtual RGB Evaluate(const TextureContext &ctx) const = 0;
    virtual bool IsConstant() const { return false; }
};
using TexturePtr = std::shared_ptr<const Texture>;

class ConstantTexture final : public Texture {
public:
    explicit ConstantTexture(RGB v) : value_(v) {}
    RGB Evaluate(const TextureContext &) const override { return value_; }
    bool IsConstant() const override { return true; }
    RGB Value() const { return value_; }

private:
    RGB value_;
};

struct TextureMapping {
    enum class Kind { UV, Spherical, Cylindrical, Planar } kind = Kind::UV;
    float su = 1, sv = 1, du = 0, dv = 0;
    Vec3f v1{1, 0, 0}, v2{0, 1, 0};
    Transform textureFromRender;
    Vec2f Map(const TextureContext &ctx) const;
};

class ScaleTexture final : public Texture {
public:
    ScaleTexture(TexturePtr a, TexturePtr b) : a_(std::move(a)), b_(std::move(b)) {}
    RGB Evaluate(const TextureContext &c) const override { return a_->Evaluate(c) * b_->Evaluate(c); }

private:
    TexturePtr a_, b_;
};

class MixTexture final : public Texture {
public:
    MixTexture(TexturePtr a, TexturePtr b, TexturePtr amount)
        : a_(std::move(a)), b_(std::move(b)), amount_(std::move(amount)) {}
    RGB Evaluate(const TextureContext &c) const override {
        float t = amount_->Evaluate(c).r;
        return a_->Evaluate(c) * (1 - t) + b_->Evaluate(c) * t;
    }

private:
    TexturePtr a_, b_, amount_;
};

class CheckerboardTexture final : public Texture {
public:
    CheckerboardTexture(TextureMapping mapping, TexturePtr tex1, TexturePtr tex2, int dimension)
        : mapping_(mapping), tex1_(std::move(tex1)), tex2_(std::move(tex2)), dim_(dimension) {}
    RGB Evaluate(const TextureContext &c) const override;

private:
    TextureMapping mapping_;
    TexturePtr tex1_, tex2_;
    int dim_;
};

enum class WrapMode { Repeat, Black, Clamp };

// Bilinear lookup in a linear-RGB image; t = 0 is the bottom row (pbrt flips images in y).
class ImageTexture final : public Texture {
public:
    ImageTexture(TextureMapping mapping, std::shared_ptr<const Image> image, WrapMode wrap,
                 float scale, bool invert);
    RGB Evaluate(const TextureContext &c) const override;

private:
    RGB Texel(int x, int y) const;
    TextureMapping mapping_;
    std::shared_ptr<const Image> image_;
    WrapMode wrap_;
    float scale_;
    bool invert_;
};

}  // namespace prism
