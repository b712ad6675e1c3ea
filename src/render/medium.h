// Participating media (pbrt-v3 core/medium.h, media/homogeneous.h, media/grid.h): a medium
// absorbs and scatters light along the ray segments that cross it. Medium::Tr is the
// transmittance of a segment, Medium::Sample samples a scattering point along it (pbrt-v3's
// interface, for volpath); Extent, Tau and SigmaS serve the ray-marched single scattering of
// the Whitted and distribution kernels (pbrt-v2's SingleScatteringIntegrator). Rays need not
// have unit directions: distances are ray parameters times the direction's length. Media live
// in render space (RenderScene::media); which medium a ray is in is tracked by the integrator
// (render/medium_interface.h).
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/rng.h"
#include "core/transform.h"
#include "geometry/ray.h"

namespace prism {

// The random numbers of medium sampling: a PCG32 stream seeded from the pixel, sample and
// path vertex, so renders stay a pure function of the pixel. The first two may be given
// (Lead): a sampler's stratified numbers, or a Markov chain's, which its small mutations then
// move a little (a homogeneous medium's channel and distance).
class MediumSampler {
  public:
    explicit MediumSampler(uint64_t seed, uint64_t stream = 0x6d656469756dULL)
        : rng_(seed, stream) {}
    MediumSampler(uint64_t seed, Vec2f lead)
        : rng_(seed, 0x6d656469756dULL), lead_(lead), next_(0) {}
    float Get1D() {
        if (next_ < 2) return next_++ == 0 ? lead_.x : lead_.y;
        return rng_.Uniform();
    }

  private:
    PCG32 rng_;
    Vec2f lead_;
    int next_ = 2;  // lead_'s next number (2: none left)
};

// Henyey–Greenstein phase function for the cosine between wo and wi, both pointing away from
// the scattering point (pbrt-v3's convention: g > 0 scatters forward, i.e. wi near -wo).
float PhaseHG(float cosTheta, float g);

class HenyeyGreenstein {
  public:
    explicit HenyeyGreenstein(float g = 0) : g_(g) {}
    float g() const { return g_; }
    float p(const Vec3f &wo, const Vec3f &wi) const { return PhaseHG(Dot(wo, wi), g_); }
    // Samples wi with density p(wo, wi) from u in [0,1)^2; returns p(wo, wi).
    float Sample_p(const Vec3f &wo, Vec3f *wi, Vec2f u) const;

  private:
    float g_;
};

// Trilinear interpolation between the centres of an nx × ny × nz grid over [0,1]^3 (pg in that
// space; pbrt's grids): value(x, y, z) is a voxel's value, T() outside the grid.
template <typename T, typename Value>
T VoxelLerp(int nx, int ny, int nz, const Vec3f &pg, const Value &value) {
    const float sx = pg.x * float(nx) - .5f, sy = pg.y * float(ny) - .5f,
                sz = pg.z * float(nz) - .5f;
    const float fx = std::floor(sx), fy = std::floor(sy), fz = std::floor(sz);
    // Far outside (or NaN): nothing, and no int overflow.
    if (!(fx >= -1 && fy >= -1 && fz >= -1 && fx < float(nx) && fy < float(ny) && fz < float(nz)))
        return T();
    const int ix = int(fx), iy = int(fy), iz = int(fz);
    const float dx = sx - fx, dy = sy - fy, dz = sz - fz;
    auto at = [&](int x, int y, int z) {
        return x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz ? T() : value(x, y, z);
    };
    auto lerp = [](float t, const T &a, const T &b) { return a * (1 - t) + b * t; };
    const T d00 = lerp(dx, at(ix, iy, iz), at(ix + 1, iy, iz));
    const T d10 = lerp(dx, at(ix, iy + 1, iz), at(ix + 1, iy + 1, iz));
    const T d01 = lerp(dx, at(ix, iy, iz + 1), at(ix + 1, iy, iz + 1));
    const T d11 = lerp(dx, at(ix, iy + 1, iz + 1), at(ix + 1, iy + 1, iz + 1));
    return lerp(dz, lerp(dy, d00, d10), lerp(dy, d01, d11));
}

// The interval of ray parameters in [0, r.tMax] inside the box [lo, hi] (slabs; a ray
// parallel to a slab counts when on or within it); false when empty.
bool ClipToBox(const Ray &r, const Vec3f &lo, const Vec3f &hi, float *t0, float *t1);

// A scattering event sampled inside a medium (Medium::Sample).
struct MediumInteraction {
    Vec3f p;
    float t = 0;  // ray parameter
};

class Medium {
  public:
    Medium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize)
        : sigmaA_(sigmaA), sigmaS_(sigmaS), phase_(g), stepSize_(stepSize) {}
    virtual ~Medium() = default;
    virtual const char *Name() const = 0;
    // Transmittance from ray.o to ray.At(ray.tMax) (tMax may be infinite).
    virtual RGB Tr(const Ray &ray, MediumSampler &sampler) const = 0;
    // pbrt-v3 Medium::Sample: either samples a scattering point before ray.tMax (*scattered
    // true, *mi set) and returns Tr·σs/pdf, or returns Tr/pdf of passing through.
    virtual RGB Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
                       bool *scattered) const = 0;
    // The ray-parameter interval within [0, ray.tMax] where the medium may be non-empty
    // (the grid's box; everything for a homogeneous medium); false when there is none.
    virtual bool Extent(const Ray &ray, float *t0, float *t1) const = 0;
    // Optical depth between ray.At(t0) and ray.At(t1), deterministic (exact for homogeneous
    // media; the density at the midpoint for grids, for the short steps of a ray march).
    virtual RGB Tau(const Ray &ray, float t0, float t1) const = 0;
    // Scattering coefficient at p.
    virtual RGB SigmaS(const Vec3f &p) const = 0;

    const HenyeyGreenstein &Phase() const { return phase_; }
    const RGB &SigmaA() const { return sigmaA_; }
    const RGB &SigmaScatter() const { return sigmaS_; }
    // The ray-march step of single scattering in render-space units: MakeNamedMedium's
    // "stepsize" (a Prism extension), or 0 when DefaultStep applies.
    float StepSize() const { return stepSize_; }
    // The medium's own step: an eighth of the mean free path at the densest point, and for
    // grids at most half a voxel (infinite when nothing scatters).
    virtual float DefaultStep() const = 0;

  protected:
    RGB sigmaA_, sigmaS_;
    HenyeyGreenstein phase_;
    float stepSize_;
};

