// SceneDescription → RenderScene: creates textures, materials, lights, the camera and the
// geometry, reading each entity's parameters with pbrt-v3's names and defaults.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "core/memory.h"
#include "geometry/sphere.h"
#include "validate/tessellate.h"
#include "render/area_light.h"
#include "image/image.h"
#include "image/image_io.h"
#include "render/render_scene.h"
#include "build/shape_factory.h"
#include "scene/ply_reader.h"

namespace prism {

namespace {

std::string Quote(const std::string &s) { return "\"" + s + "\""; }

// pbrt-v3 reads "scale" as a spectrum; v4 files write a float. Accept both.
RGB ScaleParam(const ParamSet &ps) {
    const Param *p = ps.Find("scale");
    if (p && p->type == ParamType::Float) return RGB(ps.GetFloat("scale", 1.f));
    return ps.GetRGB("scale", RGB(1));
}

using TextureTable = std::map<std::string, TexturePtr>;

struct Builder {
    const SceneDescription &desc;
    const RenderOptions &options;
    Diagnostics &diag;
    RenderScene &scene;
    TextureTable floatTextures, rgbTextures;
    std::map<std::string, std::shared_ptr<const Image>> imageCache;
    std::vector<int> sharedMaterial;  // desc material index → scene material index (-1: not yet)

    // ---- Textures -------------------------------------------------------------------------

    TexturePtr Constant(RGB v) { return std::make_shared<ConstantTexture>(v); }

    // A texture-valued parameter of a texture ("tex1", "amount", ...): texture name or value.
    TexturePtr TexParam(const ParamSet &ps, const std::string &name, bool isFloat, RGB def) {
        const Param *p = ps.Find(name);
        if (p && p->type == ParamType::Texture) {
            std::string tn = ps.GetTexture(name);
            const TextureTable &table = isFloat ? floatTextures : rgbTextures;
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
        auto it = imageCache.find(key);
        if (it != imageCache.end()) return it->second;
        ReadImageOptions ro;
        ro.encoding = enc;
        ro.maxPixels = int64_t(EffectiveMemoryBudget(options.maxMemory) / sizeof(float));
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
        } catch (const std::exception &e) {
            const Param *p = t.params.Find(param);
            throw SceneError(p ? p->loc : t.loc, e.what());
        }
        imageCache[key] = img;
        return img;
    }

    // [textures helper region] bilerp, uv, dots, fbm, wrinkled, windy and marble (pbrt-v3
    // names and defaults); nullptr (after a warning) for the float variants pbrt-v3 lacks.
    TexturePtr MakeProceduralTexture(const TextureDesc &t) {
        const ParamSet &ps = t.params;
        bool f = t.isFloat;
        auto spectrumOnly = [&]() {
            diag.Warn(t.loc, "texture class " + Quote(t.type) + " has no float variant (as in pbrt-v3); texture " +
                                 Quote(t.name) + " is ignored");
            for (const Param &p : ps.Params()) p.lookedUp = true;
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
        if (t.type == "windy") return std::make_shared<NoiseTexture>(NoiseTexture::Kind::Windy, m3, 0, 0.f);
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
            if (dim != 2 && dim != 3) throw SceneError(t.loc, "checkerboard dimension must be 2 or 3");
            ps.MarkUsed("aamode");  // supersampling replaces pbrt's closed-form filtering
            return std::make_shared<CheckerboardTexture>(Mapping(t), TexParam(ps, "tex1", f, one),
                                                         TexParam(ps, "tex2", f, zero), dim);
        }
        if (t.type == "imagemap") {
            std::string file = ps.GetString("filename", "");
            if (file.empty()) throw SceneError(t.loc, "imagemap texture needs a \"filename\"");
            std::string wrapName = ps.GetString("wrap", "repeat");
            WrapMode wrap = WrapMode::Repeat;
            if (wrapName == "black") wrap = WrapMode::Black;
            else if (wrapName == "clamp") wrap = WrapMode::Clamp;
            else if (wrapName != "repeat")
                diag.Warn(ps.Find("wrap")->loc, "unknown wrap mode " + Quote(wrapName) + "; using repeat");
            auto enc = ReadImageOptions::Encoding::Auto;
            if (ps.Has("gamma"))
                enc = ps.GetBool("gamma", false) ? ReadImageOptions::Encoding::SRGB
                                                 : ReadImageOptions::Encoding::Linear;
            for (const char *n : {"trilinear", "maxanisotropy", "filter", "encoding"}) ps.MarkUsed(n);
            auto img = LoadImage(t, file, enc, "filename");
            if (f && img->channels >= 3) {
                // pbrt converts RGB texels of float textures to luminance.
                auto lum = std::make_shared<Image>(*img);
                for (int y = 0; y < lum->height; ++y)
                    for (int x = 0; x < lum->width; ++x)
                        lum->SetRGB(x, y, RGB(img->GetRGB(x, y).Luminance()));
                img = lum;
            }
            return std::make_shared<ImageTexture>(Mapping(t), img, wrap, ps.GetFloat("scale", 1.f),
                                                  ps.GetBool("invert", false));
        }
        for (const char *c : {"bilerp", "uv", "dots", "fbm", "wrinkled", "windy", "marble"})
            if (t.type == c) return MakeProceduralTexture(t);
        if (t.type == "ptex") {
            diag.Warn(t.loc, "ptex textures are not supported; texture " + Quote(t.name) +
                                 " is a constant 0.5");
            for (const Param &p : ps.Params()) p.lookedUp = true;
            return Constant(RGB(0.5f));
        }
        diag.Warn(t.loc, "texture class " + Quote(t.type) + " is not supported; texture " +
                             Quote(t.name) + " is ignored");
        return nullptr;
    }

