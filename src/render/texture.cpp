#include "render/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "geometry/interaction.h"
#include "image/image.h"
#include "render/mipmap.h"
#include "render/noise.h"

namespace prism {

TextureContext SurfaceTextureContext(const SurfaceInteraction &si) {
    TextureContext tc{si.uv, si.p, si.uv1};
    tc.n = si.n;
    return tc;
}

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
        if (!(d > 0)) return OddFloor(x) ? 1.f : 0.f;
        return (BumpInt(x + d) - BumpInt(x - d)) / (2 * d);
    };
    const float sint = axis(s, ds), tint = axis(t, dt);
    // A square is odd where exactly one of the two axes is.
    return sint + tint - 2 * sint * tint;
}

RGB CheckerboardTexture::Evaluate(const TextureContext &c) const {
    if (dim_ == 3) {
        Vec3d p = mapping_.textureFromRender.Point(Vec3d(c.p));
        // The parity of floor(x) + floor(y) + floor(z), for coordinates of any size.
        const bool odd = OddFloor(p.x) != OddFloor(p.y) ? !OddFloor(p.z) : OddFloor(p.z);
        return !odd ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
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
    return OddFloor(st.x) == OddFloor(st.y) ? tex1_->Evaluate(c) : tex2_->Evaluate(c);
}

int WrapTexel(int x, int n, WrapMode wrap, bool *black) {
    switch (wrap) {
        case WrapMode::Repeat:
            return ((x % n) + n) % n;
        case WrapMode::Mirror: {
            // Period 2n: texels 0 .. n-1, then n-1 .. 0 (in 64 bits: 2n may not fit an int).
            const int64_t period = 2 * int64_t(n);
            const int64_t m = ((int64_t(x) % period) + period) % period;
            return int(m < n ? m : period - 1 - m);
        }
        case WrapMode::Clamp:
            return Clamp(x, 0, n - 1);
        case WrapMode::Black:
            if (x < 0 || x >= n) *black = true;
            return Clamp(x, 0, n - 1);
    }
    return x;
}

ImageTexture::ImageTexture(TextureMapping mapping, std::shared_ptr<const Image> image,
                           TextureWrap wrap, float scale, bool invert, TextureFilter filter,
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
    const int w = image_->width, h = image_->height;
    bool black = false;
    x = WrapTexel(x, w, wrap_.s, &black);
    y = WrapTexel(y, h, wrap_.t, &black);
    if (black) return RGB(0);
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
        s = ClampTexelCoord(s);
        t = ClampTexelCoord(t);
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

// Creates, one per texture class (texture_list.inc), pbrt-v3's names and defaults.

namespace {

TexturePtr Constant(RGB v) { return std::make_shared<ConstantTexture>(v); }

// A float variant pbrt-v3 lacks: ignored after a warning.
TexturePtr SpectrumOnly(const TextureParams &p, const FileLoc &loc, const char *type) {
    p.Warn(loc, std::string("texture class \"") + type +
                    "\" has no float variant (as in pbrt-v3); texture " + Quote(p.Name()) +
                    " is ignored");
    p.MarkAllUsed();
    return nullptr;
}

int Octaves(const TextureParams &p, const std::string &type) {
    const int n = p.Int("octaves", 8);
    if (n < 0 || n > 32) throw SceneError(p.Loc("octaves"), type + " octaves must be 0 to 32");
    return n;
}

}  // namespace

// Texture "constant" (texture_list.inc). Parameters:
//   value  texture  1  the value everywhere
TexturePtr CreateConstantTexture(const TextureParams &p, const FileLoc &) {
    return p.Tex("value", p.IsFloat(), RGB(1));
}

// Texture "scale" (texture_list.inc). Parameters:
//   tex1, tex2  texture        1  the product tex1 tex2
//   tex         texture        1  (v4, without tex1 and tex2) times scale
//   scale       float texture  1  (v4) the factor
TexturePtr CreateScaleTexture(const TextureParams &p, const FileLoc &) {
    const bool f = p.IsFloat();
    if (!p.Has("tex1") && !p.Has("tex2") && (p.Has("tex") || p.Has("scale")))
        return std::make_shared<ScaleTexture>(p.Tex("tex", f, RGB(1)),
                                              p.Tex("scale", true, RGB(1)));
    return std::make_shared<ScaleTexture>(p.Tex("tex1", f, RGB(1)), p.Tex("tex2", f, RGB(1)));
}

// Texture "mix" (texture_list.inc). Parameters:
//   tex1    texture        0    the value at amount 0
//   tex2    texture        1    the value at amount 1
//   amount  float texture  0.5  the blend
TexturePtr CreateMixTexture(const TextureParams &p, const FileLoc &) {
    const bool f = p.IsFloat();
    return std::make_shared<MixTexture>(p.Tex("tex1", f, RGB(0)), p.Tex("tex2", f, RGB(1)),
                                        p.Tex("amount", true, RGB(0.5f)));
}

// Texture "directionmix" (pbrt-v4; texture_list.inc). Parameters:
//   tex1  texture  0      the value where the surface's normal is along dir
//   tex2  texture  1      the value where it is perpendicular to dir
//   dir   vector   0 1 0  the direction, in the texture's space (the transform at the
//                         Texture directive), normalized; the weight of tex1 is |n . dir|
TexturePtr CreateDirectionMixTexture(const TextureParams &p, const FileLoc &loc) {
    const bool f = p.IsFloat();
    const Vec3f d = p.Vector("dir", Vec3f(0, 1, 0));
    const Vec3f dir = Vec3f(p.Mapping3D().textureFromRender.Inverse().Vector(Vec3d(d)));
    const float len = Length(dir);
    if (!(len > 0) || !std::isfinite(len))
        throw SceneError(p.Has("dir") ? p.Loc("dir") : loc,
                         "directionmix \"dir\" must be a nonzero, finite vector");
    return std::make_shared<DirectionMixTexture>(p.Tex("tex1", f, RGB(0)), p.Tex("tex2", f, RGB(1)),
                                                 dir / len);
}

// Texture "checkerboard" (texture_list.inc). Parameters:
//   dimension               integer        2        2 (over the 2-D mapping) or 3 (in the
//                                                   texture's space, point-sampled)
//   tex1, tex2              texture        1, 0     the two squares
//   aamode                  string         "closedform"  closedform box-filters a 2-D board over
//                                                   the ray's footprint; none point-samples
//   mapping                 string         "uv"     uv | spherical | cylindrical | planar
//   uscale, vscale          float          1        the 2-D mapping's scales (read by the
//                                                   assembly, assembly/textures.cpp)
//   udelta, vdelta          float          0        its offsets
//   v1, v2                  vector         1 0 0, 0 1 0  the planar mapping's axes
TexturePtr CreateCheckerboardTexture(const TextureParams &p, const FileLoc &loc) {
    const int dim = p.Int("dimension", 2);
    if (dim != 2 && dim != 3) throw SceneError(loc, "checkerboard dimension must be 2 or 3");
    auto aa = CheckerboardTexture::AAMode::ClosedForm;
    const std::string aamode = p.String("aamode", "closedform");
    if (aamode == "none")
        aa = CheckerboardTexture::AAMode::None;
    else if (aamode != "closedform")
        p.Warn(p.Loc("aamode"),
               "unknown checkerboard aamode " + Quote(aamode) + "; using \"closedform\"");
    if (p.FootprintFilteringOff()) aa = CheckerboardTexture::AAMode::None;
    const bool f = p.IsFloat();
    return std::make_shared<CheckerboardTexture>(p.Mapping(), p.Tex("tex1", f, RGB(1)),
                                                 p.Tex("tex2", f, RGB(0)), dim, aa);
}

// Texture "imagemap" (texture_list.inc). Parameters:
//   filename                string         ""       the image, relative to the scene; required
//   wrap                    string         "repeat"  repeat | black | clamp | mirror (a Prism
//                                                   extension: glTF's MIRRORED_REPEAT)
//   wraps, wrapt            string         (wrap)   Prism: the wrap along s or t alone (glTF's
//                                                   wrapS, wrapT)
//   scale                   float          1        multiplies the texels
//   invert                  bool           false    1 - the texel
//   gamma                   bool           —        true: sRGB, false: linear (default: sRGB for
//                                                   8-bit files)
//   encoding                string         —        (v4) "sRGB", "linear" or "gamma G" (v^G)
//   filter                  string         "ewa"    ewa | trilinear | bilinear | point
//   trilinear               bool           false    (v3) trilinear instead of EWA
//   maxanisotropy           float          8        EWA's longest ellipse axis over its shortest
//   channel                 string         "luminance"  float textures: luminance | alpha |
//                                                   alphaorluminance (a Prism extension)
//   mapping                 string         "uv"     uv | spherical | cylindrical | planar
//   uscale, vscale          float          1        the 2-D mapping's scales (read by the
//                                                   assembly, assembly/textures.cpp)
//   udelta, vdelta          float          0        its offsets
//   v1, v2                  vector         1 0 0, 0 1 0  the planar mapping's axes
TexturePtr CreateImageTexture(const TextureParams &p, const FileLoc &loc) {
    const std::string file = p.String("filename", "");
    if (file.empty()) throw SceneError(loc, "imagemap texture needs a \"filename\"");
    auto wrapMode = [&](const char *param, WrapMode def) {
        if (!p.Has(param)) return def;
        const std::string name = p.String(param, "");
        if (name == "repeat") return WrapMode::Repeat;
        if (name == "black") return WrapMode::Black;
        if (name == "clamp") return WrapMode::Clamp;
        if (name == "mirror") return WrapMode::Mirror;
        p.Warn(p.Loc(param), "unknown wrap mode " + Quote(name) + "; using repeat");
        return WrapMode::Repeat;
    };
    const WrapMode both = wrapMode("wrap", WrapMode::Repeat);
    const TextureWrap wrap(wrapMode("wraps", both), wrapMode("wrapt", both));
    using Enc = TextureParams::Encoding;
    Enc enc = Enc::Auto;
    if (p.Has("gamma")) enc = p.Bool("gamma", false) ? Enc::SRGB : Enc::Linear;
    const std::string encoding = p.String("encoding", "");
    float gamma = 1;
    if (encoding == "sRGB") {
        enc = Enc::SRGB;
    } else if (encoding == "linear") {
        enc = Enc::Linear;
    } else if (encoding == "gamma" || encoding.rfind("gamma ", 0) == 0) {
        // pbrt-v4's "gamma G": an 8- or 16-bit value v in [0, 1] means v^G.
        const std::string g = encoding.size() > 6 ? encoding.substr(6) : "";
        char *end = nullptr;
        gamma = std::strtof(g.c_str(), &end);
        if (g.empty() || *end != '\0' || !(gamma > 0) || !std::isfinite(gamma))
            throw SceneError(p.Loc("encoding"), "imagemap \"encoding\" " + Quote(encoding) +
                                                    ": the gamma must be a positive number");
        enc = Enc::Gamma;
    } else if (!encoding.empty()) {
        p.WarnIgnored("encoding", "only \"sRGB\", \"linear\" and \"gamma G\" are read");
    }
    const TextureFilter filter = p.Filter();
    float maxAniso = p.Float("maxanisotropy", 8.f);
    if (!(maxAniso >= 1)) {
        p.Warn(p.Loc("maxanisotropy"), "maxanisotropy below 1; using 1");
        maxAniso = 1;
    }
    // An EWA lookup reads about maxanisotropy^2 texels around its minor axis: a huge value would
    // make one lookup read millions.
    if (maxAniso > kMaxAnisotropy) {
        p.Warn(p.Loc("maxanisotropy"), "maxanisotropy above " +
                                           std::to_string(int(kMaxAnisotropy)) + "; using " +
                                           std::to_string(int(kMaxAnisotropy)));
        maxAniso = kMaxAnisotropy;
    }
    std::shared_ptr<const Image> img = p.LoadImage("filename", file, enc, gamma);
    // Prism extension for cut-outs (glTF baseColor alpha, OBJ map_d): a float texture of the
    // image's "alpha" channel (1 without one), or "alphaorluminance".
    const bool f = p.IsFloat();
    const std::string channel = f ? p.String("channel", "luminance") : "luminance";
    if (channel != "luminance" && channel != "alpha" && channel != "alphaorluminance")
        throw SceneError(p.Loc("channel"),
                         "imagemap \"channel\" must be \"luminance\", \"alpha\" or "
                         "\"alphaorluminance\", not " +
                             Quote(channel));
    if (channel != "luminance" && (img->HasAlpha() || channel == "alpha")) {
        p.Charge(img->pixels.size() * sizeof(float), "texture " + Quote(file), "filename");
        auto a = std::make_shared<Image>(*img);
        const int ac = img->channels == 2 ? 1 : 3;
        for (int y = 0; y < a->height; ++y)
            for (int x = 0; x < a->width; ++x)
                a->SetRGB(x, y, RGB(img->HasAlpha() ? img->At(x, y, ac) : 1.f));
        img = a;
    } else if (f && img->channels >= 3) {
        // pbrt converts RGB texels of float textures to luminance, in a copy.
        p.Charge(img->pixels.size() * sizeof(float), "texture " + Quote(file), "filename");
        auto lum = std::make_shared<Image>(*img);
        for (int y = 0; y < lum->height; ++y)
            for (int x = 0; x < lum->width; ++x)
                lum->SetRGB(x, y, RGB(img->GetRGB(x, y).Luminance()));
        img = lum;
    }
    std::shared_ptr<const MIPMap> mip;
    if (filter == TextureFilter::Trilinear || filter == TextureFilter::EWA)
        mip = p.Mip(img, wrap, file, "filename");
    return std::make_shared<ImageTexture>(p.Mapping(), img, wrap, p.Float("scale", 1.f),
                                          p.Bool("invert", false), filter, mip, maxAniso);
}

// Texture "bilerp" (texture_list.inc). Parameters:
//   v00, v01, v10, v11      texture        0, 1, 0, 1  the corner values, bilinear between
//   mapping                 string         "uv"     uv | spherical | cylindrical | planar
//   uscale, vscale          float          1        the 2-D mapping's scales (read by the
//                                                   assembly, assembly/textures.cpp)
//   udelta, vdelta          float          0        its offsets
//   v1, v2                  vector         1 0 0, 0 1 0  the planar mapping's axes
TexturePtr CreateBilerpTexture(const TextureParams &p, const FileLoc &) {
    auto v = [&](const char *n, float d) {
        return p.IsFloat() ? RGB(p.Float(n, d)) : p.Spectrum(n, RGB(d));
    };
    return std::make_shared<BilerpTexture>(p.Mapping(), v("v00", 0), v("v01", 1), v("v10", 0),
                                           v("v11", 1));
}

// Texture "uv" (texture_list.inc; spectrum only): (s, t, 0) of the 2-D mapping. Parameters:
//   mapping                 string         "uv"     uv | spherical | cylindrical | planar
//   uscale, vscale          float          1        the 2-D mapping's scales (read by the
//                                                   assembly, assembly/textures.cpp)
//   udelta, vdelta          float          0        its offsets
//   v1, v2                  vector         1 0 0, 0 1 0  the planar mapping's axes
TexturePtr CreateUVTexture(const TextureParams &p, const FileLoc &loc) {
    if (p.IsFloat()) return SpectrumOnly(p, loc, "uv");
    return std::make_shared<UVTexture>(p.Mapping());
}

// Texture "dots" (texture_list.inc). Parameters:
//   inside, outside         texture        1, 0     the dots and the rest
//   mapping                 string         "uv"     uv | spherical | cylindrical | planar
//   uscale, vscale          float          1        the 2-D mapping's scales (read by the
//                                                   assembly, assembly/textures.cpp)
//   udelta, vdelta          float          0        its offsets
//   v1, v2                  vector         1 0 0, 0 1 0  the planar mapping's axes
TexturePtr CreateDotsTexture(const TextureParams &p, const FileLoc &) {
    const bool f = p.IsFloat();
    return std::make_shared<DotsTexture>(p.Mapping(), p.Tex("inside", f, RGB(1)),
                                         p.Tex("outside", f, RGB(0)));
}

// Texture "fbm" (texture_list.inc): Perlin noise in the texture's space. Parameters:
//   octaves    integer  8    0 to 32
//   roughness  float    0.5  each octave's share of the one before
TexturePtr CreateFBmTexture(const TextureParams &p, const FileLoc &) {
    const int n = Octaves(p, "fbm");
    return std::make_shared<NoiseTexture>(NoiseTexture::Kind::FBm, p.Mapping3D(), n,
                                          p.Float("roughness", .5f));
}

// Texture "wrinkled" (texture_list.inc): the absolute value of fbm's noise. Parameters:
//   octaves    integer  8    0 to 32
//   roughness  float    0.5  each octave's share of the one before
TexturePtr CreateWrinkledTexture(const TextureParams &p, const FileLoc &) {
    const int n = Octaves(p, "wrinkled");
    return std::make_shared<NoiseTexture>(NoiseTexture::Kind::Wrinkled, p.Mapping3D(), n,
                                          p.Float("roughness", .5f));
}

// "windy": pbrt-v3's windy waves (no parameters).
TexturePtr CreateWindyTexture(const TextureParams &p, const FileLoc &) {
    return std::make_shared<NoiseTexture>(NoiseTexture::Kind::Windy, p.Mapping3D(), 0, 0.f);
}

// Texture "marble" (texture_list.inc; spectrum only). Parameters:
//   octaves    integer  8    0 to 32
//   roughness  float    0.5  each octave's share of the one before
//   scale      float    1    the noise's frequency
//   variation  float    0.2  the noise's amplitude
TexturePtr CreateMarbleTexture(const TextureParams &p, const FileLoc &loc) {
    if (p.IsFloat()) return SpectrumOnly(p, loc, "marble");
    const int n = Octaves(p, "marble");
    return std::make_shared<MarbleTexture>(p.Mapping3D(), n, p.Float("roughness", .5f),
                                           p.Float("scale", 1.f), p.Float("variation", .2f));
}

// "ptex": not supported; a constant 0.5 after a warning.
TexturePtr CreatePtexStandIn(const TextureParams &p, const FileLoc &loc) {
    p.Warn(loc,
           "ptex textures are not supported; texture " + Quote(p.Name()) + " is a constant 0.5");
    p.MarkAllUsed();
    return Constant(RGB(0.5f));
}

namespace {
struct RegisteredTexture {
    const char *name;
    TexturePtr (*create)(const TextureParams &, const FileLoc &);
};
constexpr RegisteredTexture Textures[] = {
#define PRISM_TEXTURE(name, create) {name, &create},
#include "render/texture_list.inc"
#undef PRISM_TEXTURE
};
}  // namespace

TexturePtr CreateTexture(const std::string &type, const TextureParams &params, const FileLoc &loc,
                         bool *known) {
    for (const RegisteredTexture &r : Textures)
        if (type == r.name) {
            *known = true;
            return r.create(params, loc);
        }
    *known = false;
    return nullptr;
}

}  // namespace prism
