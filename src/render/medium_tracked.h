// Media whose coefficients vary in space and by colour channel: pbrt-v4's "rgbgrid" (σa and σs
// given per voxel as RGB) and "cloud" (a procedural density). Each is empty outside a box of
// its own space. Tr is ratio tracking and Sample delta tracking against one majorant μ >= every
// channel of σt = σa + σs in the box; Sample picks the channel whose σt decides real
// collisions uniformly and weighs the path by the balance heuristic over the three channels
// (pbrt-v4's spectral MIS of chromatic media with three wavelengths), so a chromatic medium is
// unbiased in every channel.
#pragma once

#include <vector>

#include "render/medium.h"

namespace prism {

class TrackedMedium : public Medium {
  public:
    // sigmaA, sigmaS: the largest coefficients (Medium::SigmaA/SigmaScatter); majorant: an
    // upper bound of every channel of σa + σs in the box [p0, p1] of the medium's space;
    // featureSize: the length in the medium's space over which the coefficients change (the
    // single-scattering ray march steps at most half of it).
    TrackedMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize, float majorant,
                  float featureSize, const Vec3f &p0, const Vec3f &p1,
                  const Transform &renderFromMedium);
    RGB Tr(const Ray &ray, MediumSampler &sampler) const override;
    RGB Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
               bool *scattered) const override;
    bool Extent(const Ray &ray, float *t0, float *t1) const override;
    RGB Tau(const Ray &ray, float t0, float t1) const override;
    RGB SigmaS(const Vec3f &p) const override;
    float DefaultStep() const override;
    float Majorant() const { return majorant_; }
    // σa and σs at a render-space point (0 outside the box).
    void Coefficients(const Vec3f &pRender, RGB *sigmaA, RGB *sigmaS) const;

  protected:
    // σa and σs at a point of the medium's space inside the box.
    virtual void CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const = 0;
    // A point of the medium's space as a fraction of the box ([0,1]^3 inside it).
    Vec3f BoxFraction(const Vec3f &pMedium) const {
        const Vec3f d = pMedium - p0_;
        return Vec3f(d.x * invExtent_.x, d.y * invExtent_.y, d.z * invExtent_.z);
    }

  private:
    // The ray in the medium's space (same parameter t) and its interval inside the box.
    bool MediumSegment(const Ray &ray, Ray *rm, float *t0, float *t1) const;
    RGB SigmaT(const Ray &rm, float t) const;

    Transform mediumFromRender_;
    Vec3f p0_, p1_, invExtent_;
    float majorant_, stepLimit_;
};

// pbrt-v4 RGBGridMedium: σa and σs each an nx × ny × nz grid of RGB values over [p0, p1]
// (trilinear between voxel centres, 0 outside, as the density grid), times `scale`; a grid
// not given is 1 everywhere.
class RGBGridMedium final : public TrackedMedium {
  public:
    // sigmaA, sigmaS: nx·ny·nz values, x fastest, or empty.
    RGBGridMedium(float g, float stepSize, int nx, int ny, int nz, std::vector<RGB> sigmaA,
                  std::vector<RGB> sigmaS, float scale, const Vec3f &p0, const Vec3f &p1,
                  const Transform &renderFromMedium);
    const char *Name() const override { return "rgbgrid"; }

  private:
    void CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const override;
    RGB Lookup(const std::vector<RGB> &grid, const Vec3f &pg) const;

    int nx_, ny_, nz_;
    std::vector<RGB> gridA_, gridS_;
    float scale_;
};

// pbrt-v4 GridMedium ("uniformgrid"): σa and σs times a density grid of nx × ny × nz values over
// [p0, p1] (trilinear between voxel centres, 0 outside). Unlike pbrt-v3's grid
// (GridDensityMedium), the extinction may differ by channel.
class DensityGridMedium final : public TrackedMedium {
  public:
    // density: nx·ny·nz values, x fastest.
    DensityGridMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize, int nx, int ny,
                      int nz, std::vector<float> density, const Vec3f &p0, const Vec3f &p1,
                      const Transform &renderFromMedium);
    const char *Name() const override { return "uniformgrid"; }

  private:
    void CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const override;

    int nx_, ny_, nz_;
    std::vector<float> density_;
};

// pbrt-v4 CloudMedium: σa and σs times a density in [0, 1] made of five octaves of Perlin noise
// at `frequency` (the lookup point first bent by two octaves of the noise's slope, by
// `wispiness`), thinning with height: full below y = 0 of the medium's space, noise scaled by
// 1 - y above it (|1 - y| stays small above y = 1, where the noise's sign flips).
class CloudMedium final : public TrackedMedium {
  public:
    CloudMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize, float density,
                float wispiness, float frequency, const Vec3f &p0, const Vec3f &p1,
                const Transform &renderFromMedium);
    const char *Name() const override { return "cloud"; }
    // The density at a point of the medium's space (also outside the box).
    float Density(const Vec3f &pMedium) const;

  private:
    void CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const override;

    float density_, wispiness_, frequency_;
};

}  // namespace prism