    void BuildTextures() {
        for (const TextureDesc &t : desc.textures) {
            TexturePtr tex = MakeTexture(t);
            if (!tex) continue;
            if (!tex->IsConstant()) scene.features.textures = true;
            (t.isFloat ? floatTextures : rgbTextures)[t.name] = tex;
            t.params.ReportUnused(diag, "texture " + Quote(t.name));
        }
    }

    // ---- Materials ------------------------------------------------------------------------

    // Material parameters, looked up first among the shape's parameters (pbrt lets a Shape
    // override its material's parameters) and then the material's.
    struct MaterialParams {
        Builder &b;
        const ParamSet *shape;
        const ParamSet &mat;
        bool usedShape = false;
        const ParamSet &Src(const std::string &name) {
            if (shape && shape->Has(name)) {
                usedShape = true;
                return *shape;
            }
            return mat;
        }
        TexturePtr RGBTex(const std::string &n, RGB def) { return b.TexParam(Src(n), n, false, def); }
        TexturePtr FloatTex(const std::string &n, float def) {
            return b.TexParam(Src(n), n, true, RGB(def));
        }
        RGB Rgb(const std::string &n, RGB def) { return Src(n).GetRGB(n, def); }
        bool Bool(const std::string &n, bool def) { return Src(n).GetBool(n, def); }
        bool Has(const std::string &n) { return (shape && shape->Has(n)) || mat.Has(n); }
    };

    // ---- Materials (uber, substrate, translucent, mix, v4 names: see docs/MATERIALS.md) ----
    // [materials helper region: MakeMaterial, named-material resolution, MaterialForShape]

    // Named materials referenced by mix materials, built once each (by desc index); the state
    // detects reference cycles: 0 not built, 1 being built, 2 built.
    std::vector<std::shared_ptr<const Material>> namedMaterialCache;
    std::vector<char> namedMaterialState;

    // The material a mix names: the latest definition before the mix (pbrt-v3 resolves names
    // when the mix is declared), else a later one (pbrt-v4 files may refer forward).
    int ResolveNamedMaterial(const std::string &name, int from) const {
        for (int i = std::min(from, int(desc.materials.size())) - 1; i >= 0; --i)
            if (desc.materials[size_t(i)].name == name) return i;
        for (size_t i = size_t(std::max(from, 0)); i < desc.materials.size(); ++i)
            if (desc.materials[i].name == name) return int(i);
        return -1;
    }

    std::shared_ptr<const Material> NamedMaterialRef(const std::string &name, int from,
                                                     const FileLoc &loc, int depth) {
        int index = ResolveNamedMaterial(name, from);
        if (index < 0) {
            diag.Warn(loc, "unknown named material " + Quote(name) + " in mix; using matte");
            auto m = std::make_shared<Material>();
            m->typeName = "matte";
            m->Kd = Constant(RGB(0.5f));
            m->sigma = Constant(RGB(0));
            return m;
        }
        if (namedMaterialCache.size() < desc.materials.size()) {
            namedMaterialCache.resize(desc.materials.size());
            namedMaterialState.resize(desc.materials.size(), 0);
        }
        if (namedMaterialState[size_t(index)] == 2) return namedMaterialCache[size_t(index)];
        if (namedMaterialState[size_t(index)] == 1)
            throw SceneError(loc, "mix material refers to itself through " + Quote(name));
        namedMaterialState[size_t(index)] = 1;
        const MaterialDesc &md = desc.materials[size_t(index)];
        auto m = std::make_shared<Material>(MakeMaterial(md, index, nullptr, nullptr, depth + 1));
        md.params.ReportUnused(diag, "material " + Quote(md.type));
        namedMaterialState[size_t(index)] = 2;
        namedMaterialCache[size_t(index)] = m;
        return m;
    }

    // A spectrum-or-float texture parameter (mix "amount" is a spectrum texture in pbrt-v3 and
    // a float texture in v4).
    TexturePtr AnyTex(MaterialParams &mp, const std::string &n, RGB def) {
        const ParamSet &ps = mp.Src(n);
        const Param *p = ps.Find(n);
        if (p && p->type == ParamType::Texture) {
            std::string tn = ps.GetTexture(n);
            if (!rgbTextures.count(tn) && floatTextures.count(tn)) return floatTextures[tn];
            return TexParam(ps, n, false, def);
        }
        if (p && (p->type == ParamType::Float || p->type == ParamType::Integer))
            return Constant(RGB(ps.GetFloat(n, def.r)));
        return TexParam(ps, n, false, def);
    }

    // pbrt-v3 `roughness` / `uroughness` / `vroughness` for the materials that have all three.
    void Roughness(Material &mat, MaterialParams &mp, float def) {
        mat.roughness = mp.FloatTex("roughness", def);
        mat.uRoughness = mp.Has("uroughness") ? mp.FloatTex("uroughness", def) : nullptr;
        mat.vRoughness = mp.Has("vroughness") ? mp.FloatTex("vroughness", def) : nullptr;
        mat.remapRoughness = mp.Bool("remaproughness", true);
    }

