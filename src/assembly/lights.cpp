#include "assembly/lights.h"

#include <cmath>

#include "assembly/directive_params.h"
#include "assembly/scene_effects.h"
#include "assembly/textures.h"
#include "render/area_light.h"
#include "render/infinite_light.h"

namespace prism {

namespace {

// A light's emission spectrum `name` ("I", "L"). pbrt-v4 divides a light's spectrum by its
// photometric value: an RGB one (written "rgb" or "color", or absent: the default white) is
// measured by the colour space's white and keeps its magnitude; any other (a blackbody, a named
// illuminant, samples) comes out at luminance 1. pbrt-v3 uses the spectrum as it is. An RGB
// value is an emission of the colour space it was written in (core/color_space.h), and the
// default white is the white of the light's own (`cs`).
RGB EmissionSpectrum(const BuildContext &ctx, const ParamSet &ps, ColorSpaceId cs, const char *name,
                     RGB def) {
    const RGB value = ps.GetRGB(name, def);
    const Param *q = ps.Find(name);
    if (!q) return MapClipped(SRGBFromIlluminant(cs), value);
    const bool rgb = q->spelledType == "rgb" || q->spelledType == "color";
    if (rgb) return EmissionRGB(*q);
    if (ctx.desc.pbrtVersion.version != 4) return value;
    const double y = value.Luminance();
    return y > 0 ? value * float(1 / y) : RGB(0);
}

// A LightSource's parameters over its ParamSet, images read relative to the scene.
class SceneLightParams : public DirectiveParamsOf<LightParams> {
  public:
    SceneLightParams(BuildContext &ctx, const LightDesc &l)
        : DirectiveParamsOf(l.params, ctx.diag, "light " + Quote(l.type), l.loc),
          ctx_(ctx),
          light_(l) {}
    // Every spectrum a light reads through this is its emission ("I", "L"); "scale" is Scale().
    RGB Spectrum(const char *name, RGB def) const override {
        return EmissionSpectrum(ctx_, ps_, light_.colorSpace, name, def);
    }
    Vec3f Point3(const char *name, Vec3f def) const override { return ps_.GetPoint3(name, def); }
    std::vector<Vec3f> Point3s(const char *name) const override { return ps_.GetPoint3s(name); }
    RGB Scale() const override { return ScaleParam(ps_); }
    std::shared_ptr<const Image> LoadImage(const char *name,
                                           const std::string &file) const override {
        return LoadSceneImage(ctx_, light_, file, ReadImageOptions::Encoding::Auto, name);
    }

