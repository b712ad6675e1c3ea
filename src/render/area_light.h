// Area lights, sampled with stratified shadow rays (distribution ray tracing): pbrt-v3's
// "diffuse" AreaLightSource on spheres, disks, cylinders and triangle meshes.
#pragma once

#include <memory>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "render/distribution.h"
#include "render/light.h"

namespace prism {

class DiffuseAreaLight final : public Light {
  public:
    // Exactly one of analytic/mesh is set; both outlive the light (owned by the Accel).
    DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh, const RGB &L,
                     bool twoSided, int nSamples);
    const char *Name() const override { return "area"; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const override;
    int NumSamples() const override { return nSamples_; }
    float PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                const SurfaceInteraction *hit) const override;
    // Radiance leaving the surface point with normal n in direction w.
    RGB L(const Vec3f &n, const Vec3f &w) const {
        return (twoSided_ || Dot(n, w) > 0) ? Lemit_ : RGB(0);
    }
    bool IsArea() const override { return true; }
    double Power(double) const override;

  private:
    const AnalyticShape *analytic_;
    const TriangleMesh *mesh_;
    RGB Lemit_;
    bool twoSided_;
    int nSamples_;
    Distribution1D triangleAreas_;
    double meshArea_ = 0;
};

}  // namespace prism
