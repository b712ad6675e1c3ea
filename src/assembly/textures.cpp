#include "assembly/textures.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "core/memory.h"
#include "render/gltf_material.h"
#include "render/mipmap.h"

namespace prism {

TexturePtr Constant(RGB v) { return std::make_shared<ConstantTexture>(v); }

namespace {

struct TextureBuilder : BuildStep {
    using BuildStep::BuildStep;

    // A texture-valued parameter of a texture ("tex1", "amount", ...): texture name or value.
    TexturePtr TexParam(const ParamSet &ps, const std::string &name, bool isFloat, RGB def) {
        const Param *p = ps.Find(name);
        if (p && p->type == ParamType::Texture) {
            std::string tn = ps.GetTexture(name);
            const auto &table = isFloat ? ctx.floatTextures : ctx.rgbTextures;
            auto it = table.find(tn);
            if (it != table.end()) return it->second;
            diag.Warn(p->loc, (isFloat ? "unknown float texture " : "unknown spectrum texture ") +
                                  Quote(tn) + "; using the default value");
            return Constant(def);
        }
        if (isFloat) return Constant(RGB(ps.GetFloat(name, def.r)));
        return Constant(ps.GetRGB(name, def));
    }

    TextureMapping Mapping(const TextureDesc &t) {
        const ParamSet &ps = t.params;
        TextureMapping m;
        std::string kind = ps.GetString("mapping", "uv");
        m.su = ps.GetFloat("uscale", 1.f);
        m.sv = ps.GetFloat("vscale", 1.f);
        m.du = ps.GetFloat("udelta", 0.f);
        m.dv = ps.GetFloat("vdelta", 0.f);
        m.textureFromRender = (scene.renderFromWorld * t.worldFromTexture).Inverse();
        if (kind == "uv") {
            m.kind = TextureMapping::Kind::UV;
        } else if (kind == "spherical") {
            m.kind = TextureMapping::Kind::Spherical;
        } else if (kind == "cylindrical") {
            m.kind = TextureMapping::Kind::Cylindrical;
        } else if (kind == "planar") {
            m.kind = TextureMapping::Kind::Planar;
            m.v1 = ps.GetVector3("v1", Vec3f(1, 0, 0));
            m.v2 = ps.GetVector3("v2", Vec3f(0, 1, 0));
        } else {
            const Param *p = ps.Find("mapping");
            diag.Warn(p ? p->loc : t.loc, "unknown texture mapping " + Quote(kind) + "; using uv");
        }
        return m;
    }

    std::shared_ptr<const Image> LoadImage(const SceneEntity &t, const std::string &file,
                                           ReadImageOptions::Encoding enc, const char *param) {
        int embedded = EmbeddedImageIndex(file);
        std::string path = embedded >= 0 ? file : ResolveScenePath(desc, file);
        std::string key = path + "#" + std::to_string(int(enc));
        auto it = ctx.imageCache.find(key);
        if (it != ctx.imageCache.end()) return it->second;
        const Param *p = t.params.Find(param);
        const FileLoc &loc = p ? p->loc : t.loc;
        const std::string what = "texture " + Quote(file);
        ReadImageOptions ro;
        ro.encoding = enc;
        // The decoder refuses images larger than what remains of the budget before allocating.
        ro.maxPixels = int64_t(std::min<uint64_t>(budget.Remaining() / sizeof(float), INT64_MAX));
        std::shared_ptr<const Image> img;
        try {
            if (embedded >= 0) {
                if (size_t(embedded) >= desc.embeddedImages.size())
                    throw std::runtime_error("no embedded image " + std::to_string(embedded));
                const EmbeddedImage &e = desc.embeddedImages[size_t(embedded)];
                std::string ext = e.mimeType == "image/jpeg" ? ".jpg" : ".png";
                img = std::make_shared<Image>(ReadImageFromMemory(e.bytes, file + ext, ro));
            } else {
                img = std::make_shared<Image>(ReadImage(path, ro));
            }
        } catch (const MemoryBudgetError &e) {
            budget.Check(e.Requested(), what, loc);  // throws the budget's message here
            throw SceneError(loc, e.what());
        } catch (const std::exception &e) {
            throw SceneError(loc, e.what());
        }
        budget.Charge(img->pixels.size() * sizeof(float), what, loc);
        ctx.imageCache[key] = img;
        return img;
    }

