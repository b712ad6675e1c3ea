// Area and environment lights, sampled with stratified shadow rays (distribution ray
// tracing): pbrt-v3's "diffuse" AreaLightSource on spheres, disks, cylinders and triangle
// meshes, and the "infinite" light with a constant radiance or an equirectangular map.
#pragma once

#include <memory>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "render/distribution.h"
#include "render/light.h"

namespace prism {

struct Image;

class DiffuseAreaLight final : public Light {
public:
    // Exactly one of analytic/mesh is set; both outlive the light (owned by the Accel).
    DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh, const RGB &L,
                     bool twoSided, int nSamples);
    const char *Name() const override { return "area"; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const override;
    int NumSamples() const override { return nSamples_; }
    // Radiance leaving the surface point with normal n in direction w.
    RGB L(const Vec3f &n, const Vec3f &w) const {
        return (twoSided_ || Dot(n, w) > 0) ? Lemit_ : RGB(0);
    }
    bool IsArea() const override { return true; }

private:
    const AnalyticShape *analytic_;
    const TriangleMesh *mesh_;
    RGB Lemit_;
    bool twoSided_;
    int nSamples_;
    Distribution1D triangleAreas_;
    double meshArea_ = 0;
};

class InfiniteLight final : public Light {
public:
    // lightFromRender rotates render-space directions into the map's frame (z = pole).
    InfiniteLight(const Transform &renderFromLight, const RGB &L,
                  std::shared_ptr<const Image> map, int nSamples);
    const char *Name() const override { return "infinite"; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const override;
    RGB Le(const Ray &ray) const override;
    int NumSamples() const override { return nSamples_; }

private:
    RGB Lookup(const Vec3f &wRender) const;
    Transform renderFromLight_;
    RGB L_;
    std::shared_ptr<const Image> map_;
    Distribution2D distribution_;
    int nSamples_;
};

}  // namespace prism
