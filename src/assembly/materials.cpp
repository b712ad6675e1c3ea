#include "assembly/materials.h"

#include <algorithm>
#include <cmath>

#include "assembly/textures.h"
#include "core/file_io.h"
#include "render/bsdf.h"
#include "render/materials.h"
#include "render/texture.h"
#include "scene/scene_description.h"

namespace prism {

// A Material directive's parameters as the models' Creates read them (render/material.h
// MaterialParams), looked up first among the shape's parameters (pbrt lets a Shape override its
// material's parameters) and then the material's.
class MaterialBuilder::SceneMaterialParams : public MaterialParams {
  public:
    SceneMaterialParams(MaterialBuilder &b, const MaterialDesc &m, const ParamSet *shape,
                        int descIndex, int depth)
        : b_(b),
          m_(m),
          shape(shape),
          mat(m.params),
          descIndex_(descIndex),
          depth_(depth),
          context_("material " + Quote(m.type)) {}

    const ParamSet &Src(const std::string &name) const {
        if (shape && shape->Has(name)) {
            usedShape = true;
            return *shape;
        }
        return mat;
    }
    const std::string &Context() const override { return context_; }
    const std::string &Type() const override { return m_.type; }
    bool Has(const char *n) const override { return (shape && shape->Has(n)) || mat.Has(n); }
    int Int(const char *n, int def) const override { return Src(n).GetInt(n, def); }
    float Float(const char *n, float def) const override { return Src(n).GetFloat(n, def); }
    bool Bool(const char *n, bool def) const override { return Src(n).GetBool(n, def); }
    std::string String(const char *n, const std::string &def) const override {
        return Src(n).GetString(n, def);
    }
    std::vector<std::string> Strings(const char *n) const override { return Src(n).GetStrings(n); }
    FileLoc Loc(const char *n) const override {
        const Param *p = Src(n).Find(n);
        return p ? p->loc : m_.loc;
    }
    void Warn(const FileLoc &loc, const std::string &message) const override {
        b_.diag.Warn(loc, message);
    }
    void WarnUnread(const std::string &why) const override {
        WarnIgnoredRest(mat, b_.diag, context_, why);
    }
    void MarkUsed(const char *n) const override { Src(n).MarkUsed(n); }
    TexturePtr SpectrumTex(const char *n, RGB def) const override {
        return TextureParam(b_.ctx, Src(n), n, false, def);
    }
    TexturePtr FloatTex(const char *n, float def) const override {
        const ParamSet &ps = Src(n);
        const Param *p = ps.Find(n);
        if (p && p->type == ParamType::RGB) {
            // pbrt-v4 takes a spectrum where Prism reads a number (a dielectric's "spectrum
            // eta", "glass-BK7"): its luminance-weighted mean. An RGB renderer has no
            // wavelengths to disperse, so a varying one is said.
            const RGB c = ps.GetRGB(n, RGB(def));
            const float v = c.Luminance();
            if (c.r != c.g || c.g != c.b)
                Warn(p->loc, context_ + ": \"" + n + "\" varies with wavelength; rendered as " +
                                 std::to_string(v) +
                                 " (its luminance-weighted mean), without dispersion");
            return Constant(RGB(v));
        }
        return TextureParam(b_.ctx, ps, n, true, RGB(def));
    }
    TexturePtr AnyTex(const char *n, RGB def) const override {
        const ParamSet &ps = Src(n);
        const Param *p = ps.Find(n);
        if (p && p->type == ParamType::Texture) {
            std::string tn = ps.GetTexture(n);
            if (!b_.ctx.rgbTextures.count(tn) && b_.ctx.floatTextures.count(tn))
                return b_.ctx.floatTextures[tn];
            return TextureParam(b_.ctx, ps, n, false, def);
        }
        if (p && (p->type == ParamType::Float || p->type == ParamType::Integer))
            return Constant(RGB(ps.GetFloat(n, def.r)));
        return TextureParam(b_.ctx, ps, n, false, def);
    }
    RGB Spectrum(const char *n, RGB def) const override { return Src(n).GetRGB(n, def); }
    TexturePtr Map(const char *n) const override {
        if (!Has(n)) return nullptr;
        return WithTexCoordParams(SpectrumTex(n, RGB(1)), shape, mat, n);
    }
    std::shared_ptr<const Material> NamedMaterial(const std::string &name,
                                                  const FileLoc &loc) const override {
        return b_.NamedMaterialRef(name, descIndex_, loc, depth_);
    }
    int MixDepth() const override { return depth_; }
    bool RoughGlassRendered() const override {
        return b_.ctx.scene.integrator->Traits().roughGlass;
    }
    int PbrtVersion() const override { return b_.ctx.desc.pbrtVersion.version == 4 ? 4 : 3; }
    std::string ReadFile(const char *n, const std::string &what) const override {
        const std::string file = String(n, "");
        if (file.empty())
            throw SceneError(Loc(n), what + ": \"" + std::string(n) + "\" is required");
        const std::string path = ResolveScenePath(b_.ctx.desc, file);
        CheckReadConfinement(path, Loc(n), what, file);
        return ReadFileOrThrow(path, Loc(n), b_.ctx.budget, what + " " + Quote(file));
    }