    // An imagemap's lookup: --texture-filter, else pbrt's "filter" (pbrt-v4's names), else
    // pbrt-v3's "trilinear" bool (false: EWA, pbrt-v3's default).
    TextureFilter Filter(const ParamSet &ps) {
        auto parse = [](const std::string &n, TextureFilter *f) {
            for (TextureFilter c : {TextureFilter::Point, TextureFilter::Bilinear,
                                    TextureFilter::Trilinear, TextureFilter::EWA})
                if (n == TextureFilterName(c)) {
                    *f = c;
                    return true;
                }
            return false;
        };
        TextureFilter f =
            ps.GetBool("trilinear", false) ? TextureFilter::Trilinear : TextureFilter::EWA;
        std::string name = ps.GetString("filter", "");
        if (!name.empty() && !parse(name, &f))
            diag.Warn(ps.Find("filter")->loc, "unknown texture filter " + Quote(name) +
                                                  " (point, bilinear, trilinear or ewa); using " +
                                                  TextureFilterName(f));
        // "none": lookups as before filtering existed (bilinear at the finest level).
        if (settings.textureFilter == "none") return TextureFilter::Bilinear;
        if (!settings.textureFilter.empty()) parse(settings.textureFilter, &f);
        return f;
    }

    // [textures helper region] bilerp, uv, dots, fbm, wrinkled, windy and marble (pbrt-v3
    // names and defaults); nullptr (after a warning) for the float variants pbrt-v3 lacks.
    TexturePtr MakeProceduralTexture(const TextureDesc &t) {
        const ParamSet &ps = t.params;
        bool f = t.isFloat;
        auto spectrumOnly = [&]() {
            diag.Warn(t.loc, "texture class " + Quote(t.type) +
                                 " has no float variant (as in pbrt-v3); texture " + Quote(t.name) +
                                 " is ignored");
            ps.MarkAllUsed();
            return TexturePtr();
        };
        auto octaves = [&]() {
            int n = ps.GetInt("octaves", 8);
            if (n < 0 || n > 32) {
                const Param *p = ps.Find("octaves");
                throw SceneError(p ? p->loc : t.loc, t.type + " octaves must be 0 to 32");
            }
            return n;
        };
        TextureMapping3D m3{(scene.renderFromWorld * t.worldFromTexture).Inverse()};
        if (t.type == "bilerp") {
            auto v = [&](const char *n, float d) {
                return f ? RGB(ps.GetFloat(n, d)) : ps.GetRGB(n, RGB(d));
            };
            return std::make_shared<BilerpTexture>(Mapping(t), v("v00", 0), v("v01", 1),
                                                   v("v10", 0), v("v11", 1));
        }
        if (t.type == "uv") {
            if (f) return spectrumOnly();
            return std::make_shared<UVTexture>(Mapping(t));
        }
        if (t.type == "dots")
            return std::make_shared<DotsTexture>(Mapping(t), TexParam(ps, "inside", f, RGB(1)),
                                                 TexParam(ps, "outside", f, RGB(0)));
        if (t.type == "fbm" || t.type == "wrinkled") {
            auto kind = t.type == "fbm" ? NoiseTexture::Kind::FBm : NoiseTexture::Kind::Wrinkled;
            int n = octaves();
            return std::make_shared<NoiseTexture>(kind, m3, n, ps.GetFloat("roughness", .5f));
        }
        if (t.type == "windy")
            return std::make_shared<NoiseTexture>(NoiseTexture::Kind::Windy, m3, 0, 0.f);
        if (t.type == "marble") {
            if (f) return spectrumOnly();
            int n = octaves();
            return std::make_shared<MarbleTexture>(m3, n, ps.GetFloat("roughness", .5f),
                                                   ps.GetFloat("scale", 1.f),
                                                   ps.GetFloat("variation", .2f));
        }
        return nullptr;
    }
    // [end of textures helper region]

