// Area lights, sampled with stratified shadow rays (distribution ray tracing): pbrt-v3's
// "diffuse" AreaLightSource on spheres, disks, cylinders and triangle meshes, and on meshes a
// textured radiance L(uv) = L × texture(uv) (glTF emissive textures: emissiveFactor ×
// emissiveStrength × emissiveTexture).
#pragma once

#include <memory>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "render/distribution.h"
#include "render/light.h"
#include "render/texture.h"

namespace prism {

class DiffuseAreaLight final : public Light {
  public:
    // Exactly one of analytic/mesh is set; both outlive the light (owned by the Accel).
    // `radiance` (meshes only; null: constant L): the emitted radiance is L × radiance at the
    // point's uv (TextureContext uv, p, uv1). Mesh points are sampled by triangle in proportion
    // to area × the triangle's mean radiance (the texture averaged over a grid of points on
    // the triangle, finer for larger uv footprints: TextureMeanSamples); triangles whose mean
    // is black are never sampled (their light is then seen only by rays that hit them).
    // The means take at most about MaxTextureMeanLookups texture lookups per light.
    // `powerPerTriangle` (meshes; 0: none) is pbrt-v4's "power" as pbrt-v4 gives it to a
    // mesh, which makes each triangle a light of its own: each triangle's radiance is L times
    // the power over pi x its area (x2 two-sided) x the area-weighted mean luminance of the
    // texture over the mesh (1 untextured), as pbrt-v4 measures by its image's mean. A patch of
    // triangles (TriangleMesh::SetPatches: a bilinear patch, a PLY quad) is one light: its
    // area is the patch's.
    DiffuseAreaLight(const AnalyticShape *analytic, const TriangleMesh *mesh, const RGB &L,
                     bool twoSided, int nSamples, TexturePtr radiance = nullptr,
                     double powerPerTriangle = 0);
    const char *Name() const override { return "area"; }
    bool SampleLi(const SurfaceInteraction &si, Vec2f u, LightSample *ls) const override;
    // Meshes, for a triangle the light BVH chose: SampleLi over triangle `tri` alone (a
    // uniform point on it), and the solid-angle density with which it gives the direction wi
    // that met the mesh at hit (on that triangle).
    bool SampleLiTriangle(const SurfaceInteraction &si, int tri, Vec2f u, LightSample *ls) const;
    float PdfLiTriangle(const SurfaceInteraction &ref, const Vec3f &wi,
                        const SurfaceInteraction &hit) const;
    // An analytic shape whole; a mesh's triangles one by one (those SampleLi can choose), or
    // the mesh whole when they are at most MaxTrianglesChosenWhole or the mesh moves.
    void Bounds(std::vector<LightPartBounds> *parts) const override;
    static constexpr int MaxTrianglesChosenWhole = 8;
    int NumSamples() const override { return nSamples_; }
    float PdfLi(const SurfaceInteraction &ref, const Vec3f &wi,
                const SurfaceInteraction *hit) const override;
    // Radiance leaving the surface point with normal n in direction w (the constant L; for a
    // textured light use the overload below).
    RGB L(const Vec3f &n, const Vec3f &w) const {
        return (twoSided_ || Dot(n, w) > 0) ? Lemit_ : RGB(0);
    }
    // Radiance leaving a hit on the light's shape in direction w (pbrt-v3's
    // AreaLight::L(intr, w)): L × the texture at the hit's uv (the hit needs NeedUV).
    RGB L(const SurfaceInteraction &si, const Vec3f &w) const {
        if (!(twoSided_ || Dot(si.n, w) > 0)) return RGB(0);
        const RGB Le = Emitted(si.prim);
        return radiance_ ? Le * radiance_->Evaluate(SurfaceTextureContext(si)).Clamped(0.f) : Le;
    }
    bool IsArea() const override { return true; }
    // Emission: a point by SampleLi's distribution over the surface (per unit area), a
    // cosine-weighted direction on its emitting side (either side, half and half, when
    // two-sided).
    bool SampleLe(Vec2f uPos, Vec2f uDir, const SceneSphere &sphere,
                  LightLeSample *ls) const override;
    void PdfLe(const Vec3f &p, const Vec3f &n, const Vec3f &w, const SceneSphere &sphere,
               float *pdfPos, float *pdfDir) const override;
    // The density per unit area with which SampleLe picks the point with unit normal n on
    // triangle prim (meshes) or on the analytic shape.
    float PdfPosition(const Vec3f &n, int prim) const;
    bool TwoSided() const { return twoSided_; }
    bool Textured() const { return radiance_ != nullptr; }
    // Meshes: the density (per unit area) with which SampleLi picks points of triangle `prim`
    // (0 for a triangle never sampled), for integrators that weigh light samples against
    // BSDF samples; analytic shapes: 0 (their Sample gives its own pdf).
    double PdfArea(int prim) const;
    // Meshes: the triangles SampleLi can pick (a textured light skips the black ones).
    int SampledTriangles() const { return sampledTriangles_; }

    // Points per triangle side at which the mean radiance of a textured triangle is taken:
    // about 2048 per unit of uv (one per texel of a 2048² texture: DamagedHelmet's emissive
    // details, a few texels wide, are found), at least 1, at most 256, and at most
    // √(MaxTextureMeanLookups / triangles) so a large mesh costs a bounded start-up.
    static int TextureMeanSamples(double uvArea);
    static constexpr double MaxTextureMeanLookups = 4e6;
    double Power(double) const override;

  private:
    // SampleLi at the point of triangle tri for (ux, uy) (uniform over it), whose density per
    // unit area is pdfArea; and its last step, for a point p with normal n and density pdf.
    bool SampleTriangle(const SurfaceInteraction &si, int tri, double ux, float uy, double pdfArea,
                        LightSample *ls) const;
    bool Finish(const SurfaceInteraction &si, const Vec3f &p, const Vec3f &n, float pdf,
                const RGB &Le, LightSample *ls) const;
    double AnalyticArea() const;  // render-space area of the analytic shape
    // L, times triangle `prim`'s scale when "power" gave each triangle one.
    RGB Emitted(int prim) const {
        return triangleScale_.empty() || prim < 0 || size_t(prim) >= triangleScale_.size()
                   ? Lemit_
                   : Lemit_ * triangleScale_[size_t(prim)];
    }

    const AnalyticShape *analytic_;
    const TriangleMesh *mesh_;
    RGB Lemit_;
    bool twoSided_;
    int nSamples_;
    TexturePtr radiance_;
    Distribution1D triangleWeights_;  // area (× mean radiance when textured)
    std::vector<double> triangleAreas_;
    std::vector<float> triangleScale_;  // per triangle (powerPerTriangle), or empty
    double meshArea_ = 0;
    int sampledTriangles_ = 0;
};

}  // namespace prism