  private:
    MaterialBuilder &b_;
    const MaterialDesc &m_;

  public:
    const ParamSet *shape;
    const ParamSet &mat;
    mutable bool usedShape = false;

  private:
    int descIndex_, depth_;
    std::string context_;
};

namespace {

// pbrt's default material, and what an unknown one becomes: matte, Kd 0.5, Lambertian.
Material DefaultMatte(TexturePtr kd = Constant(RGB(0.5f))) {
    return Material(std::make_shared<MatteMaterial>(std::move(kd), Constant(RGB(0))), "matte");
}

}  // namespace

MaterialBuilder::MaterialBuilder(BuildContext &ctx) : BuildStep(ctx) {
    sharedMaterial_.assign(desc.materials.size(), -1);
    Material def = DefaultMatte();
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
        return std::make_shared<Material>(DefaultMatte());
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

// Material "(every material)": the shading normal's perturbation (render/bump.cpp), read here
// for each material, from the material or, for a shape's own material parameters, the shape.
// Parameters:
//   bumpmap (v4: displacement)  texture   (none)  a float height texture: the shading normal
//                                                 follows its gradient (a constant moves
//                                                 nothing)
//   normalmap                   texture   (none)  a tangent-space normal map: pbrt-v4's "string
//                                                 normalmap" (an image file, read linearly) or
//                                                 a Prism "texture normalmap"
//   normalscale                 float     1       Prism: the map's x and y scale (glTF's
//                                                 normalTexture.scale)
//   normalmaptexcoord           integer   0       Prism: the uv set the map reads
//   normalmaptransform          float[5]  (none)  Prism: a transform of the map's uv (offset u v,
//                                                 rotation in radians, scale u v)
void MaterialBuilder::ShadingPerturbation(Material &mat, const SceneMaterialParams &mp,
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
            mat.normalMap = mp.SpectrumTex("normalmap", RGB(0.5f, 0.5f, 1.f));
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
    SceneMaterialParams mp(*this, m, shapeParams, descIndex, depth);
    mp.mat.MarkUsed("type");
    Material perturbation;
    ShadingPerturbation(perturbation, mp, m);
    std::shared_ptr<const MaterialModel> model = CreateMaterialModel(m.type, mp, m.loc);
    Material mat;
    if (model) {
        mat = Material(std::move(model), m.type);
    } else {
        // measured and unknown types.
        const char *colour = mp.Has("Kd")            ? "Kd"
                             : mp.Has("reflectance") ? "reflectance"
                             : mp.Has("color")       ? "color"
                                                     : nullptr;
        diag.Warn(m.loc, "material " + Quote(m.type) + " is not supported; using matte" +
                             (colour ? std::string(" with its \"") + colour + "\"" : ""));
        mat = DefaultMatte(colour ? mp.SpectrumTex(colour, RGB(0.5f)) : Constant(RGB(0.5f)));
        mat.typeName = m.type;
        m.params.MarkAllUsed();
    }
    mat.bump = perturbation.bump;
    mat.normalMap = perturbation.normalMap;
    mat.normalScale = perturbation.normalScale;
    mat.normalMapUVSet = perturbation.normalMapUVSet;
    if (usedShape) *usedShape = mp.usedShape;
    return mat;
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