    // `descIndex` is the material's position in desc.materials (mix names resolve from there);
    // `depth` counts enclosing mixes.
    Material MakeMaterial(const MaterialDesc &m, int descIndex, const ParamSet *shapeParams,
                          bool *usedShape, int depth = 0) {
        MaterialParams mp{*this, shapeParams, m.params};
        Material mat;
        mat.typeName = m.type;
        std::string type = m.type;
        // pbrt-v4 names mapped onto the same models.
        if (type == "diffuse") type = "matte";
        else if (type == "dielectric") type = "glass";
        else if (type == "conductor") type = "metal";
        else if (type == "interface") type = "none";
        else if (type == "diffusetransmission") type = "translucent";
        mp.mat.MarkUsed("type");
        if (mp.Has("bumpmap") || mp.Has("displacement")) {
            const Param *p = m.params.Find("bumpmap");
            if (!p) p = m.params.Find("displacement");
            diag.Warn(p ? p->loc : m.loc, "bump mapping is not supported; ignored");
            m.params.MarkUsed("bumpmap");
            m.params.MarkUsed("displacement");
        }
        if (type == "matte") {
            mat.kind = Material::Kind::Matte;
            mat.Kd = mp.Has("reflectance") ? mp.RGBTex("reflectance", RGB(0.5f))
                                           : mp.RGBTex("Kd", RGB(0.5f));
            mat.sigma = mp.FloatTex("sigma", 0.f);
        } else if (type == "plastic") {
            mat.kind = Material::Kind::Plastic;
            mat.Kd = mp.RGBTex("Kd", RGB(0.25f));
            mat.Ks = mp.RGBTex("Ks", RGB(0.25f));
            mat.roughness = mp.FloatTex("roughness", 0.1f);
            mat.remapRoughness = mp.Bool("remaproughness", true);
        } else if (type == "mirror") {
            mat.kind = Material::Kind::Mirror;
            mat.Kr = mp.RGBTex("Kr", RGB(0.9f));
        } else if (type == "glass") {
            mat.kind = Material::Kind::Glass;
            mat.Kr = mp.RGBTex("Kr", RGB(1));
            mat.Kt = mp.RGBTex("Kt", RGB(1));
            mat.index = mp.Has("eta") ? mp.FloatTex("eta", 1.5f) : mp.FloatTex("index", 1.5f);
            if (mp.Has("uroughness") || mp.Has("vroughness") || mp.Has("roughness")) {
                float r = std::max({mp.Src("uroughness").GetFloat("uroughness", 0.f),
                                    mp.Src("vroughness").GetFloat("vroughness", 0.f),
                                    mp.Src("roughness").GetFloat("roughness", 0.f)});
                if (r > 0)
                    diag.Warn(m.loc, "rough glass is rendered as smooth glass by the Whitted integrator");
            }
            mp.Src("remaproughness").MarkUsed("remaproughness");
        } else if (type == "metal") {
            mat.kind = Material::Kind::Metal;
            if (mp.Has("reflectance") && !mp.Has("eta") && !mp.Has("k")) {
                // pbrt-v4 conductor given its normal-incidence reflectance r: eta 1 and
                // k = 2 sqrt(r) / sqrt(1 - r), which reproduces r at normal incidence.
                RGB r = mp.Rgb("reflectance", RGB(0.9f)).Clamped(0.f, 0.9999f);
                mat.metalEta = RGB(1);
                mat.metalK = RGB(2 * std::sqrt(r.r / (1 - r.r)), 2 * std::sqrt(r.g / (1 - r.g)),
                                 2 * std::sqrt(r.b / (1 - r.b)));
            } else {
                // pbrt-v3's default is copper; these are its eta/k spectra reduced to RGB.
                mat.metalEta = mp.Rgb("eta", RGB(0.200438f, 0.924033f, 1.10221f));
                mat.metalK = mp.Rgb("k", RGB(3.91295f, 2.45285f, 2.14219f));
            }
            // pbrt-v4's conductor defaults to a polished surface; v3's metal to roughness 0.01.
            float defRough = m.type == "conductor" ? 0.f : 0.01f;
            TexturePtr rough = mp.FloatTex("roughness", defRough);
            mat.uRoughness = mp.Has("uroughness") ? mp.FloatTex("uroughness", 0.f) : rough;
            mat.vRoughness = mp.Has("vroughness") ? mp.FloatTex("vroughness", 0.f) : rough;
            mat.remapRoughness = mp.Bool("remaproughness", true);
            if (m.type == "conductor" && mat.remapRoughness) {
                // pbrt-v4 remaps roughness r to alpha = sqrt(r) (v3 used a polynomial that
                // never reaches 0); constant values are converted here.
                auto v4Alpha = [&](TexturePtr &t) {
                    if (auto *c = dynamic_cast<const ConstantTexture *>(t.get()))
                        t = Constant(RGB(std::sqrt(std::max(0.f, c->Value().r))));
                };
                if (mat.uRoughness->IsConstant() && mat.vRoughness->IsConstant()) {
                    v4Alpha(mat.uRoughness);
                    v4Alpha(mat.vRoughness);
                    mat.remapRoughness = false;
                }
            }
        } else if (type == "uber") {
            mat.kind = Material::Kind::Uber;
            mat.Kd = mp.RGBTex("Kd", RGB(0.25f));
            mat.Ks = mp.RGBTex("Ks", RGB(0.25f));
            mat.Kr = mp.RGBTex("Kr", RGB(0));
            mat.Kt = mp.RGBTex("Kt", RGB(0));
            Roughness(mat, mp, 0.1f);
            mat.index = mp.Has("eta") ? mp.FloatTex("eta", 1.5f) : mp.FloatTex("index", 1.5f);
            mat.opacity = mp.RGBTex("opacity", RGB(1));
        } else if (type == "coateddiffuse") {
            // pbrt-v4's layered coat, approximated as uber: the diffuse base plus the coat's
            // dielectric reflection (a highlight when rough, a Fresnel mirror when smooth).
            mat.kind = Material::Kind::Uber;
            mat.Kd = mp.RGBTex("reflectance", RGB(0.5f));
            Roughness(mat, mp, 0.f);
            auto *c = dynamic_cast<const ConstantTexture *>(
                (mat.uRoughness ? mat.uRoughness : mat.roughness).get());
            bool smooth = c && c->Value().r == 0;
            mat.Ks = Constant(RGB(smooth ? 0.f : 1.f));
            mat.Kr = Constant(RGB(smooth ? 1.f : 0.f));
            mat.Kt = Constant(RGB(0));
            mat.index = mp.FloatTex("eta", 1.5f);
            for (const char *n : {"thickness", "albedo", "g", "maxdepth", "nsamples", "seed"})
                mp.Src(n).MarkUsed(n);
        } else if (type == "substrate") {
            mat.kind = Material::Kind::Substrate;
            mat.Kd = mp.RGBTex("Kd", RGB(0.5f));
            mat.Ks = mp.RGBTex("Ks", RGB(0.5f));
            mat.uRoughness = mp.FloatTex("uroughness", 0.1f);
            mat.vRoughness = mp.FloatTex("vroughness", 0.1f);
            mat.remapRoughness = mp.Bool("remaproughness", true);
        } else if (type == "translucent") {
            mat.kind = Material::Kind::Translucent;
            if (m.type == "diffusetransmission") {
                // pbrt-v4: Lambertian reflectance and transmittance, times "scale".
                mat.Kd = Constant(RGB(mp.Src("scale").GetFloat("scale", 1.f)));
                mat.Ks = Constant(RGB(0));
                mat.reflect = mp.RGBTex("reflectance", RGB(0.25f));
                mat.transmit = mp.RGBTex("transmittance", RGB(0.25f));
            } else {
                mat.Kd = mp.RGBTex("Kd", RGB(0.25f));
                mat.Ks = mp.RGBTex("Ks", RGB(0.25f));
                mat.reflect = mp.RGBTex("reflect", RGB(0.5f));
                mat.transmit = mp.RGBTex("transmit", RGB(0.5f));
            }
            mat.roughness = mp.FloatTex("roughness", 0.1f);
            mat.remapRoughness = mp.Bool("remaproughness", true);
        } else if (type == "mix") {
            mat.kind = Material::Kind::Mix;
            // Each nesting level adds at least one BSDF part, so deeper nests than this are
            // over the limit anyway; stopping here also bounds the recursion.
            if (depth >= BSDF::MaxParts)
                throw SceneError(m.loc, "mix materials are nested too deeply (more than " +
                                            std::to_string(BSDF::MaxParts) + " levels)");
            mat.amount = AnyTex(mp, "amount", RGB(0.5f));
            std::string n1, n2;
            FileLoc loc1 = m.loc, loc2 = m.loc;
            if (mp.Has("materials")) {
                // pbrt-v4: "string materials" [a b], amount selects b (= v3's namedmaterial1).
                const Param *p = mp.Src("materials").Find("materials");
                std::vector<std::string> names = mp.Src("materials").GetStrings("materials");
                if (names.size() != 2)
                    throw SceneError(p->loc, "mix \"materials\" must name exactly two materials");
                n1 = names[1];
                n2 = names[0];
                loc1 = loc2 = p->loc;
            } else {
                n1 = mp.Src("namedmaterial1").GetString("namedmaterial1", "");
                n2 = mp.Src("namedmaterial2").GetString("namedmaterial2", "");
                if (const Param *p = m.params.Find("namedmaterial1")) loc1 = p->loc;
                if (const Param *p = m.params.Find("namedmaterial2")) loc2 = p->loc;
            }
            mat.mix1 = NamedMaterialRef(n1, descIndex, loc1, depth);
            mat.mix2 = NamedMaterialRef(n2, descIndex, loc2, depth);
            if (mat.MaxParts() > BSDF::MaxParts)
                throw SceneError(m.loc, "mix material combines more than " +
                                            std::to_string(BSDF::MaxParts) + " materials");
        } else if (type == "none" || type.empty()) {
            mat.kind = Material::Kind::None;
        } else {
            // fourier, hair, subsurface, kdsubsurface, disney, ... and unknown types.
            const char *colour = mp.Has("Kd")            ? "Kd"
                                 : mp.Has("reflectance") ? "reflectance"
                                 : mp.Has("color")       ? "color"
                                                         : nullptr;
            diag.Warn(m.loc, "material " + Quote(m.type) + " is not supported; using matte" +
                                 (colour ? std::string(" with its \"") + colour + "\"" : ""));
            mat.kind = Material::Kind::Matte;
            mat.Kd = colour ? mp.RGBTex(colour, RGB(0.5f)) : Constant(RGB(0.5f));
            mat.sigma = Constant(RGB(0));
            for (const Param &p : m.params.Params()) p.lookedUp = true;
        }
        if (usedShape) *usedShape = mp.usedShape;
        return mat;
    }