// pbrt-v3 HomogeneousMedium: constant σa and σs; everything analytic.
class HomogeneousMedium final : public Medium {
  public:
    HomogeneousMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize)
        : Medium(sigmaA, sigmaS, g, stepSize), sigmaT_(sigmaA + sigmaS) {}
    const char *Name() const override { return "homogeneous"; }
    RGB Tr(const Ray &ray, MediumSampler &sampler) const override;
    RGB Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
               bool *scattered) const override;
    bool Extent(const Ray &ray, float *t0, float *t1) const override;
    RGB Tau(const Ray &ray, float t0, float t1) const override;
    RGB SigmaS(const Vec3f &) const override { return sigmaS_; }
    float DefaultStep() const override;

  private:
    RGB sigmaT_;
};

// pbrt-v3 GridDensityMedium: σa and σs scaled by a density grid of nx × ny × nz samples over
// the box [p0, p1] of the medium's space (trilinear; 0 outside). As in pbrt-v3 the extinction
// is grey: σt = σa + σs of the first (red) channel; the albedo σs/σt keeps its colour. Tr is
// ratio tracking and Sample delta tracking against the majorant σt · max density.
class GridDensityMedium final : public Medium {
  public:
    // renderFromMedium: the CTM at MakeNamedMedium (with the render-space translation).
    GridDensityMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize, int nx, int ny,
                      int nz, std::vector<float> density, const Vec3f &p0, const Vec3f &p1,
                      const Transform &renderFromMedium);
    const char *Name() const override { return "heterogeneous"; }
    RGB Tr(const Ray &ray, MediumSampler &sampler) const override;
    RGB Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
               bool *scattered) const override;
    bool Extent(const Ray &ray, float *t0, float *t1) const override;
    RGB Tau(const Ray &ray, float t0, float t1) const override;
    RGB SigmaS(const Vec3f &p) const override;
    float DefaultStep() const override;
    // Trilinear density at a render-space point.
    float Density(const Vec3f &pRender) const;

  private:
    float DensityGrid(const Vec3f &pg) const;  // pg in grid space [0,1]^3
    // The ray in grid space (same parameter t) and its interval inside [0,1]^3.
    bool GridSegment(const Ray &ray, Ray *rg, float *t0, float *t1) const;

    int nx_, ny_, nz_;
    std::vector<float> density_;
    Transform gridFromRender_;
    float sigmaT_ = 0, invMaxDensity_ = 0;
    float voxelSize_ = 0;  // the smallest voxel edge in render space
};

}  // namespace prism