    TexturePtr MakeTexture(const TextureDesc &t) {
        const ParamSet &ps = t.params;
        bool f = t.isFloat;
        RGB one(1), zero(0);
        if (t.type == "constant") return TexParam(ps, "value", f, one);
        if (t.type == "scale") {
            if (!ps.Has("tex1") && !ps.Has("tex2") && (ps.Has("tex") || ps.Has("scale")))
                // pbrt-v4 spelling: "tex" times the float "scale".
                return std::make_shared<ScaleTexture>(TexParam(ps, "tex", f, one),
                                                      TexParam(ps, "scale", true, one));
            return std::make_shared<ScaleTexture>(TexParam(ps, "tex1", f, one),
                                                  TexParam(ps, "tex2", f, one));
        }
        if (t.type == "mix")
            return std::make_shared<MixTexture>(TexParam(ps, "tex1", f, zero),
                                                TexParam(ps, "tex2", f, one),
                                                TexParam(ps, "amount", true, RGB(0.5f)));
        if (t.type == "checkerboard") {
            int dim = ps.GetInt("dimension", 2);
            if (dim != 2 && dim != 3)
                throw SceneError(t.loc, "checkerboard dimension must be 2 or 3");
            // pbrt-v3's "aamode": "closedform" (the default) box-filters the 2-D board over
            // the ray's footprint; "none" point-samples. 3-D boards are point-sampled.
            auto aa = CheckerboardTexture::AAMode::ClosedForm;
            std::string aamode = ps.GetString("aamode", "closedform");
            if (aamode == "none")
                aa = CheckerboardTexture::AAMode::None;
            else if (aamode != "closedform")
                diag.Warn(ps.Find("aamode")->loc, "unknown checkerboard aamode " + Quote(aamode) +
                                                      "; using \"closedform\"");
            // --texture-filter none or point: no footprint filtering anywhere.
            if (settings.textureFilter == "none" || settings.textureFilter == "point")
                aa = CheckerboardTexture::AAMode::None;
            return std::make_shared<CheckerboardTexture>(Mapping(t), TexParam(ps, "tex1", f, one),
                                                         TexParam(ps, "tex2", f, zero), dim, aa);
        }
        if (t.type == "imagemap") {
            std::string file = ps.GetString("filename", "");
            if (file.empty()) throw SceneError(t.loc, "imagemap texture needs a \"filename\"");
            std::string wrapName = ps.GetString("wrap", "repeat");
            WrapMode wrap = WrapMode::Repeat;
            if (wrapName == "black")
                wrap = WrapMode::Black;
            else if (wrapName == "clamp")
                wrap = WrapMode::Clamp;
            else if (wrapName != "repeat")
                diag.Warn(ps.Find("wrap")->loc,
                          "unknown wrap mode " + Quote(wrapName) + "; using repeat");
            auto enc = ReadImageOptions::Encoding::Auto;
            if (ps.Has("gamma"))
                enc = ps.GetBool("gamma", false) ? ReadImageOptions::Encoding::SRGB
                                                 : ReadImageOptions::Encoding::Linear;
            // pbrt-v4's "encoding" for 8-bit images: "sRGB" and "linear" are honoured.
            std::string encoding = ps.GetString("encoding", "");
            if (encoding == "sRGB")
                enc = ReadImageOptions::Encoding::SRGB;
            else if (encoding == "linear")
                enc = ReadImageOptions::Encoding::Linear;
            else if (!encoding.empty())
                WarnIgnored(ps, {"encoding"}, diag, "imagemap texture",
                            "only \"sRGB\" and \"linear\" are read");
            const TextureFilter filter = Filter(ps);
            float maxAniso = ps.GetFloat("maxanisotropy", 8.f);
            if (!(maxAniso >= 1)) {
                diag.Warn(ps.Find("maxanisotropy")->loc, "maxanisotropy below 1; using 1");
                maxAniso = 1;
            }
            auto img = LoadImage(t, file, enc, "filename");
            // Prism extension for cut-outs (glTF baseColor alpha, OBJ map_d): a float texture
            // of the image's "alpha" channel (1 without one), or "alphaorluminance".
            std::string channel = f ? ps.GetString("channel", "luminance") : "luminance";
            if (channel != "luminance" && channel != "alpha" && channel != "alphaorluminance")
                throw SceneError(ps.Find("channel")->loc,
                                 "imagemap \"channel\" must be \"luminance\", \"alpha\" or "
                                 "\"alphaorluminance\", not " +
                                     Quote(channel));
            if (channel != "luminance" && (img->HasAlpha() || channel == "alpha")) {
                const Param *fp = ps.Find("filename");
                budget.Charge(img->pixels.size() * sizeof(float), "texture " + Quote(file),
                              fp ? fp->loc : t.loc);
                auto a = std::make_shared<Image>(*img);
                const int ac = img->channels == 2 ? 1 : 3;
                for (int y = 0; y < a->height; ++y)
                    for (int x = 0; x < a->width; ++x)
                        a->SetRGB(x, y, RGB(img->HasAlpha() ? img->At(x, y, ac) : 1.f));
                img = a;
            } else if (f && img->channels >= 3) {
                // pbrt converts RGB texels of float textures to luminance, in a copy.
                const Param *fp = ps.Find("filename");
                budget.Charge(img->pixels.size() * sizeof(float), "texture " + Quote(file),
                              fp ? fp->loc : t.loc);
                auto lum = std::make_shared<Image>(*img);
                for (int y = 0; y < lum->height; ++y)
                    for (int x = 0; x < lum->width; ++x)
                        lum->SetRGB(x, y, RGB(img->GetRGB(x, y).Luminance()));
                img = lum;
            }
            std::shared_ptr<const MIPMap> mip;
            if (filter == TextureFilter::Trilinear || filter == TextureFilter::EWA) {
                auto &cached = ctx.mipCache[{img.get(), int(wrap)}];
                if (!cached) {
                    const Param *fp = ps.Find("filename");
                    const FileLoc &loc = fp ? fp->loc : t.loc;
                    // The levels above the image take a third of it (in RGB floats).
                    budget.Check(size_t(img->width) * size_t(img->height) * sizeof(RGB) / 3 + 64,
                                 "MIP map of texture " + Quote(file), loc);
                    cached = std::make_shared<MIPMap>(img, wrap);
                    budget.Charge(cached->Bytes(), "MIP map of texture " + Quote(file), loc);
                }
                mip = cached;
            }
            return std::make_shared<ImageTexture>(Mapping(t), img, wrap, ps.GetFloat("scale", 1.f),
                                                  ps.GetBool("invert", false), filter, mip,
                                                  maxAniso);
        }
        for (const char *c : {"bilerp", "uv", "dots", "fbm", "wrinkled", "windy", "marble"})
            if (t.type == c) return MakeProceduralTexture(t);
        if (t.type == "ptex") {
            diag.Warn(t.loc, "ptex textures are not supported; texture " + Quote(t.name) +
                                 " is a constant 0.5");
            ps.MarkAllUsed();
            return Constant(RGB(0.5f));
        }
        diag.Warn(t.loc, "texture class " + Quote(t.type) + " is not supported; texture " +
                             Quote(t.name) + " is ignored");
        return nullptr;
    }

