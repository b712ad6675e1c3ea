#include "render/light.h"

#include <algorithm>
#include <cmath>

#include "image/image.h"

namespace prism {

Vec3f UniformSphereDirection(Vec2f u) {
    const float z = 1 - 2 * u.x, r = std::sqrt(std::max(0.f, 1 - z * z));
    const float phi = float(2 * Pi) * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3f UniformConeDirection(Vec2f u, float cosMax) {
    const float z = (1 - u.x) + u.x * cosMax, r = std::sqrt(std::max(0.f, 1 - z * z));
    const float phi = float(2 * Pi) * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec2f ConcentricDisk(Vec2f u) {
    // Shirley and Chiu's concentric map of the square onto the disk.
    const float ux = 2 * u.x - 1, uy = 2 * u.y - 1;
    if (ux == 0 && uy == 0) return {0, 0};
    float r, theta;
    if (std::abs(ux) > std::abs(uy)) {
        r = ux;
        theta = float(Pi / 4) * (uy / ux);
    } else {
        r = uy;
        theta = float(Pi / 2) - float(Pi / 4) * (ux / uy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

Vec3f DiskOrigin(const SceneSphere &sphere, const Vec3f &d, Vec2f u) {
    Vec3f s, t;
    CoordinateSystem(d, &s, &t);
    const Vec2f c = ConcentricDisk(u);
    return sphere.center + (s * c.x + t * c.y - d) * sphere.radius;
}

namespace {

// A point or spot light's emitted ray. It ignores surfaces within a few ulps of the light
// (tMin), as the shadow rays toward the light do (they stop ShadowEpsilon short of it): a light
// placed exactly on a surface, such as a spot at the apex of its closed lamp shade, would
// otherwise hit that surface at t = 0 and scatter its light out through the wrong side.
void PointEmission(const Vec3f &pos, const Vec3f &w, const RGB &Le, float pdfDir,
                   LightLeSample *ls) {
    ls->ray = Ray{pos, w};
    ls->ray.tMin = (std::max({std::abs(pos.x), std::abs(pos.y), std::abs(pos.z)}) + 1) * 0x1p-20f;
    ls->n = Vec3f(0, 0, 0);
    ls->Le = Le;
    ls->pdfPos = 1;
    ls->pdfDir = pdfDir;
}

}  // namespace

bool PointLight::SampleLe(Vec2f, Vec2f uDir, const SceneSphere &, LightLeSample *ls) const {
    PointEmission(pos_, UniformSphereDirection(uDir), I_, float(1 / (4 * Pi)), ls);
    return true;
}

void PointLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &, const SceneSphere &,
                       float *pdfPos, float *pdfDir) const {
    *pdfPos = 0;
    *pdfDir = float(1 / (4 * Pi));
}

bool SpotLight::SampleLe(Vec2f, Vec2f uDir, const SceneSphere &, LightLeSample *ls) const {
    const Vec3f wl = UniformConeDirection(uDir, cosTotalWidth_);
    Vec3f s, t;
    CoordinateSystem(dir_, &s, &t);
    const Vec3f w = Normalize(s * wl.x + t * wl.y + dir_ * wl.z);
    PointEmission(pos_, w, I_ * Falloff(w), float(1 / (2 * Pi * (1 - double(cosTotalWidth_)))), ls);
    return true;
}

void SpotLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &w, const SceneSphere &,
                      float *pdfPos, float *pdfDir) const {
    *pdfPos = 0;
    *pdfDir =
        Dot(w, dir_) >= cosTotalWidth_ ? float(1 / (2 * Pi * (1 - double(cosTotalWidth_)))) : 0.f;
}

bool DistantLight::SampleLe(Vec2f uPos, Vec2f, const SceneSphere &sphere, LightLeSample *ls) const {
    const Vec3f d = -w_;
    ls->ray = Ray{DiskOrigin(sphere, d, uPos), d};
    ls->n = Vec3f(0, 0, 0);
    ls->Le = L_;
    ls->pdfPos = float(1 / (Pi * double(sphere.radius) * sphere.radius));
    ls->pdfDir = 1;
    return true;
}

void DistantLight::PdfLe(const Vec3f &, const Vec3f &, const Vec3f &, const SceneSphere &sphere,
                         float *pdfPos, float *pdfDir) const {
    *pdfPos = float(1 / (Pi * double(sphere.radius) * sphere.radius));
    *pdfDir = 0;
}

bool SamplePointPosition(const Vec3f &pos, const SurfaceInteraction &si, LightSample *ls,
                         float *dist2) {
    const Vec3f d = pos - si.p;
    *dist2 = LengthSquared(d);
    if (!(*dist2 > 0)) return false;
    ls->wi = d / std::sqrt(*dist2);
    ls->pLight = pos;
    ls->infinite = false;
    ls->pdf = 1;
    return true;
}

bool PointLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    float dist2;
    if (!SamplePointPosition(pos_, si, ls, &dist2)) return false;
    ls->Li = I_ / dist2;
    return true;
}

LightPartBounds PointBounds(const Vec3f &pos, float phi, const Vec3f &w, float cosTheta_o,
                            float cosTheta_e) {
    LightPartBounds b;
    b.lb.bounds = Bounds3f(pos, pos);
    b.lb.phi = phi;
    b.lb.w = w;
    b.lb.cosTheta_o = cosTheta_o;
    b.lb.cosTheta_e = cosTheta_e;
    return b;
}

void PointLight::Bounds(std::vector<LightPartBounds> *parts) const {
    parts->push_back(PointBounds(pos_, float(4 * Pi) * I_.MaxComponent(), {0, 0, 1}, -1, 0));
}

void SpotLight::Bounds(std::vector<LightPartBounds> *parts) const {
    // All of its light within the cone's total width, along the cone's directions only.
    parts->push_back(PointBounds(pos_, float(4 * Pi) * I_.MaxComponent(), dir_, cosTotalWidth_, 1));
}

SpotLight::SpotLight(const Vec3f &pos, const Vec3f &dir, const RGB &I, float coneAngle,
                     float coneDelta, FalloffCurve curve)
    : pos_(pos),
      dir_(dir),
      I_(I),
      cosTotalWidth_(float(std::cos(Radians(coneAngle)))),
      cosFalloffStart_(float(std::cos(Radians(coneAngle - coneDelta)))),
      curve_(curve) {}

float SpotLight::Falloff(const Vec3f &w) const {
    float cosTheta = Dot(w, dir_);
    if (cosTheta < cosTotalWidth_) return 0;
    if (cosTheta >= cosFalloffStart_) return 1;
    // pbrt-v3: the fourth power of the normalized cosine; pbrt-v4: its smoothstep.
    float delta = (cosTheta - cosTotalWidth_) / (cosFalloffStart_ - cosTotalWidth_);
    if (curve_ == FalloffCurve::SmoothStep) return delta * delta * (3 - 2 * delta);
    return (delta * delta) * (delta * delta);
}

bool SpotLight::SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const {
    float dist2;
    if (!SamplePointPosition(pos_, si, ls, &dist2)) return false;
    const float f = Falloff(-ls->wi);
    if (f == 0) return false;
    ls->Li = I_ * (f / dist2);
    return true;
}

bool DistantLight::SampleLi(const SurfaceInteraction &, Vec2f, LightSample *ls) const {
    ls->wi = w_;
    ls->Li = L_;
    ls->infinite = true;
    ls->pdf = 1;
    return true;
}

RGB PhotometricScale(const LightParams &p, const RGB &value, const char *param, double k_e,
                     const FileLoc &loc) {
    if (!p.Has(param)) return value;
    const float v = p.Float(param, 0);
    if (!(v >= 0) || !std::isfinite(v))
        throw SceneError(p.Loc(param).Valid() ? p.Loc(param) : loc,
                         p.Context() + ": \"" + param + "\" must be finite and not negative");
    return value * float(double(v) / k_e);
}

// LightSource "point" (light_list.inc). Parameters:
//   I      spectrum  1        radiant intensity
//   scale  spectrum  1        multiplies I
//   power  float     (none)   pbrt-v4: the radiant power; I is scaled by power / 4 pi
//   from   point     0 0 0    position, in the light's coordinate system
std::unique_ptr<Light> CreatePointLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB I = PhotometricScale(p, p.Spectrum("I", RGB(1)) * p.Scale(), "power", 4 * Pi, in.loc);
    const Vec3f from = p.Point3("from", Vec3f(0, 0, 0));
    return std::make_unique<PointLight>(Vec3f(in.renderFromLight.Point(Vec3d(from))), I);
}

// LightSource "spot" (light_list.inc). Parameters:
//   I               spectrum  1       radiant intensity on the axis
//   scale           spectrum  1       multiplies I
//   from, to        point     0 0 0, 0 0 1  position and a point on the axis
//   coneangle       float     30      the cone's half angle, degrees
//   conedeltaangle  float     5       the falloff band inside it, degrees
//   power           float     (none)  pbrt-v4: the radiant power; I is scaled by power over
//                                     2 pi (1 - (cos(coneangle - conedeltaangle) +
//                                     cos(coneangle)) / 2)
std::unique_ptr<Light> CreateSpotLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const Vec3f from = p.Point3("from", Vec3f(0, 0, 0)), to = p.Point3("to", Vec3f(0, 0, 1));
    if (from == to) throw SceneError(in.loc, "spot light \"from\" and \"to\" are the same point");
    const float cone = p.Float("coneangle", 30.f), delta = p.Float("conedeltaangle", 5.f);
    const double cosStart = std::cos(double(cone - delta) * Pi / 180),
                 cosEnd = std::cos(double(cone) * Pi / 180);
    const double k_e = 2 * Pi * (1 - 0.5 * (cosStart + cosEnd));
    const RGB I =
        p.Has("power") && !(k_e > 0)
            ? RGB(0)
            : PhotometricScale(p, p.Spectrum("I", RGB(1)) * p.Scale(), "power", k_e, in.loc);
    const Vec3d dir = Normalize(in.renderFromLight.Vector(Vec3d(to) - Vec3d(from)));
    return std::make_unique<SpotLight>(Vec3f(in.renderFromLight.Point(Vec3d(from))), Vec3f(dir), I,
                                       cone, delta,
                                       in.pbrtVersion == 4 ? SpotLight::FalloffCurve::SmoothStep
                                                           : SpotLight::FalloffCurve::Quartic);
}

// LightSource "distant" (light_list.inc). Parameters:
//   L         spectrum  1              radiance
//   scale     spectrum  1              multiplies L
//   from, to  point     0 0 0, 0 0 1   light travels from "from" toward "to"
//   illuminance  float  (none)  pbrt-v4: the irradiance on a surface facing the light; L is
//                               scaled by it
std::unique_ptr<Light> CreateDistantLight(const LightInputs &in) {
    const LightParams &p = in.params;
    const RGB L =
        PhotometricScale(p, p.Spectrum("L", RGB(1)) * p.Scale(), "illuminance", 1, in.loc);
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

SphereMap ReadSphereMap(const LightParams &p, const char *light) {
    SphereMap m;
    m.equalArea = !p.String("filename", "").empty();
    if (m.equalArea && !p.String("mapname", "").empty())
        throw SceneError(p.Loc("filename"),
                         std::string(light) +
                             ": give \"mapname\" (pbrt-v3, latitude-longitude) or \"filename\" "
                             "(pbrt-v4, equal-area), not both");
    m.image = p.OptionalImage(m.equalArea ? "filename" : "mapname");
    if (m.equalArea && m.image->width != m.image->height)
        throw SceneError(p.Loc("filename"),
                         std::string(light) + " \"filename\" is " + std::to_string(m.image->width) +
                             "x" + std::to_string(m.image->height) +
                             ": pbrt-v4's maps of directions are square equal-area images (a "
                             "latitude-longitude map goes in \"mapname\")");
    return m;
}

}  // namespace prism
