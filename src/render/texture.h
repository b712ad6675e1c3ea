// Textures (pbrt-v3 §10): constant, scale, mix, checkerboard (2-D and 3-D), imagemap, bilerp,
// uv, dots and the noise textures fbm, wrinkled, windy and marble, pbrt-v4's directionmix,
// with the uv / spherical /
// cylindrical / planar mappings. Float textures are RGB textures whose channels are equal;
// materials read .r for float parameters.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/color.h"
#include "core/params.h"
#include "core/transform.h"
#include "core/vecmath.h"

namespace prism {

struct Image;
struct SurfaceInteraction;

struct TextureContext {
    Vec2f uv;
    Vec3f p;    // render-space hit point (for 3-D textures and non-uv mappings)
    Vec2f uv1;  // the second texture coordinate set (SurfaceInteraction::uv1; glTF TEXCOORD_1)
    // The footprint of the pixel sample (pbrt-v3 ComputeDifferentials, render/differentials.h):
    // how p and (u, v) change from one pixel to the next. All zero where the ray carries no
    // differentials; filtered lookups then read the finest level, bilinearly.
    Vec3f dpdx{}, dpdy{};
    float dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
    Vec3f n{};  // the unit geometric normal (directionmix); zero where there is no surface
};

// The context of a surface hit: its uv, p, uv1 and normal, without a footprint.
TextureContext SurfaceTextureContext(const SurfaceInteraction &si);

class Texture {
  public:
    virtual ~Texture() = default;
    virtual RGB Evaluate(const TextureContext &ctx) const = 0;
    virtual bool IsConstant() const { return false; }
    // Whether Evaluate reads the footprint (filtered image lookups, closed-form checkerboard),
    // itself or through a texture it reads: only then do rays carry differentials.
    virtual bool UsesDifferentials() const { return false; }
};
using TexturePtr = std::shared_ptr<const Texture>;

// A float texture's value (float textures keep it in every channel).
inline float EvalFloat(const TexturePtr &t, const TextureContext &tc) { return t->Evaluate(tc).r; }

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
    // The same with the footprint in (s, t) (pbrt-v3 TextureMapping2D::Map with dstdx, dstdy).
    Vec2f Map(const TextureContext &ctx, Vec2f *dstdx, Vec2f *dstdy) const;
};

// 3-D textures read the hit point in texture space: the inverse of the CTM at the Texture
// directive (as pbrt-v4 does; pbrt-v3 applied the CTM itself), composed with world-from-render.
struct TextureMapping3D {
    Transform textureFromRender;
    Vec3f Map(const TextureContext &ctx) const;
};

// pbrt-v4 DirectionMixTexture: tex1 where the normal is along `dir` (render space, unit),
// tex2 where it is perpendicular; the weight of tex1 is |n . dir|.
class DirectionMixTexture final : public Texture {
  public:
    DirectionMixTexture(TexturePtr tex1, TexturePtr tex2, Vec3f dir)
        : tex1_(std::move(tex1)), tex2_(std::move(tex2)), dir_(dir) {}
    RGB Evaluate(const TextureContext &c) const override {
        const float amount = std::min(std::abs(Dot(c.n, dir_)), 1.f);
        RGB v(0);
        if (amount != 0) v = tex1_->Evaluate(c) * amount;
        if (amount != 1) v = v + tex2_->Evaluate(c) * (1 - amount);
        return v;
    }
    bool UsesDifferentials() const override {
        return tex1_->UsesDifferentials() || tex2_->UsesDifferentials();
    }

  private:
    TexturePtr tex1_, tex2_;
    Vec3f dir_;
};

class ScaleTexture final : public Texture {
  public:
    ScaleTexture(TexturePtr a, TexturePtr b) : a_(std::move(a)), b_(std::move(b)) {}
    RGB Evaluate(const TextureContext &c) const override {
        return a_->Evaluate(c) * b_->Evaluate(c);
    }
    bool UsesDifferentials() const override {
        return a_->UsesDifferentials() || b_->UsesDifferentials();
    }

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
    bool UsesDifferentials() const override {
        return a_->UsesDifferentials() || b_->UsesDifferentials() || amount_->UsesDifferentials();
    }

  private:
    TexturePtr a_, b_, amount_;
};

