// pbrt's "projection" light: a point light that throws an image through a perspective frustum
// along its +z, like a slide projector (the intensity of each direction is the texel it passes
// through; none outside the frustum). pbrt-v3's "mapname" lands upside down (row 0 along -y,
// bilinear); pbrt-v4's "filename" upright (row 0 along +y, the nearest texel).
#pragma once

#include <memory>

#include "core/transform.h"
#include "render/light.h"

namespace prism {

struct Image;

class ProjectionLight final : public Light {
  public:
    // renderFromLight: the CTM at the LightSource (the light sits at its origin, looking along
    // +z); fovDeg: the frustum's angle across the image's shorter side; map may be null (a
    // square frustum of constant intensity).
    // `upright`: pbrt-v4's reading of the map (above).
    ProjectionLight(const Transform &renderFromLight, const RGB &I,
                    std::shared_ptr<const Image> map, double fovDeg, bool upright = false);
    const char *Name() const override { return "projection"; }
    bool UsesSample() const override { return false; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f, LightSample *ls) const override;
    // I times the integral of the map over the frustum's solid angle (exact per texel).
    double Power(double) const override { return I_.Luminance() * mapIntegral_; }
    // A point emitting within the cone through the image's corners.
    void Bounds(std::vector<LightPartBounds> *parts) const override {
        parts->push_back(PointBounds(pos_, float(mapIntegral_) * I_.MaxComponent(), axis_,
                                     float(cosTotalWidth_), 1));
    }
    // Emission: uniform in the cone about +z that bounds the frustum.
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;
    // The map's scale of the intensity toward render-space direction w (from the light).
    RGB Projection(const Vec3f &w) const;
    double CosTotalWidth() const { return cosTotalWidth_; }
    // The map's luminance integrated over the frustum's solid angle: "power" is measured by it.
    double MapIntegral() const { return mapIntegral_; }

  private:
    Vec3f pos_, axis_;
    Transform renderFromLight_, lightFromRender_;
    RGB I_;
    std::shared_ptr<const Image> map_;
    bool upright_ = false;
    // The image on the plane z = 1: [-sx, sx] x [-sy, sy] (sx, sy: tan of the half angles).
    double sx_, sy_;
    double cosTotalWidth_;
    double mapIntegral_ = 0;
};

}  // namespace prism
