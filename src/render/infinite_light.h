// The environment light: pbrt's "infinite" light with a constant radiance or a map, either
// pbrt-v3's equirectangular "mapname" (bilinear) or pbrt-v4's square equal-area "filename"
// (core/equal_area.h; nearest texel, as pbrt-v4 looks it up), sampled with stratified shadow
// rays by the map's luminance.
#pragma once

#include <memory>
#include <optional>

#include "core/transform.h"
#include "render/distribution.h"
#include "render/light.h"

namespace prism {

struct Image;

// pbrt-v4's portal of an infinite light: a rectangle in render space with corner p0 and edges u
// (to its fourth corner) and v (to its second); light arrives only from the side its unit
// normal n = u x v / |u x v| points to, in the directions whose dot with n is positive.
struct LightPortal {
    Vec3f p0, u, v, n;
    float area = 0;
};

class InfiniteLight final : public Light {
  public:
    enum class Projection { LatLong, EqualArea };
    // renderFromLight rotates the map's frame (z = pole) into render space. With a portal,
    // only the directions facing it emit, and light samples are drawn uniformly over its area
    // as seen from the shading point (none from points on its outer side).
    InfiniteLight(const Transform &renderFromLight, const RGB &L, std::shared_ptr<const Image> map,
                  int nSamples, Projection projection = Projection::LatLong,
                  std::optional<LightPortal> portal = std::nullopt);
    const char *Name() const override { return "infinite"; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const override;
    RGB Le(const Ray &ray) const override;
    double Power(double r) const override { return Pi * r * r * averageLuminance_; }
    float PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                const SurfaceInteraction *hit) const override;
    int NumSamples() const override { return nSamples_; }
    // Emission: the direction by the map (uniform over the sphere without one), the origin on
    // the scene sphere's disk facing it.
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;
    bool IsInfinite() const override { return true; }

  private:
    // Whether light arrives from direction w (toward the light): always without a portal.
    bool Faces(const Vec3f &w) const { return !portal_ || Dot(w, portal_->n) > 0; }
    // The portal's light sample from p, and its density for direction wi (0 when wi misses
    // the portal or p is not on its inner side).
    bool SamplePortal(const Vec3f &p, Vec2f u, Vec3f *wi, float *pdf) const;
    float PortalPdf(const Vec3f &p, const Vec3f &wi) const;
    // A direction toward the light by the map's luminance, and its density (solid angle).
    bool SampleMap(Vec2f u, Vec3f *wi, float *pdf) const;
    // The density of the direction toward the light wi as SampleLe draws it (solid angle).
    float DirectionPdf(const Vec3f &wi) const;
    RGB Lookup(const Vec3f &wRender) const;
    Transform renderFromLight_;
    RGB L_;
    std::shared_ptr<const Image> map_;
    Projection projection_;
    Distribution2D distribution_;
    int nSamples_;
    double averageLuminance_ = 0;  // over the sphere of directions
    std::optional<LightPortal> portal_;
};

}  // namespace prism