    // The scene material index for a shape: the shared one, or a new one when the shape's own
    // parameters override the material's.
    int MaterialForShape(const ShapeDesc &s) {
        if (s.material < 0) return 0;
        const MaterialDesc &md = desc.materials[size_t(s.material)];
        bool usedShape = false;
        Material m = MakeMaterial(md, s.material, &s.params, &usedShape);
        if (usedShape) {
            scene.materials.push_back(std::move(m));
            return int(scene.materials.size()) - 1;
        }
        int &shared = sharedMaterial[size_t(s.material)];
        if (shared < 0) {
            scene.materials.push_back(std::move(m));
            shared = int(scene.materials.size()) - 1;
            md.params.ReportUnused(diag, "material " + Quote(md.type));
        }
        return shared;
    }
    // [end of materials helper region]

    // ---- Lights ---------------------------------------------------------------------------

    void BuildLights() {
        for (const LightDesc &l : desc.lights) {
            const ParamSet &ps = l.params;
            Transform renderFromLight = scene.renderFromWorld * l.worldFromLight;
            RGB sc = ScaleParam(ps);
            if (l.type == "point") {
                RGB I = ps.GetRGB("I", RGB(1)) * sc;
                Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
                scene.lights.push_back(std::make_unique<PointLight>(
                    Vec3f(renderFromLight.Point(Vec3d(from))), I));
            } else if (l.type == "spot") {
                RGB I = ps.GetRGB("I", RGB(1)) * sc;
                Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
                Vec3f to = ps.GetPoint3("to", Vec3f(0, 0, 1));
                if (from == to) throw SceneError(l.loc, "spot light \"from\" and \"to\" are the same point");
                float cone = ps.GetFloat("coneangle", 30.f), delta = ps.GetFloat("conedeltaangle", 5.f);
                Vec3d dir = Normalize(renderFromLight.Vector(Vec3d(to) - Vec3d(from)));
                scene.lights.push_back(std::make_unique<SpotLight>(
                    Vec3f(renderFromLight.Point(Vec3d(from))), Vec3f(dir), I, cone, delta));
            } else if (l.type == "distant") {
                RGB L = ps.GetRGB("L", RGB(1)) * sc;
                Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
                Vec3f to = ps.GetPoint3("to", Vec3f(0, 0, 1));
                Vec3d w = renderFromLight.Vector(Vec3d(from) - Vec3d(to));
                if (!(Length(w) > 0)) throw SceneError(l.loc, "distant light \"from\" and \"to\" are the same point");
                scene.lights.push_back(std::make_unique<DistantLight>(Vec3f(Normalize(w)), L));
            } else if (l.type == "infinite") {
                RGB L = ps.GetRGB("L", RGB(1)) * sc;
                std::string mapname = ps.GetString("mapname", "");
                std::shared_ptr<const Image> map;
                if (!mapname.empty()) map = LoadImage(l, mapname, ReadImageOptions::Encoding::Auto, "mapname");
                int n = ps.GetInt("nsamples", ps.GetInt("samples", 1));
                if (options.lightSamples > 0) n = options.lightSamples;
                if (n < 1 || n > 4096) throw SceneError(l.loc, "infinite light nsamples must be 1 to 4096");
                scene.lights.push_back(std::make_unique<InfiniteLight>(renderFromLight, L, map, n));
                scene.features.environment = true;
            } else {
                diag.WarnOnce("light:" + l.type, l.loc,
                              "light source " + Quote(l.type) + " is not supported; every such light is ignored");
                for (const Param &p : ps.Params()) p.lookedUp = true;
            }
            ps.ReportUnused(diag, "light " + Quote(l.type));
        }
    }