// pbrt-v3 Checkerboard2DTexture / Checkerboard3DTexture. 2-D boards antialias with "aamode":
// ClosedForm (pbrt-v3's default) averages the two textures over the box the footprint spans
// (closed form of the box-filtered checkerboard); None point-samples.
class CheckerboardTexture final : public Texture {
  public:
    enum class AAMode { None, ClosedForm };
    CheckerboardTexture(TextureMapping mapping, TexturePtr tex1, TexturePtr tex2, int dimension,
                        AAMode aa = AAMode::None)
        : mapping_(mapping),
          tex1_(std::move(tex1)),
          tex2_(std::move(tex2)),
          dim_(dimension),
          aa_(dimension == 2 ? aa : AAMode::None) {}
    RGB Evaluate(const TextureContext &c) const override;
    bool UsesDifferentials() const override {
        return aa_ == AAMode::ClosedForm || tex1_->UsesDifferentials() ||
               tex2_->UsesDifferentials();
    }
    // The fraction of tex2 (the odd squares) over [s0, s1] x [t0, t1] around (s, t), ds and dt
    // the half-widths (pbrt-v3's closed form; exposed for the tests).
    static float OddFraction(float s, float t, float ds, float dt);

  private:
    TextureMapping mapping_;
    TexturePtr tex1_, tex2_;
    int dim_;
    AAMode aa_;
};

// How an image texture's lookups outside [0, 1] wrap, per axis: pbrt's repeat, black and clamp,
// and glTF's MIRRORED_REPEAT (mirror: every other tile reflected).
enum class WrapMode { Repeat, Black, Clamp, Mirror };
struct TextureWrap {
    WrapMode s = WrapMode::Repeat, t = WrapMode::Repeat;
    constexpr TextureWrap() = default;
    constexpr TextureWrap(WrapMode both) : s(both), t(both) {}  // NOLINT: one mode for both
    constexpr TextureWrap(WrapMode s_, WrapMode t_) : s(s_), t(t_) {}
    bool operator<(const TextureWrap &o) const { return s != o.s ? s < o.s : t < o.t; }
};
// Texel x of a row of n under `wrap`; *black set for a black border's outside texels.
int WrapTexel(int x, int n, WrapMode wrap, bool *black);
class MIPMap;

// How an image texture is looked up (pbrt's imagemap "filter"): Point (nearest texel of the
// finest level), Bilinear (finest level), Trilinear (pbrt-v3 MIPMap::Lookup with the isotropic
// width) and EWA (pbrt-v3's elliptically weighted average over two levels, the default).
enum class TextureFilter { Point, Bilinear, Trilinear, EWA };
const char *TextureFilterName(TextureFilter f);

// A lookup in a linear-RGB image; t = 0 is the bottom row (pbrt flips images in y). Trilinear
// and EWA read the MIP pyramid `mip` (render/mipmap.h) built from the image.
class ImageTexture final : public Texture {
  public:
    ImageTexture(TextureMapping mapping, std::shared_ptr<const Image> image, TextureWrap wrap,
                 float scale, bool invert, TextureFilter filter = TextureFilter::Bilinear,
                 std::shared_ptr<const MIPMap> mip = nullptr, float maxAnisotropy = 8);
    RGB Evaluate(const TextureContext &c) const override;
    bool UsesDifferentials() const override { return mip_ != nullptr; }
    TextureFilter Filter() const { return filter_; }

  private:
    RGB Texel(int x, int y) const;
    TextureMapping mapping_;
    std::shared_ptr<const Image> image_;
    TextureWrap wrap_;
    float scale_;
    bool invert_;
    TextureFilter filter_;
    std::shared_ptr<const MIPMap> mip_;
    float maxAnisotropy_;
};

// pbrt-v3 BilerpTexture: bilinear interpolation of four corner values over (s, t), which is
// not wrapped (values extrapolate outside [0, 1]^2).
class BilerpTexture final : public Texture {
  public:
    BilerpTexture(TextureMapping mapping, RGB v00, RGB v01, RGB v10, RGB v11)
        : mapping_(mapping), v00_(v00), v01_(v01), v10_(v10), v11_(v11) {}
    RGB Evaluate(const TextureContext &c) const override;

  private:
    TextureMapping mapping_;
    RGB v00_, v01_, v10_, v11_;
};

// pbrt-v3 UVTexture: (frac(s), frac(t), 0), for checking parameterizations.
class UVTexture final : public Texture {
  public:
    explicit UVTexture(TextureMapping mapping) : mapping_(mapping) {}
    RGB Evaluate(const TextureContext &c) const override;

