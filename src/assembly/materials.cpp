#include "assembly/materials.h"

#include <algorithm>
#include <cmath>

#include "assembly/textures.h"
#include "render/bsdf.h"
#include "render/texture.h"

namespace prism {

// Material parameters, looked up first among the shape's parameters (pbrt lets a Shape
// override its material's parameters) and then the material's.
struct MaterialBuilder::MaterialParams {
    BuildContext &ctx;
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
    TexturePtr RGBTex(const std::string &n, RGB def) {
        return TextureParam(ctx, Src(n), n, false, def);
    }
    TexturePtr FloatTex(const std::string &n, float def) {
        return TextureParam(ctx, Src(n), n, true, RGB(def));
    }
    RGB Rgb(const std::string &n, RGB def) { return Src(n).GetRGB(n, def); }
    bool Bool(const std::string &n, bool def) { return Src(n).GetBool(n, def); }
    bool Has(const std::string &n) { return (shape && shape->Has(n)) || mat.Has(n); }
};

MaterialBuilder::MaterialBuilder(BuildContext &ctx) : BuildStep(ctx) {
    sharedMaterial_.assign(desc.materials.size(), -1);
    Material def;
    def.kind = Material::Kind::Matte;
    def.typeName = "matte";
    def.Kd = Constant(RGB(0.5f));
    def.sigma = Constant(RGB(0));
    def.Prepare();
    scene.materials.push_back(def);
}

// The material a mix names: the latest definition before the mix (pbrt-v3 resolves names
// when the mix is declared), else a later one (pbrt-v4 files may refer forward).
int MaterialBuilder::ResolveNamedMaterial(const std::string &name, int from) const {
    for (int i = std::min(from, int(desc.materials.size())) - 1; i >= 0; --i)
        if (desc.materials[size_t(i)].name == name) return i;
    for (size_t i = size_t(std::max(from, 0)); i < desc.materials.size(); ++i)
        if (desc.materials[i].name == name) return int(i);
    return -1;
}

std::shared_ptr<const Material> MaterialBuilder::NamedMaterialRef(const std::string &name, int from,
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
    if (namedMaterialCache_.size() < desc.materials.size()) {
        namedMaterialCache_.resize(desc.materials.size());
        namedMaterialState_.resize(desc.materials.size(), 0);
    }
    if (namedMaterialState_[size_t(index)] == 2) return namedMaterialCache_[size_t(index)];
    if (namedMaterialState_[size_t(index)] == 1)
        throw SceneError(loc, "mix material refers to itself through " + Quote(name));
    namedMaterialState_[size_t(index)] = 1;
    const MaterialDesc &md = desc.materials[size_t(index)];
    auto m = std::make_shared<Material>(MakeMaterial(md, index, nullptr, nullptr, depth + 1));
    md.params.ReportUnused(diag, "material " + Quote(md.type));
    namedMaterialState_[size_t(index)] = 2;
    namedMaterialCache_[size_t(index)] = m;
    return m;
}

// A spectrum-or-float texture parameter (mix "amount" is a spectrum texture in pbrt-v3 and
// a float texture in v4).
TexturePtr MaterialBuilder::AnyTex(MaterialParams &mp, const std::string &n, RGB def) {
    const ParamSet &ps = mp.Src(n);
    const Param *p = ps.Find(n);
    if (p && p->type == ParamType::Texture) {
        std::string tn = ps.GetTexture(n);
        if (!ctx.rgbTextures.count(tn) && ctx.floatTextures.count(tn)) return ctx.floatTextures[tn];
        return TextureParam(ctx, ps, n, false, def);
    }
    if (p && (p->type == ParamType::Float || p->type == ParamType::Integer))
        return Constant(RGB(ps.GetFloat(n, def.r)));
    return TextureParam(ctx, ps, n, false, def);
}

namespace {

// pbrt-v4 remaps roughness r to alpha = sqrt(r) (v3 used a polynomial that never reaches 0):
// constant u/v roughness of a v4 material ("conductor", "dielectric") is converted here.
void RemapRoughnessAsV4(Material &mat) {
    if (!mat.remapRoughness || !mat.uRoughness->IsConstant() || !mat.vRoughness->IsConstant())
        return;
    auto v4Alpha = [](TexturePtr &t) {
        if (auto *c = dynamic_cast<const ConstantTexture *>(t.get()))
            t = Constant(RGB(std::sqrt(std::max(0.f, c->Value().r))));
    };
    v4Alpha(mat.uRoughness);
    v4Alpha(mat.vRoughness);
    mat.remapRoughness = false;
}

}  // namespace

// pbrt-v3 `roughness` / `uroughness` / `vroughness` for the materials that have all three.
void MaterialBuilder::Roughness(Material &mat, MaterialParams &mp, float def) {
    mat.roughness = mp.FloatTex("roughness", def);
    mat.uRoughness = mp.Has("uroughness") ? mp.FloatTex("uroughness", def) : nullptr;
    mat.vRoughness = mp.Has("vroughness") ? mp.FloatTex("vroughness", def) : nullptr;
    mat.remapRoughness = mp.Bool("remaproughness", true);
}

// pbrt-v3 "bumpmap" (v4 "displacement"): a float texture; a tangent-space normal map, as
// pbrt-v4's "string normalmap" (an image file, read linearly) or a Prism "texture normalmap",
// with the Prism extension "float normalscale" (glTF's normalTexture.scale; default 1) and
// "normalmaptexcoord" / "normalmaptransform" (WithTexCoordParams).
void MaterialBuilder::ShadingPerturbation(Material &mat, MaterialParams &mp,
                                          const MaterialDesc &m) {
    for (const char *n : {"bumpmap", "displacement"})
        if (!mat.bump && mp.Has(n)) {
            mat.bump = mp.FloatTex(n, 0.f);
            if (mat.bump->IsConstant()) mat.bump = nullptr;  // a constant moves nothing
        }
    if (mp.Has("normalmap")) {
        const ParamSet &ps = mp.Src("normalmap");
        const Param *p = ps.Find("normalmap");
        if (p->type == ParamType::String) {
            std::string file = ps.GetString("normalmap", "");
            auto img =
                LoadSceneImage(ctx, m, file, ReadImageOptions::Encoding::Linear, "normalmap");
            mat.normalMap =
                std::make_shared<ImageTexture>(TextureMapping{}, img, WrapMode::Repeat, 1.f, false);
        } else {
            mat.normalMap = mp.RGBTex("normalmap", RGB(0.5f, 0.5f, 1.f));
        }
        mat.normalMap = WithTexCoordParams(mat.normalMap, mp.shape, mp.mat, "normalmap");
        if (mp.Has("normalmaptexcoord"))
            mat.normalMapUVSet = mp.Src("normalmaptexcoord").GetInt("normalmaptexcoord", 0);
        mat.normalScale = mp.Src("normalscale").GetFloat("normalscale", 1.f);
    }
}

// `descIndex` is the material's position in desc.materials (mix names resolve from there);
// `depth` counts enclosing mixes.
Material MaterialBuilder::MakeMaterial(const MaterialDesc &m, int descIndex,
                                       const ParamSet *shapeParams, bool *usedShape, int depth) {
    MaterialParams mp{ctx, shapeParams, m.params};
    Material mat;
    mat.typeName = m.type;
    std::string type = m.type;
    // pbrt-v4 names mapped onto the same models.
    if (type == "diffuse")
        type = "matte";
    else if (type == "dielectric")
        type = "glass";
    else if (type == "conductor")
        type = "metal";
    else if (type == "interface")
        type = "none";
    else if (type == "diffusetransmission")
        type = "translucent";
    mp.mat.MarkUsed("type");
    ShadingPerturbation(mat, mp, m);
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
        // Rough glass (pbrt-v3: uroughness/vroughness, v4: roughness) is glossy for the
        // distribution integrator; Whitted renders it smooth whatever its roughness (a value
        // or a float texture), and a roughness that may be non-zero is named once per material.
        TexturePtr rough = mp.FloatTex("roughness", 0.f);
        mat.uRoughness = mp.Has("uroughness") ? mp.FloatTex("uroughness", 0.f) : rough;
        mat.vRoughness = mp.Has("vroughness") ? mp.FloatTex("vroughness", 0.f) : rough;
        mat.remapRoughness = mp.Bool("remaproughness", true);
        bool isRough = false;
        for (const TexturePtr &r : {mat.uRoughness, mat.vRoughness}) {
            auto *c = dynamic_cast<const ConstantTexture *>(r.get());
            if (!c || c->Value().r > 0) isRough = true;
        }
        if (m.type == "dielectric") RemapRoughnessAsV4(mat);
        if (isRough && !ctx.scene.integrator->Traits().roughGlass)
            diag.Warn(m.loc,
                      "rough glass is rendered as smooth glass by the Whitted integrator "
                      "(Integrator \"distribution\" renders it rough)");
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
        if (m.type == "conductor") RemapRoughnessAsV4(mat);
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
    } else if (type == "gltf") {
        MakeGltfMaterial(mat, mp);
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
        m.params.MarkAllUsed();
    }
    if (usedShape) *usedShape = mp.usedShape;
    return mat;
}