    // ---- Camera and film ------------------------------------------------------------------

    void BuildCameraAndFilm() {
        const ParamSet &film = desc.film.params;
        int xres = film.GetInt("xresolution", 1280), yres = film.GetInt("yresolution", 720);
        // The file's values are checked even when --res overrides them: they are bad input.
        const int maxRes = 1 << 16;
        if (xres <= 0 || yres <= 0 || xres > maxRes || yres > maxRes) {
            const Param *p = film.Find(xres <= 0 || xres > maxRes ? "xresolution" : "yresolution");
            throw SceneError(p ? p->loc : desc.film.loc,
                             "image resolution " + std::to_string(xres) + "x" + std::to_string(yres) +
                                 " is out of range (1 to " + std::to_string(maxRes) + " per axis)");
        }
        if (options.resolution.x > 0) {
            xres = options.resolution.x;
            yres = options.resolution.y;
            if (xres > maxRes || yres > maxRes)
                throw SceneError("--res " + std::to_string(xres) + "x" + std::to_string(yres) +
                                 " is out of range (1 to " + std::to_string(maxRes) + " per axis)");
        }
        scene.resolution = {xres, yres};
        std::array<float, 4> crop{0, 1, 0, 1};
        std::vector<float> cw = film.GetFloats("cropwindow");
        if (cw.size() == 4) std::copy(cw.begin(), cw.end(), crop.begin());
        if (options.crop) crop = *options.crop;
        crop = {Clamp(std::min(crop[0], crop[1]), 0.f, 1.f), Clamp(std::max(crop[0], crop[1]), 0.f, 1.f),
                Clamp(std::min(crop[2], crop[3]), 0.f, 1.f), Clamp(std::max(crop[2], crop[3]), 0.f, 1.f)};
        Bounds2i pb;
        pb.pMin = {int(std::ceil(xres * crop[0])), int(std::ceil(yres * crop[2]))};
        pb.pMax = {int(std::ceil(xres * crop[1])), int(std::ceil(yres * crop[3]))};
        if (pb.pMax.x <= pb.pMin.x || pb.pMax.y <= pb.pMin.y)
            throw SceneError(desc.film.loc, "the crop window covers no pixels");
        scene.pixelBounds = pb;
        {
            // Film (4 doubles per pixel), tile buffers with filter margins, the float image
            // and its encoded copy: about 96 bytes per pixel, checked before any is allocated.
            const uint64_t bytesPerPixel = 96;
            uint64_t pixels = uint64_t(pb.pMax.x - pb.pMin.x) * uint64_t(pb.pMax.y - pb.pMin.y);
            uint64_t budget = EffectiveMemoryBudget(options.maxMemory);
            if (pixels > budget / bytesPerPixel) {
                std::string msg = "image " + std::to_string(xres) + "x" + std::to_string(yres) +
                                  " needs about " + FormatBytes(pixels * bytesPerPixel) +
                                  ", more than the memory budget of " + FormatBytes(budget) +
                                  " (--max-memory)";
                if (options.resolution.x > 0) throw SceneError(msg);
                const Param *p = film.Find("xresolution");
                throw SceneError(p ? p->loc : desc.film.loc, msg);
            }
        }
        scene.outputFilename = film.GetString("filename", "");
        scene.filmScale = film.GetFloat("scale", 1.f);
        scene.maxSampleLuminance = film.GetFloat("maxsampleluminance", Infinity);
        film.MarkUsed("diagonal");
        film.ReportUnused(diag, "film");

        const CameraDesc &cd = desc.camera;
        const ParamSet &cp = cd.params;
        CameraParams params;
        std::string type = cd.specified ? cd.type : "perspective";
        if (type == "orthographic") {
            params.orthographic = true;
        } else if (type != "perspective") {
            diag.Warn(cd.loc, "camera " + Quote(type) + " is not supported; using perspective");
        }
        params.fovDeg = cp.GetFloat("fov", 90.f);
        float halffov = cp.GetFloat("halffov", -1.f);
        if (halffov > 0) params.fovDeg = 2 * halffov;
        if (options.fov > 0) params.fovDeg = options.fov;
        if (!(params.fovDeg > 0 && params.fovDeg < 180)) {
            const Param *p = cp.Find("fov");
            throw SceneError(p ? p->loc : cd.loc, "camera fov must be between 0 and 180 degrees");
        }
        std::vector<float> sw = cp.GetFloats("screenwindow");
        if (sw.size() == 4)
            for (int i = 0; i < 4; ++i) params.screenWindow[i] = sw[size_t(i)];
        params.lensRadius = cp.GetFloat("lensradius", 0.f);
        params.focalDistance = cp.GetFloat("focaldistance", 1e6f);
        scene.features.lens = params.lensRadius > 0;
        double frame = cp.GetFloat("frameaspectratio", float(double(xres) / yres));
        for (const char *n : {"shutteropen", "shutterclose"}) cp.MarkUsed(n);
        cp.ReportUnused(diag, "camera");

        Transform worldFromCamera = cd.cameraFromWorld.Inverse();
        if (options.lookAt) {
            const auto &v = *options.lookAt;
            try {
                worldFromCamera = LookAt({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}).Inverse();
            } catch (const std::invalid_argument &e) {
                throw SceneError(std::string("--lookat: ") + e.what());
            }
        }
        // Render in camera-centred world space (pbrt-v4 "cameraworld"): far-away scenes keep
        // full float precision near the viewer.
        Vec3d eye = worldFromCamera.Point(Vec3d(0, 0, 0));
        scene.renderFromWorld = options.cameraRelative ? Translate(-eye) : Transform();
        scene.camera = std::make_unique<Camera>(params, scene.renderFromWorld * worldFromCamera,
                                                scene.resolution, frame);

        const ParamSet &sp = desc.sampler.params;
        int spp;
        if (desc.sampler.type == "stratified") {
            // In 64 bits: the product of two file values must not overflow.
            int64_t n = int64_t(sp.GetInt("xsamples", 4)) * sp.GetInt("ysamples", 4);
            spp = int(std::clamp<int64_t>(n, -(int64_t(1) << 30), int64_t(1) << 30));
            sp.MarkUsed("jitter");
        } else {
            spp = sp.GetInt("pixelsamples", desc.sampler.type == "random" ? 4 : 16);
        }
        sp.MarkUsed("dimensions");
        sp.MarkUsed("seed");
        if (options.spp > 0) spp = options.spp;
        const int maxSpp = 1 << 16;
        if (spp <= 0 || spp > maxSpp)
            throw SceneError(desc.sampler.loc, "samples per pixel " + std::to_string(spp) +
                                                   " out of range (1 to " + std::to_string(maxSpp) + ")");
        scene.spp = spp;
        sp.ReportUnused(diag, "sampler");

        const ParamSet &fp = desc.filter.params;
        Filter f;
        std::string ft = desc.filter.type;
        bool known = ft == "box" || ft == "gaussian" || ft == "triangle" || ft == "mitchell";
        if (known) {
            // pbrt-v3 radii: 0.5 for the box, 2 for the others.
            float defaultRadius = ft == "box" ? 0.5f : 2.f;
            f.radiusX = fp.GetFloat("xwidth", defaultRadius);
            f.radiusY = fp.GetFloat("ywidth", defaultRadius);
        }
        if (ft == "box") {
            f.kind = Filter::Kind::Box;
        } else if (ft == "gaussian") {
            f.kind = Filter::Kind::Gaussian;
            f.alpha = fp.GetFloat("alpha", 2.f);
        } else if (ft == "triangle") {
            f.kind = Filter::Kind::Triangle;
        } else if (ft == "mitchell") {
            f.kind = Filter::Kind::Mitchell;
            f.B = fp.GetFloat("B", 1.f / 3);
            f.C = fp.GetFloat("C", 1.f / 3);
        } else {
            diag.Warn(desc.filter.loc, "pixel filter " + Quote(ft) + " is not supported; using gaussian");
            f.kind = Filter::Kind::Gaussian;
            f.radiusX = f.radiusY = 2;
            for (const Param &p : fp.Params()) p.lookedUp = true;
        }
        if (!(f.radiusX > 0 && f.radiusY > 0 && f.radiusX <= 16 && f.radiusY <= 16))
            throw SceneError(desc.filter.loc, "pixel filter width must be in (0, 16]");
        scene.filter = f;
        fp.ReportUnused(diag, "pixel filter");

        const ParamSet &ip = desc.integrator.params;
        scene.integratorName = desc.integrator.type;
        int maxDepth = ip.GetInt("maxdepth", 5);
        // Only an Integrator the file names is worth a warning (pbrt's default is "path").
        if (desc.integrator.type != "whitted" && desc.integrator.loc.Valid())
            diag.Warn(desc.integrator.loc, "integrator " + Quote(desc.integrator.type) +
                                               " is rendered with Whitted (maxdepth " +
                                               std::to_string(options.maxDepth >= 0 ? options.maxDepth : maxDepth) + ")");
        for (const Param &p : ip.Params()) p.lookedUp = true;  // other integrators' settings
        if (options.maxDepth >= 0) maxDepth = options.maxDepth;
        if (maxDepth < 0 || maxDepth > 1000)
            throw SceneError(desc.integrator.loc, "maxdepth " + std::to_string(maxDepth) + " out of range (0 to 1000)");
        scene.maxDepth = maxDepth;
    }

