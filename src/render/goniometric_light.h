// pbrt's "goniometric" light: a point light whose intensity in each direction is scaled by an
// image over the sphere of directions: pbrt-v3's "mapname" in latitude-longitude (the light's
// +y the pole, bilinear, RGB), or pbrt-v4's "filename" in the equal-area square (the light's +y
// at its centre, the nearest texel, the mean of its R, G and B).
#pragma once

#include <memory>

#include "core/transform.h"
#include "render/light.h"

namespace prism {

struct Image;

// Bilinear lookup of an image at (s, t) in [0,1]^2 (pbrt-v3 MIPMap's finest level: texel
// centres at (i + 0.5) / size), row 0 at t = 0; s wraps around when wrapS, else it is clamped
// like t.
RGB ImageBilerp(const Image &image, double s, double t, bool wrapS);

class GoniometricLight final : public Light {
  public:
    // renderFromLight: the CTM at the LightSource (the light sits at its origin). map may be
    // null (a point light); `equalArea`: a square pbrt-v4 map (see above).
    GoniometricLight(const Transform &renderFromLight, const RGB &I,
                     std::shared_ptr<const Image> map, bool equalArea = false);
    const char *Name() const override { return "goniometric"; }
    bool UsesSample() const override { return false; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const override;
    // 4 pi I times the map's average over the sphere (latitude-longitude rows weighted by
    // their solid angle; equal-area texels are equal).
    double Power(double) const override { return 4 * Pi * I_.Luminance() * mapAverage_; }
    void Bounds(std::vector<LightPartBounds> *parts) const override {
        parts->push_back(
            PointBounds(pos_, float(4 * Pi * mapAverage_) * I_.MaxComponent(), {0, 0, 1}, -1, 0));
    }
    // The map's average over the sphere (1 without one): "power" is measured by it.
    double MapAverage() const { return mapAverage_; }
    // Emission: uniform over the sphere, the radiance the map gives each direction.
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;
    // The map's scale of the intensity toward render-space direction w (from the light).
    RGB Scale(const Vec3f &w) const;

  private:
    Vec3f pos_;
    Transform lightFromRender_;
    RGB I_;
    std::shared_ptr<const Image> map_;
    bool equalArea_ = false;
    double mapAverage_ = 1;
};

}  // namespace prism