// Prism's "gltf" material (written by the glTF reader, usable in .pbrt files): the glTF 2.0
// metallic-roughness model (render/gltf_material.h). Maps are named textures; "<map>transform"
// is KHR_texture_transform as [offset.u offset.v rotation scale.u scale.v], "<map>texcoord" 1
// reads the mesh's second uv set (WithTexCoordParams).
void MaterialBuilder::MakeGltfMaterial(Material &mat, MaterialParams &mp) {
    mat.kind = Material::Kind::Gltf;
    GltfMaterialParams &g = mat.gltf;
    auto map = [&](const char *name) -> TexturePtr {
        if (!mp.Has(name)) return nullptr;
        return WithTexCoordParams(mp.RGBTex(name, RGB(1)), mp.shape, mp.mat, name);
    };
    const RGB baseFactor = mp.Rgb("basecolor", RGB(1));
    if (TexturePtr t = map("basecolormap"))
        g.baseColor = std::make_shared<ScaleTexture>(t, Constant(baseFactor));
    else
        g.baseColor = Constant(baseFactor);
    g.metallic = mp.Src("metallic").GetFloat("metallic", 1.f);
    g.roughness = mp.Src("roughness").GetFloat("roughness", 1.f);
    g.metallicRoughness = map("metallicroughnessmap");
    const RGB emissive = mp.Rgb("emissive", RGB(0));
    // Emission the material carries itself (the glTF reader turns untextured emission into an
    // area light on the mesh instead, which light samples reach).
    if (TexturePtr t = map("emissivemap")) {
        if (!emissive.IsBlack()) g.emissive = std::make_shared<ScaleTexture>(t, Constant(emissive));
    } else if (!emissive.IsBlack()) {
        g.emissive = Constant(emissive);
    }
    g.occlusion = map("occlusionmap");
    g.occlusionStrength = mp.Src("occlusionstrength").GetFloat("occlusionstrength", 1.f);
    g.ior = mp.Src("ior").GetFloat("ior", 1.5f);
    g.transmission = mp.Src("transmission").GetFloat("transmission", 0.f);
    g.specular = mp.Src("specular").GetFloat("specular", 1.f);
    g.specularColor = mp.Rgb("specularcolor", RGB(1));
    g.clearcoat = mp.Src("clearcoat").GetFloat("clearcoat", 0.f);
    g.clearcoatRoughness = mp.Src("clearcoatroughness").GetFloat("clearcoatroughness", 0.f);
}

// The scene material index for a shape: the shared one, or a new one when the shape's own
// parameters override the material's.
int MaterialBuilder::MaterialForShape(const ShapeDesc &s) {
    if (s.material < 0) return 0;
    const MaterialDesc &md = desc.materials[size_t(s.material)];
    bool usedShape = false;
    Material m = MakeMaterial(md, s.material, &s.params, &usedShape);
    if (usedShape) {
        m.Prepare();
        scene.materials.push_back(std::move(m));
        return int(scene.materials.size()) - 1;
    }
    int &shared = sharedMaterial_[size_t(s.material)];
    if (shared < 0) {
        m.Prepare();
        scene.materials.push_back(std::move(m));
        shared = int(scene.materials.size()) - 1;
        md.params.ReportUnused(diag, "material " + Quote(md.type));
    }
    return shared;
}
// [end of materials helper region]

}  // namespace prism
