#include "render/medium_tracked.h"

#include <algorithm>
#include <cmath>

#include "render/noise.h"

namespace prism {

namespace {

// 1 - σt/μ per channel: the probability of a null collision, and its weight.
RGB NullFraction(const RGB &sigmaT, float invMajorant) {
    RGB n;
    for (int c = 0; c < 3; ++c) n[c] = std::max(0.f, 1 - sigmaT[c] * invMajorant);
    return n;
}

// The shortest of the medium space's axis directions, of length `len`, in render space.
float RenderLength(const Transform &renderFromMedium, float len) {
    return float(std::min({Length(renderFromMedium.Vector(Vec3d(len, 0, 0))),
                           Length(renderFromMedium.Vector(Vec3d(0, len, 0))),
                           Length(renderFromMedium.Vector(Vec3d(0, 0, len)))}));
}

}  // namespace

TrackedMedium::TrackedMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize,
                             float majorant, float featureSize, const Vec3f &p0, const Vec3f &p1,
                             const Transform &renderFromMedium)
    : Medium(sigmaA, sigmaS, g, stepSize),
      mediumFromRender_(renderFromMedium.Inverse()),
      p0_(p0),
      p1_(p1),
      invExtent_(1 / (p1.x - p0.x), 1 / (p1.y - p0.y), 1 / (p1.z - p0.z)),
      majorant_(majorant) {
    const float s = majorant_ > 0 ? 1 / (8 * majorant_) : Infinity;
    stepLimit_ = std::min(s, 0.5f * RenderLength(renderFromMedium, featureSize));
}

bool TrackedMedium::MediumSegment(const Ray &ray, Ray *rm, float *t0, float *t1) const {
    rm->o = mediumFromRender_.Point(ray.o);
    rm->d = mediumFromRender_.Vector(ray.d);
    rm->tMax = ray.tMax;
    return ClipToBox(*rm, p0_, p1_, t0, t1);
}

RGB TrackedMedium::SigmaT(const Ray &rm, float t) const {
    RGB sa, ss;
    CoefficientsAt(rm.At(t), &sa, &ss);
    return sa + ss;
}

bool TrackedMedium::Extent(const Ray &ray, float *t0, float *t1) const {
    Ray rm;
    return MediumSegment(ray, &rm, t0, t1);
}

void TrackedMedium::Coefficients(const Vec3f &pRender, RGB *sigmaA, RGB *sigmaS) const {
    const Vec3f p = mediumFromRender_.Point(pRender);
    if (!(p.x >= p0_.x && p.y >= p0_.y && p.z >= p0_.z && p.x <= p1_.x && p.y <= p1_.y &&
          p.z <= p1_.z)) {
        *sigmaA = *sigmaS = RGB(0);
        return;
    }
    CoefficientsAt(p, sigmaA, sigmaS);
}

RGB TrackedMedium::Tr(const Ray &ray, MediumSampler &sampler) const {
    Ray rm;
    float t0, t1;
    if (!MediumSegment(ray, &rm, &t0, &t1) || !(majorant_ > 0)) return RGB(1);
    // Ratio tracking per channel, with Russian roulette once every channel is small. Distances
    // are render-space lengths (the parameter times the render-space direction's length).
    const float invMajorant = 1 / majorant_, step = invMajorant / Length(ray.d);
    RGB tr(1);
    float t = t0;
    for (;;) {
        t -= std::log(1 - sampler.Get1D()) * step;
        if (!(t < t1)) break;
        tr *= NullFraction(SigmaT(rm, t), invMajorant);
        const float m = tr.MaxComponent();
        if (m < .1f) {
            const float q = std::max(.05f, 1 - m);
            if (sampler.Get1D() < q) return RGB(0);
            tr = tr / (1 - q);
        }
    }
    return tr;
}

RGB TrackedMedium::Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
                          bool *scattered) const {
    *scattered = false;
    Ray rm;
    float t0, t1;
    if (!MediumSegment(ray, &rm, &t0, &t1) || !(majorant_ > 0)) return RGB(1);
    // Delta tracking by one channel's σt, chosen uniformly. Under channel c the tentative
    // collisions so far had the probability (and the null-collision weight) Π (1 - σt,c / μ),
    // `nulls`; a real collision adds σt,c / μ to the probability and σs,c / μ to the weight.
    // The estimate is the weight over the mean of the three channels' probabilities.
    const int channel = std::min(int(sampler.Get1D() * 3), 2);
    const float invMajorant = 1 / majorant_, step = invMajorant / Length(ray.d);
    RGB nulls(1);
    float t = t0;
    for (;;) {
        t -= std::log(1 - sampler.Get1D()) * step;
        if (!(t < t1)) break;
        RGB sa, ss;
        CoefficientsAt(rm.At(t), &sa, &ss);
        const RGB sigmaT = sa + ss;
        if (sigmaT[channel] * invMajorant > sampler.Get1D()) {
            const float pdf = (nulls * sigmaT).Average();
            if (!(pdf > 0)) return RGB(0);
            *scattered = true;
            *mi = {ray.At(t), t};
            return nulls * ss / pdf;
        }
        nulls *= NullFraction(sigmaT, invMajorant);
        // Only the channels' ratios matter: keep them in float's range.
        const float m = nulls.MaxComponent();
        if (!(m > 0)) return RGB(0);
        if (m < 1e-20f) nulls = nulls / m;
    }
    const float pdf = nulls.Average();
    return pdf > 0 ? nulls / pdf : RGB(0);
}

RGB TrackedMedium::Tau(const Ray &ray, float t0, float t1) const {
    RGB sa, ss;
    Coefficients(ray.At(0.5f * (t0 + t1)), &sa, &ss);
    return (sa + ss) * ((t1 - t0) * Length(ray.d));
}

