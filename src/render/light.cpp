#include "render/light.h"

#include <cmath>

namespace prism {

bool PointLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    Vec3f d = pos_ - si.p;
    float dist2 = LengthSquared(d);
    if (!(dist2 > 0)) return false;
    ls->wi = d / std::sqrt(dist2);
    ls->Li = I_ / dist2;
    ls->pLight = pos_;
    ls->infinite = false;
    ls->pdf = 1;
    return true;
}

SpotLight::SpotLight(const Vec3f &pos, const Vec3f &dir, const RGB &I, float coneAngle,
                     float coneDelta)
    : pos_(pos),
      dir_(dir),
      I_(I),
      cosTotalWidth_(float(std::cos(Radians(coneAngle)))),
      cosFalloffStart_(float(std::cos(Radians(coneAngle - coneDelta)))) {}

float SpotLight::Falloff(const Vec3f &w) const {
    float cosTheta = Dot(w, dir_);
    if (cosTheta < cosTotalWidth_) return 0;
    if (cosTheta >= cosFalloffStart_) return 1;
    // pbrt-v3 SpotLight::Falloff: the fourth power of the normalized cosine.
    float delta = (cosTheta - cosTotalWidth_) / (cosFalloffStart_ - cosTotalWidth_);
    return (delta * delta) * (delta * delta);
}

bool SpotLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    Vec3f d = pos_ - si.p;
    float dist2 = LengthSquared(d);
    if (!(dist2 > 0)) return false;
    ls->wi = d / std::sqrt(dist2);
    float f = Falloff(-ls->wi);
    if (f == 0) return false;
    ls->Li = I_ * (f / dist2);
    ls->pLight = pos_;
    ls->infinite = false;
    ls->pdf = 1;
    return true;
}

bool DistantLight::SampleLi(const SurfaceInteraction &, Vec2f, LightSample *ls) const {
    ls->wi = w_;
    ls->Li = L_;
    ls->infinite = true;
    ls->pdf = 1;
    return true;
}

// LightSource "point" (light_list.inc). Parameters:
//   I      spectrum  1        radiant intensity
//   scale  spectrum  1        multiplies I
//   from   point     0 0 0    position, in the light's coordinate system
std::unique_ptr<Light> CreatePointLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB I = p.Spectrum("I", RGB(1)) * p.Scale();
    const Vec3f from = p.Point3("from", Vec3f(0, 0, 0));
    return std::make_unique<PointLight>(Vec3f(in.renderFromLight.Point(Vec3d(from))), I);
}

// LightSource "spot" (light_list.inc). Parameters:
//   I               spectrum  1       radiant intensity on the axis
//   scale           spectrum  1       multiplies I
//   from, to        point     0 0 0, 0 0 1  position and a point on the axis
//   coneangle       float     30      the cone's half angle, degrees
//   conedeltaangle  float     5       the falloff band inside it, degrees
std::unique_ptr<Light> CreateSpotLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB I = p.Spectrum("I", RGB(1)) * p.Scale();
    const Vec3f from = p.Point3("from", Vec3f(0, 0, 0)), to = p.Point3("to", Vec3f(0, 0, 1));
    if (from == to) throw SceneError(in.loc, "spot light \"from\" and \"to\" are the same point");
    const float cone = p.Float("coneangle", 30.f), delta = p.Float("conedeltaangle", 5.f);
    const Vec3d dir = Normalize(in.renderFromLight.Vector(Vec3d(to) - Vec3d(from)));
    return std::make_unique<SpotLight>(Vec3f(in.renderFromLight.Point(Vec3d(from))), Vec3f(dir), I,
                                       cone, delta);
}

// LightSource "distant" (light_list.inc). Parameters:
//   L         spectrum  1              radiance
//   scale     spectrum  1              multiplies L
//   from, to  point     0 0 0, 0 0 1   light travels from "from" toward "to"
std::unique_ptr<Light> CreateDistantLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB L = p.Spectrum("L", RGB(1)) * p.Scale();
    const Vec3f from = p.Point3("from", Vec3f(0, 0, 0)), to = p.Point3("to", Vec3f(0, 0, 1));
    const Vec3d w = in.renderFromLight.Vector(Vec3d(from) - Vec3d(to));
    if (!(Length(w) > 0))
        throw SceneError(in.loc, "distant light \"from\" and \"to\" are the same point");
    return std::make_unique<DistantLight>(Vec3f(Normalize(w)), L);
}

// The Create functions of light_list.inc, each defined beside its class.
#define PRISM_LIGHT(name, create) std::unique_ptr<Light> create(const LightInputs &);
#include "render/light_list.inc"
#undef PRISM_LIGHT

namespace {
struct RegisteredLight {
    const char *name;
    std::unique_ptr<Light> (*create)(const LightInputs &);
};
constexpr RegisteredLight Lights[] = {
#define PRISM_LIGHT(name, create) {name, &create},
#include "render/light_list.inc"
#undef PRISM_LIGHT
};
}  // namespace

std::unique_ptr<Light> CreateLight(const std::string &type, const LightInputs &in) {
    for (const RegisteredLight &r : Lights)
        if (type == r.name) return r.create(in);
    return nullptr;
}

const std::vector<std::string> &LightNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const RegisteredLight &r : Lights) v.push_back(r.name);
        return v;
    }();
    return names;
}

}  // namespace prism
