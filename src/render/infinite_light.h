// The environment light: pbrt's "infinite" light with a constant radiance or a map, either
// pbrt-v3's equirectangular "mapname" (bilinear) or pbrt-v4's square equal-area "filename"
// (core/equal_area.h; nearest texel, as pbrt-v4 looks it up), sampled with stratified shadow
// rays by the map's luminance.
#pragma once

#include <memory>

#include "core/transform.h"
#include "render/distribution.h"
#include "render/light.h"

namespace prism {

struct Image;

class InfiniteLight final : public Light {
  public:
    enum class Projection { LatLong, EqualArea };
    // renderFromLight rotates the map's frame (z = pole) into render space.
    InfiniteLight(const Transform &renderFromLight, const RGB &L, std::shared_ptr<const Image> map,
                  int nSamples, Projection projection = Projection::LatLong);
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
};

}  // namespace prism