RGB TrackedMedium::SigmaS(const Vec3f &p) const {
    RGB sa, ss;
    Coefficients(p, &sa, &ss);
    return ss;
}

float TrackedMedium::DefaultStep() const { return stepLimit_; }

// RGB grid.

namespace {

float MaxOf(const std::vector<float> &v) {
    float m = 0;
    for (float x : v) m = std::max(m, x);
    return m;
}

float SmallestVoxel(int nx, int ny, int nz, const Vec3f &p0, const Vec3f &p1) {
    return std::min(
        {(p1.x - p0.x) / float(nx), (p1.y - p0.y) / float(ny), (p1.z - p0.z) / float(nz)});
}

RGB MaxOf(const std::vector<RGB> &grid) {
    if (grid.empty()) return RGB(1);
    RGB m;
    for (const RGB &v : grid)
        for (int c = 0; c < 3; ++c) m[c] = std::max(m[c], v[c]);
    return m;
}

// The largest channel of σa + σs over the voxels (an absent grid is 1): trilinear weights sum
// to at most 1, so no point of the box exceeds it.
float GridMajorant(const std::vector<RGB> &sigmaA, const std::vector<RGB> &sigmaS, size_t n,
                   float scale) {
    float m = 0;
    for (size_t i = 0; i < n; ++i) {
        const RGB t = (sigmaA.empty() ? RGB(1) : sigmaA[i]) + (sigmaS.empty() ? RGB(1) : sigmaS[i]);
        m = std::max(m, t.MaxComponent());
    }
    return m * scale;
}

}  // namespace

RGBGridMedium::RGBGridMedium(float g, float stepSize, int nx, int ny, int nz,
                             std::vector<RGB> sigmaA, std::vector<RGB> sigmaS, float scale,
                             const Vec3f &p0, const Vec3f &p1, const Transform &renderFromMedium)
    : TrackedMedium(MaxOf(sigmaA) * scale, MaxOf(sigmaS) * scale, g, stepSize,
                    GridMajorant(sigmaA, sigmaS, size_t(nx) * size_t(ny) * size_t(nz), scale),
                    SmallestVoxel(nx, ny, nz, p0, p1), p0, p1, renderFromMedium),
      nx_(nx),
      ny_(ny),
      nz_(nz),
      gridA_(std::move(sigmaA)),
      gridS_(std::move(sigmaS)),
      scale_(scale) {}

RGB RGBGridMedium::Lookup(const std::vector<RGB> &grid, const Vec3f &pg) const {
    if (grid.empty()) return RGB(scale_);
    return scale_ * VoxelLerp<RGB>(nx_, ny_, nz_, pg, [&](int x, int y, int z) {
               return grid[(size_t(z) * size_t(ny_) + size_t(y)) * size_t(nx_) + size_t(x)];
           });
}

void RGBGridMedium::CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const {
    const Vec3f pg = BoxFraction(pMedium);
    *sigmaA = Lookup(gridA_, pg);
    *sigmaS = Lookup(gridS_, pg);
}

// Density grid.

DensityGridMedium::DensityGridMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize,
                                     int nx, int ny, int nz, std::vector<float> density,
                                     const Vec3f &p0, const Vec3f &p1,
                                     const Transform &renderFromMedium)
    : TrackedMedium(sigmaA, sigmaS, g, stepSize, (sigmaA + sigmaS).MaxComponent() * MaxOf(density),
                    SmallestVoxel(nx, ny, nz, p0, p1), p0, p1, renderFromMedium),
      nx_(nx),
      ny_(ny),
      nz_(nz),
      density_(std::move(density)) {}

void DensityGridMedium::CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const {
    const Vec3f pg = BoxFraction(pMedium);
    const float density = VoxelLerp<float>(nx_, ny_, nz_, pg, [&](int x, int y, int z) {
        return density_[(size_t(z) * size_t(ny_) + size_t(y)) * size_t(nx_) + size_t(x)];
    });
    *sigmaA = sigmaA_ * density;
    *sigmaS = sigmaS_ * density;
}

// Cloud.

CloudMedium::CloudMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize,
                         float density, float wispiness, float frequency, const Vec3f &p0,
                         const Vec3f &p1, const Transform &renderFromMedium)
    // The density is at most 1; the finest octave's lattice is 1.99^4 times the first's.
    : TrackedMedium(sigmaA, sigmaS, g, stepSize, (sigmaA + sigmaS).MaxComponent(),
                    frequency > 0 ? 1 / (frequency * 15.7f) : Infinity, p0, p1, renderFromMedium),
      density_(density),
      wispiness_(wispiness),
      frequency_(frequency) {}

float CloudMedium::Density(const Vec3f &p) const {
    Vec3f pp = p * frequency_;
    if (wispiness_ > 0) {
        // Bend the lookup point along the noise's slope, two octaves.
        float omega = .05f * wispiness_, lambda = 10.f;
        for (int i = 0; i < 2; ++i) {
            pp += PerlinNoiseSlope(pp * lambda) * omega;
            omega *= .5f;
            lambda *= 1.99f;
        }
    }
    // Five octaves of noise from half weight, then thinning with height.
    const float noise = .5f * FBm(pp, .5f, 5);
    float d = std::clamp((1 - p.y) * 4.5f * density_ * noise, 0.f, 1.f);
    d += 2 * std::max(0.f, .5f - p.y);
    return std::clamp(d, 0.f, 1.f);
}

void CloudMedium::CoefficientsAt(const Vec3f &pMedium, RGB *sigmaA, RGB *sigmaS) const {
    const float d = Density(pMedium);
    *sigmaA = sigmaA_ * d;
    *sigmaS = sigmaS_ * d;
}

}  // namespace prism
