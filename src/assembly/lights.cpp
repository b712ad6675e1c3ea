#include "assembly/lights.h"

#include "assembly/scene_effects.h"
#include "assembly/textures.h"
#include "render/area_light.h"
#include "render/infinite_light.h"

namespace prism {

void BuildLights(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    RenderScene &scene = ctx.scene;
    Diagnostics &diag = ctx.diag;
    for (const LightDesc &l : desc.lights) {
        const size_t lightsBefore = scene.lights.size();
        const ParamSet &ps = l.params;
        Transform renderFromLight = scene.renderFromWorld * l.worldFromLight;
        RGB sc = ScaleParam(ps);
        if (l.type == "point") {
            RGB I = ps.GetRGB("I", RGB(1)) * sc;
            Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
            scene.lights.push_back(
                std::make_unique<PointLight>(Vec3f(renderFromLight.Point(Vec3d(from))), I));
        } else if (l.type == "spot") {
            RGB I = ps.GetRGB("I", RGB(1)) * sc;
            Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
            Vec3f to = ps.GetPoint3("to", Vec3f(0, 0, 1));
            if (from == to)
                throw SceneError(l.loc, "spot light \"from\" and \"to\" are the same point");
            float cone = ps.GetFloat("coneangle", 30.f), delta = ps.GetFloat("conedeltaangle", 5.f);
            Vec3d dir = Normalize(renderFromLight.Vector(Vec3d(to) - Vec3d(from)));
            scene.lights.push_back(std::make_unique<SpotLight>(
                Vec3f(renderFromLight.Point(Vec3d(from))), Vec3f(dir), I, cone, delta));
        } else if (l.type == "distant") {
            RGB L = ps.GetRGB("L", RGB(1)) * sc;
            Vec3f from = ps.GetPoint3("from", Vec3f(0, 0, 0));
            Vec3f to = ps.GetPoint3("to", Vec3f(0, 0, 1));
            Vec3d w = renderFromLight.Vector(Vec3d(from) - Vec3d(to));
            if (!(Length(w) > 0))
                throw SceneError(l.loc, "distant light \"from\" and \"to\" are the same point");
            scene.lights.push_back(std::make_unique<DistantLight>(Vec3f(Normalize(w)), L));
        } else if (l.type == "infinite") {
            RGB L = ps.GetRGB("L", RGB(1)) * sc;
            std::string mapname = ps.GetString("mapname", "");
            std::shared_ptr<const Image> map;
            if (!mapname.empty())
                map = LoadSceneImage(ctx, l, mapname, ReadImageOptions::Encoding::Auto, "mapname");
            int n = ps.GetInt("nsamples", ps.GetInt("samples", 1));
            if (ctx.settings.lightSamples > 0) n = ctx.settings.lightSamples;
            if (n < 1 || n > 4096)
                throw SceneError(l.loc, "infinite light nsamples must be 1 to 4096");
            scene.lights.push_back(std::make_unique<InfiniteLight>(renderFromLight, L, map, n));
            scene.features.environment = true;
        } else {
            diag.WarnOnce(
                "light:" + l.type, l.loc,
                "light source " + Quote(l.type) + " is not supported; every such light is ignored");
            ps.MarkAllUsed();
        }
        ps.ReportUnused(diag, "light " + Quote(l.type));
        if (scene.lights.size() > lightsBefore)
            NoteLightEffects(ctx, "LightSource " + Quote(l.type), l.loc);
    }
}

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
    RGB L = ps.GetRGB("L", RGB(1)) * ScaleParam(ps);
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
    if (ps.Has("emissionmap")) {
        radiance = WithTexCoordParams(TextureParam(ctx, ps, "emissionmap", false, RGB(1)), nullptr,
                                      ps, "emissionmap");
        if (analytic) {
            diag.Warn(ps.Find("emissionmap")->loc,
                      "\"emissionmap\" is read on triangle meshes only; \"" + s.type +
                          "\" emits its constant \"L\"");
            radiance = nullptr;
        } else if (radiance->IsConstant()) {
            L = L * static_cast<const ConstantTexture &>(*radiance).Value();
            radiance = nullptr;
        }
    }
    auto light = std::make_unique<DiffuseAreaLight>(analytic, scene.accel->Mesh(shape), L, twoSided,
                                                    n, radiance);
    const DiffuseAreaLight &al = *light;
    scene.lights.push_back(std::move(light));
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