    void Build() {
        for (const TextureDesc &t : desc.textures) {
            TexturePtr tex = MakeTexture(t);
            if (!tex) continue;
            if (!tex->IsConstant()) scene.features.textures = true;
            (t.isFloat ? ctx.floatTextures : ctx.rgbTextures)[t.name] = tex;
            t.params.ReportUnused(diag, "texture " + Quote(t.name));
        }
    }
};

}  // namespace

void BuildTextures(BuildContext &ctx) { TextureBuilder(ctx).Build(); }

TexturePtr TextureParam(BuildContext &ctx, const ParamSet &ps, const std::string &name,
                        bool isFloat, RGB def) {
    return TextureBuilder(ctx).TexParam(ps, name, isFloat, def);
}

std::shared_ptr<const Image> LoadSceneImage(BuildContext &ctx, const SceneEntity &entity,
                                            const std::string &file, ReadImageOptions::Encoding enc,
                                            const char *param) {
    return TextureBuilder(ctx).LoadImage(entity, file, enc, param);
}

TexturePtr WithTexCoordParams(TexturePtr t, const ParamSet *primary, const ParamSet &fallback,
                              const std::string &name) {
    auto src = [&](const std::string &n) -> const ParamSet & {
        return primary && primary->Has(n) ? *primary : fallback;
    };
    const std::string tn = name + "transform", cn = name + "texcoord";
    if (src(tn).Has(tn)) {
        std::vector<float> v = src(tn).GetFloats(tn);
        if (v.size() != 5)
            throw SceneError(src(tn).Find(tn)->loc, "\"" + tn + "\" must have 5 values");
        t = std::make_shared<UVTransformTexture>(t, Vec2f(v[0], v[1]), v[2], Vec2f(v[3], v[4]));
    }
    if (src(cn).Has(cn)) {
        const int set = src(cn).GetInt(cn, 0);
        if (set != 0 && set != 1)
            throw SceneError(src(cn).Find(cn)->loc,
                             "\"" + cn + "\" must be 0 or 1, not " + std::to_string(set));
        if (set == 1) t = std::make_shared<TexCoord1Texture>(t);
    }
    return t;
}

}  // namespace prism