  private:
    BuildContext &ctx_;
    const LightDesc &light_;
};

}  // namespace

void BuildLights(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    for (const LightDesc &l : desc.lights) {
        const ParamSet &ps = l.params;
        const SceneLightParams params(ctx, l);
        const LightInputs in{params,
                             scene.renderFromWorld * l.worldFromLight,
                             l.loc,
                             ctx.settings.lightSamples,
                             desc.pbrtVersion.version,
                             scene.renderFromWorld};
        std::unique_ptr<Light> light = CreateLight(l.type, in);
        if (!light) {
            diag.WarnOnce(
                "light:" + l.type, l.loc,
                "light source " + Quote(l.type) + " is not supported; every such light is ignored");
            ps.MarkAllUsed();
        }
        ps.ReportUnused(diag, "light " + Quote(l.type));
        if (!light) continue;
        // A light that is neither delta nor an area light surrounds the scene (infinite).
        if (!light->IsDelta() && !light->IsArea()) scene.features.environment = true;
        scene.lights.push_back(std::move(light));
        scene.lightMedia.resize(scene.lights.size());
        scene.lightMedia.back() = {l.medium, l.medium};
        NoteLightEffects(ctx, "LightSource " + Quote(l.type), l.loc);
    }
}

// AreaLightSource "diffuse", "area" (pbrt-v3 accepts both names). Parameters:
//   L                   spectrum  1       emitted radiance
//   scale               spectrum  1       multiplies L
//   twosided            bool      false   emits from both sides
//   nsamples (samples)  integer   1       light samples per shading point, 1 to 4096;
//                                         --light-samples wins
//   power               float     (none)  pbrt-v4: the radiant power; L is scaled by it over
//                                         pi x area (x 2 two-sided); on a mesh, each
//                                         triangle's own (each emits it, as in pbrt-v4)
//   emissionmap         texture   (none)  Prism: L x the texture (triangle meshes)
//   filename            string    (none)  pbrt-v4: an image of the radiance over the
//                                         shape's (u, v) (triangle meshes), times scale;
//                                         not with L or emissionmap
const AreaLightDesc *AddAreaLight(BuildContext &ctx, const ShapeDesc &s, int shape) {
    const SceneDescription &desc = ctx.desc;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    const AreaLightDesc &a = desc.areaLights[size_t(s.areaLight)];
    const ParamSet &ps = a.params;
    if (a.type != "diffuse" && a.type != "area") {  // pbrt-v3 accepts both names
        diag.WarnOnce(
            "arealight:" + a.type, a.loc,
            "area light " + Quote(a.type) + " is not supported; shapes using it do not emit");
        return nullptr;
    }
    // pbrt-v4's "filename": the image is the radiance (in sRGB, whatever the ColorSpace).
    const std::string image = ps.GetString("filename", "");
    if (!image.empty())
        for (const char *other : {"L", "emissionmap"})
            if (ps.Has(other))
                throw SceneError(ps.Find("filename")->loc,
                                 "area light: \"filename\" and \"" + std::string(other) +
                                     "\" both give its radiance; give one");
    RGB L = (image.empty() ? EmissionSpectrum(ctx, ps, a.colorSpace, "L", RGB(1)) : RGB(1)) *
            ScaleParam(ps);
    bool twoSided = ps.GetBool("twosided", false);
    int n = ps.GetInt("nsamples", ps.GetInt("samples", 1));
    if (ctx.settings.lightSamples > 0) n = ctx.settings.lightSamples;
    if (n < 1 || n > 4096) throw SceneError(a.loc, "area light nsamples must be 1 to 4096");
    const AnalyticShape *analytic = scene.accel->Analytic(shape);
    if (analytic && !analytic->CanSample()) {
        diag.Warn(s.loc, "area lights on \"" + s.type +
                             "\" shapes are not supported; the shape does not emit");
        return nullptr;
    }
    // Prism extension: "texture emissionmap" (with "emissionmaptexcoord"/"emissionmaptransform",
    // WithTexCoordParams), a textured radiance L × emissionmap(uv) on triangle meshes. The
    // glTF reader writes it for emissive textures.
    TexturePtr radiance;
    const char *mapParam = !image.empty() ? "filename" : ps.Has("emissionmap") ? "emissionmap" : "";
    if (*mapParam) {
        radiance = !image.empty()
                       ? ImageOnSurface(ctx, a, image, "filename")
                       : WithTexCoordParams(TextureParam(ctx, ps, "emissionmap", false, RGB(1)),
                                            nullptr, ps, "emissionmap");
        if (analytic) {
            diag.Warn(ps.Find(mapParam)->loc, "\"" + std::string(mapParam) +
                                                  "\" is read on triangle meshes only; \"" +
                                                  s.type + "\" emits a constant \"L\"");
            radiance = nullptr;
        } else if (radiance->IsConstant()) {
            L = L * static_cast<const ConstantTexture &>(*radiance).Value();
            radiance = nullptr;
        }
    }
    // pbrt-v4's "power": L scaled so the light emits it (render/light.h PhotometricScale:
    // an RGB L keeps its magnitude). pbrt-v4 makes each triangle of a mesh a light of its own,
    // each emitting the power (a quad of two triangles emits twice it): so does Prism, to
    // render pbrt-v4's image, by giving the mesh's light the power per triangle.
    const bool hasPower = ps.Has("power");
    const float power = ps.GetFloat("power", 0);
    if (hasPower && (!(power >= 0) || !std::isfinite(power)))
        throw SceneError(ps.Find("power")->loc,
                         "area light: \"power\" must be finite and not negative");
    auto light = std::make_unique<DiffuseAreaLight>(analytic, scene.accel->Mesh(shape), L, twoSided,
                                                    n, radiance, analytic ? 0.0 : double(power));
    // An analytic shape's L is scaled by the power over Power(): pi x area (x2 two-sided) x L's
    // luminance.
    if (hasPower && analytic) {
        const double P = light->Power(0), y = L.Luminance();
        const double f = P > 0 && y > 0 ? double(power) / P * y : 0;
        light = std::make_unique<DiffuseAreaLight>(analytic, scene.accel->Mesh(shape), L * float(f),
                                                   twoSided, n, radiance);
    }
    const DiffuseAreaLight &al = *light;
    scene.lights.push_back(std::move(light));
    scene.lightMedia.resize(scene.lights.size());
    scene.lightMedia.back() = {s.mediumInside, s.mediumOutside};
    ShapeInfo &info = scene.shapes[size_t(shape)];
    info.areaLight = int(scene.lights.size()) - 1;
    scene.features.areaLights = true;
    std::string why = "AreaLightSource " + Quote(a.type);
    if (al.Textured()) {
        // The hit's uv is read for the emitted radiance.
        scene.accel->SetSurfaceNeeds(
            shape, scene.materials[size_t(info.material)].SurfaceNeeds() | NeedUV);
        const std::string material =
            s.material >= 0 && size_t(s.material) < desc.materials.size()
                ? " of material " + Quote(desc.materials[size_t(s.material)].name)
                : std::string();
        const size_t triangles = scene.accel->Mesh(shape)->NumTriangles();
        why = "emissive texture" + material + " (a textured area light; " +
              std::to_string(al.SampledTriangles()) + " of " + std::to_string(triangles) +
              " triangles emit and are sampled)";
    }
    NoteLightEffects(ctx, why, a.loc);
    return &a;
}

}  // namespace prism
