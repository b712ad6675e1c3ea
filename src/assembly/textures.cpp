#include "assembly/textures.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "assembly/directive_params.h"
#include "core/file_io.h"
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
                                           ReadImageOptions::Encoding enc, const char *param,
                                           float gamma = 1) {
        int embedded = EmbeddedImageIndex(file);
        std::string path = embedded >= 0 ? file : ResolveScenePath(desc, file);
        std::string key = path + "#" + std::to_string(int(enc));
        if (enc == ReadImageOptions::Encoding::Gamma)
            key += "^" + std::to_string(std::bit_cast<uint32_t>(gamma));
        auto it = ctx.imageCache.find(key);
        if (it != ctx.imageCache.end()) return it->second;
        const Param *p = t.params.Find(param);
        const FileLoc &loc = p ? p->loc : t.loc;
        const std::string what = "texture " + Quote(file);
        ReadImageOptions ro;
        ro.encoding = enc;
        ro.gamma = gamma;
        // The decoder refuses images larger than what remains of the budget before allocating.
        ro.maxPixels = int64_t(std::min<uint64_t>(budget.Remaining() / sizeof(float), INT64_MAX));
        // Refused under --confine with the name as the scene wrote it.
        if (embedded < 0) CheckReadConfinement(path, loc, "image file", file);
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

    // A Texture directive's parameters over its ParamSet, with the builder's tables.
    class SceneTextureParams : public DirectiveParamsOf<TextureParams> {
      public:
        SceneTextureParams(TextureBuilder &b, const TextureDesc &t)
            : DirectiveParamsOf(t.params, b.diag, "texture " + Quote(t.name), t.loc),
              b_(b),
              t_(t) {}
        bool IsFloat() const override { return t_.isFloat; }
        const std::string &Name() const override { return t_.name; }
        TexturePtr Tex(const char *name, bool isFloat, RGB def) const override {
            return b_.TexParam(ps_, name, isFloat, def);
        }
        RGB Spectrum(const char *name, RGB def) const override { return ps_.GetRGB(name, def); }
        Vec3f Vector(const char *name, Vec3f def) const override {
            return ps_.GetVector3(name, def);
        }
        TextureMapping Mapping() const override { return b_.Mapping(t_); }
        TextureMapping3D Mapping3D() const override {
            return TextureMapping3D{(b_.scene.renderFromWorld * t_.worldFromTexture).Inverse()};
        }
        std::shared_ptr<const Image> LoadImage(const char *param, const std::string &file,
                                               Encoding enc, float gamma) const override {
            const auto e = enc == Encoding::SRGB     ? ReadImageOptions::Encoding::SRGB
                           : enc == Encoding::Linear ? ReadImageOptions::Encoding::Linear
                           : enc == Encoding::Gamma  ? ReadImageOptions::Encoding::Gamma
                                                     : ReadImageOptions::Encoding::Auto;
            return b_.LoadImage(t_, file, e, param, gamma);
        }
        void Charge(size_t bytes, const std::string &what, const char *param) const override {
            b_.budget.Charge(bytes, what, Loc(param));
        }
        std::shared_ptr<const MIPMap> Mip(const std::shared_ptr<const Image> &img, TextureWrap wrap,
                                          const std::string &file,
                                          const char *param) const override {
            auto &cached = b_.ctx.mipCache[{img.get(), wrap}];
            if (!cached) {
                const FileLoc loc = Loc(param);
                // The levels above the image take a third of it (in RGB floats).
                b_.budget.Check(size_t(img->width) * size_t(img->height) * sizeof(RGB) / 3 + 64,
                                "MIP map of texture " + Quote(file), loc);
                cached = std::make_shared<MIPMap>(img, wrap);
                b_.budget.Charge(cached->Bytes(), "MIP map of texture " + Quote(file), loc);
            }
            return cached;
        }
        TextureFilter Filter() const override { return b_.Filter(ps_); }
        bool FootprintFilteringOff() const override {
            const std::string &f = b_.settings.textureFilter;
            return f == "none" || f == "point";
        }
        void WarnIgnored(const char *name, const std::string &why) const override {
            prism::WarnIgnored(ps_, {name}, diag_, t_.type + " texture", why);
        }
        void MarkAllUsed() const override { ps_.MarkAllUsed(); }

      private:
        TextureBuilder &b_;
        const TextureDesc &t_;
    };

    // Each Texture directive through its class's Create (render/texture_list.inc).
    void Build() {
        for (const TextureDesc &t : desc.textures) {
            const SceneTextureParams params(*this, t);
            bool known = false;
            TexturePtr tex = CreateTexture(t.type, params, t.loc, &known);
            if (!known)
                diag.Warn(t.loc, "texture class " + Quote(t.type) + " is not supported; texture " +
                                     Quote(t.name) + " is ignored");
            if (!tex) continue;
            if (!tex->IsConstant()) scene.features.textures = true;
            (t.isFloat ? ctx.floatTextures : ctx.rgbTextures)[t.name] = tex;
            t.params.ReportUnused(diag, "texture " + Quote(t.name));
        }
    }
};

}  // namespace

void BuildTextures(BuildContext &ctx) { TextureBuilder(ctx).Build(); }

TexturePtr ImageOnSurface(BuildContext &ctx, const SceneEntity &entity, const std::string &file,
                          const char *param) {
    // An imagemap texture of its own, located at the parameter, through the one Create.
    const Param *p = entity.params.Find(param);
    const FileLoc loc = p ? p->loc : entity.loc;
    TextureDesc t;
    t.name = "image " + Quote(file);
    t.type = "imagemap";
    t.loc = loc;
    auto add = [&](const char *name, const std::string &value) {
        Param q;
        q.type = ParamType::String;
        q.name = name;
        q.strings = {value};
        q.loc = loc;
        t.params.Add(std::move(q));
    };
    add("filename", file);
    add("filter", "bilinear");
    add("wrap", "clamp");
    TextureBuilder b(ctx);
    const TextureBuilder::SceneTextureParams params(b, t);
    bool known = false;
    TexturePtr tex = CreateTexture(t.type, params, t.loc, &known);
    if (!tex) throw SceneError(loc, "image " + Quote(file) + " cannot be used as a texture");
    if (!tex->IsConstant()) ctx.scene.features.textures = true;
    return tex;
}

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