    // ---- Shapes ---------------------------------------------------------------------------

    // pbrt's "alpha" / "shadowalpha": a constant 0 removes the shape from all rays / from
    // shadow rays (pbrt-v3 cuts out only where alpha is exactly 0). Textured alpha is not
    // supported and treated as opaque.
    unsigned VisibilityMask(const ShapeDesc &s) {
        const ParamSet &ps = s.params;
        float alpha = 1, shadowAlpha = 1;
        for (const char *n : {"alpha", "shadowalpha"}) {
            const Param *p = ps.Find(n);
            if (!p) continue;
            if (p->type == ParamType::Texture) {
                diag.WarnOnce(std::string("texalpha:") + n, p->loc,
                              std::string("textured \"") + n + "\" is not supported; treated as opaque");
                ps.MarkUsed(n);
                continue;
            }
            (std::string(n) == "alpha" ? alpha : shadowAlpha) = ps.GetFloat(n, 1.f);
        }
        if (!ps.Has("shadowalpha") || ps.Find("shadowalpha")->type == ParamType::Texture)
            shadowAlpha = alpha;
        unsigned mask = AllRays;
        if (alpha == 0) mask &= ~CameraRays;
        if (shadowAlpha == 0) mask &= ~ShadowRays;
        return mask;
    }

