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

}  // namespace prism