  private:
    TextureMapping mapping_;
};

// pbrt-v3 DotsTexture: polka dots of radius 0.35 on the unit (s, t) grid, each cell's dot
// present and jittered according to Perlin noise.
class DotsTexture final : public Texture {
  public:
    DotsTexture(TextureMapping mapping, TexturePtr inside, TexturePtr outside)
        : mapping_(mapping), inside_(std::move(inside)), outside_(std::move(outside)) {}
    RGB Evaluate(const TextureContext &c) const override;
    bool UsesDifferentials() const override {
        return inside_->UsesDifferentials() || outside_->UsesDifferentials();
    }

  private:
    TextureMapping mapping_;
    TexturePtr inside_, outside_;
};

// pbrt-v3's noise textures over the 3-D texture-space point (see render/noise.h).
class NoiseTexture final : public Texture {
  public:
    enum class Kind { FBm, Wrinkled, Windy };
    NoiseTexture(Kind kind, TextureMapping3D mapping, int octaves, float omega)
        : kind_(kind), mapping_(mapping), octaves_(octaves), omega_(omega) {}
    RGB Evaluate(const TextureContext &c) const override;

  private:
    Kind kind_;
    TextureMapping3D mapping_;
    int octaves_;
    float omega_;
};

// pbrt-v3 MarbleTexture: sin(p.y + variation·FBm) through a Bézier spline of marble colours.
class MarbleTexture final : public Texture {
  public:
    MarbleTexture(TextureMapping3D mapping, int octaves, float omega, float scale, float variation)
        : mapping_(mapping),
          octaves_(octaves),
          omega_(omega),
          scale_(scale),
          variation_(variation) {}
    RGB Evaluate(const TextureContext &c) const override;

  private:
    TextureMapping3D mapping_;
    int octaves_;
    float omega_, scale_, variation_;
};

// A Texture directive's parameters as a texture's Create reads them: core/params.h's plus
// texture-valued parameters, spectra, the mappings, and image loading for image maps.
class TextureParams : public Params {
  public:
    // Of 8- and 16-bit images: Auto by the file type, Gamma v^gamma (LoadImage's gamma).
    enum class Encoding { Auto, SRGB, Linear, Gamma };
    virtual bool IsFloat() const = 0;             // a "float" (not "spectrum") texture
    virtual const std::string &Name() const = 0;  // the texture's name, for messages
    // A texture-valued parameter ("tex1", "amount"): a named texture of that kind, or a value,
    // else def.
    virtual TexturePtr Tex(const char *name, bool isFloat, RGB def) const = 0;
    virtual RGB Spectrum(const char *name, RGB def) const = 0;
    // A "vector" parameter as written (in the texture's space), else def.
    virtual Vec3f Vector(const char *name, Vec3f def) const = 0;
    // pbrt's 2-D mapping ("mapping", "uscale", ...) and the texture space of 3-D textures.
    virtual TextureMapping Mapping() const = 0;
    virtual TextureMapping3D Mapping3D() const = 0;
    // The image parameter `param` names (relative to the scene, cached, within the memory
    // budget), a charge to the budget for a copy of it, its MIP pyramid (cached), and the
    // lookup filter the command line and the texture ask for.
    virtual std::shared_ptr<const Image> LoadImage(const char *param, const std::string &file,
                                                   Encoding enc, float gamma) const = 0;
    virtual void Charge(size_t bytes, const std::string &what, const char *param) const = 0;
    virtual std::shared_ptr<const MIPMap> Mip(const std::shared_ptr<const Image> &image,
                                              TextureWrap wrap, const std::string &file,
                                              const char *param) const = 0;
    virtual TextureFilter Filter() const = 0;
    // --texture-filter none or point: no texture filters over the footprint.
    virtual bool FootprintFilteringOff() const = 0;
    // Marks `name` read, naming it once with `why` ("accepted, not simulated").
    virtual void WarnIgnored(const char *name, const std::string &why) const = 0;
    virtual void MarkAllUsed() const = 0;
};

// The texture class registered as `type` (texture_list.inc): the texture, or null when the
// class is unknown (*known false) or its Create ignored the directive after a warning. Throws
// SceneError for bad parameters.
TexturePtr CreateTexture(const std::string &type, const TextureParams &params, const FileLoc &loc,
                         bool *known);

}  // namespace prism