    // Creates the geometry of one shape and adds it to `accel`; records its ShapeInfo in
    // `infos` (by accel shape index). Returns the shape index, or -1 if skipped.
    int AddShapeTo(Accel &accel, std::vector<ShapeInfo> &infos, const ShapeDesc &s,
                   const Transform &renderFromObject) {
        ShapeFactoryContext ctx{desc, diag, options.precision, options.maxMemory};
        ShapeGeometry geom = CreateShapeGeometry(s, renderFromObject, ctx);
        if (!geom.mesh && !geom.analytic) return -1;  // skipped with a warning
        if (options.tessellate > 0 && geom.analytic) {  // [validate hook] --tessellate N
            try {
                if (auto twin = MakeTessellatedMesh(*geom.analytic, options.tessellate)) {
                    geom.mesh = std::move(twin);
                    geom.analytic.reset();
                }
            } catch (const std::length_error &e) {
                throw SceneError(s.loc, e.what());
            }
        }
        unsigned mask = VisibilityMask(s);
        if (mask == 0) return -1;  // alpha 0: cut out entirely
        int material = MaterialForShape(s);
        s.params.ReportUnused(diag, "shape " + Quote(s.type));
        int index;
        if (geom.mesh) {
            scene.features.meshes++;
            scene.features.triangles += geom.mesh->NumTriangles();
            index = accel.AddMesh(std::move(geom.mesh), mask);
        } else {
            scene.features.analyticShapes++;
            index = accel.AddAnalytic(std::move(geom.analytic), mask);
        }
        if (int(infos.size()) <= index) infos.resize(size_t(index) + 1);
        infos[size_t(index)] = {material, -1, s.directiveIndex, s.type, -1};
        const Material &m = scene.materials[size_t(material)];
        if (m.MayReflectSpecularly()) scene.features.specularReflection = true;
        if (m.MayTransmit()) scene.features.transmission = true;
        return index;
    }

    void AddShape(const ShapeDesc &s, const Transform &renderFromObject) {
        int index = AddShapeTo(*scene.accel, scene.shapes, s, renderFromObject);
        if (index >= 0 && s.areaLight >= 0) AddAreaLight(s, index);
    }

    // ObjectInstance: each ObjectBegin group becomes one committed prototype, shared by all
    // its instances (Embree instances; one level, as in pbrt-v3).
    std::map<std::string, std::pair<std::shared_ptr<const Accel>, int>> prototypeOf;

    void AddInstance(const InstanceDesc &inst) {
        auto it = prototypeOf.find(inst.object);
        if (it == prototypeOf.end()) {
            const ObjectDesc *obj = nullptr;
            for (const ObjectDesc &o : desc.objects)
                if (o.name == inst.object) obj = &o;
            if (!obj) throw SceneError(inst.loc, "unknown object " + Quote(inst.object));
            AccelOptions ao;
            ao.precision = options.precision;
            auto proto = std::make_shared<Accel>(ao);
            std::vector<ShapeInfo> infos;
            for (const ShapeDesc &s : obj->shapes) {
                if (s.areaLight >= 0)
                    diag.Warn(s.loc, "area lights inside object instances are not supported (as in pbrt-v3); the shape does not emit");
                AddShapeTo(*proto, infos, s, s.worldFromObject);
            }
            proto->Commit();
            scene.prototypes.push_back(std::move(infos));
            it = prototypeOf.emplace(inst.object, std::make_pair(proto, int(scene.prototypes.size()) - 1)).first;
        }
        if (it->second.first->NumShapes() == 0) return;
        int index = scene.accel->AddInstance(it->second.first, scene.renderFromWorld * inst.worldFromInstance);
        if (int(scene.shapes.size()) <= index) scene.shapes.resize(size_t(index) + 1);
        ShapeInfo info;
        info.type = "instance";
        info.prototype = it->second.second;
        scene.shapes[size_t(index)] = info;
    }

    void AddAreaLight(const ShapeDesc &s, int shape) {
        const AreaLightDesc &a = desc.areaLights[size_t(s.areaLight)];
        const ParamSet &ps = a.params;
        if (a.type != "diffuse" && a.type != "area") {  // pbrt-v3 accepts both names
            diag.WarnOnce("arealight:" + a.type, a.loc,
                          "area light " + Quote(a.type) + " is not supported; shapes using it do not emit");
            return;
        }
        RGB L = ps.GetRGB("L", RGB(1)) * ScaleParam(ps);
        bool twoSided = ps.GetBool("twosided", false);
        int n = ps.GetInt("nsamples", ps.GetInt("samples", 1));
        if (options.lightSamples > 0) n = options.lightSamples;
        if (n < 1 || n > 4096) throw SceneError(a.loc, "area light nsamples must be 1 to 4096");
        const AnalyticShape *analytic = scene.accel->Analytic(shape);
        if (analytic && !analytic->CanSample()) {
            diag.Warn(s.loc, "area lights on \"" + s.type + "\" shapes are not supported; the shape does not emit");
            return;
        }
        scene.lights.push_back(std::make_unique<DiffuseAreaLight>(analytic, scene.accel->Mesh(shape), L, twoSided, n));
        scene.shapes[size_t(shape)].areaLight = int(scene.lights.size()) - 1;
        scene.features.areaLights = true;
        reportAreaLights.push_back(&a);
    }
    std::vector<const AreaLightDesc *> reportAreaLights;

    void BuildShapes() {
        AccelOptions ao;
        ao.precision = options.precision;
        scene.accel = std::make_unique<Accel>(ao);
        for (const ShapeDesc &s : desc.shapes) AddShape(s, scene.renderFromWorld * s.worldFromObject);
        for (const InstanceDesc &inst : desc.instances) AddInstance(inst);
        for (const AreaLightDesc *a : reportAreaLights) a->params.ReportUnused(diag, "area light");
        auto start = std::chrono::steady_clock::now();
        scene.accel->Commit();
        scene.buildSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
};

}  // namespace

RenderScene BuildRenderScene(const SceneDescription &desc, const RenderOptions &options,
                             Diagnostics &diag) {
    RenderScene scene;
    Builder b{desc, options, diag, scene, {}, {}, {}, {}, {}, {}};
    b.sharedMaterial.assign(desc.materials.size(), -1);
    // Material 0: pbrt's default, matte with Kd 0.5.
    Material def;
    def.kind = Material::Kind::Matte;
    def.typeName = "matte";
    def.Kd = b.Constant(RGB(0.5f));
    def.sigma = b.Constant(RGB(0));
    scene.materials.push_back(def);

    b.BuildCameraAndFilm();
    b.BuildTextures();
    b.BuildLights();
    b.BuildShapes();
    if (scene.lights.empty())
        diag.Warn(desc.sourceFile.empty() ? FileLoc{} : FileLoc{desc.sourceFile, 0, 0},
                  "the scene has no light sources");
    return scene;
}

}  // namespace prism
