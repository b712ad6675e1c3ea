#include "render/medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prism {

namespace {

constexpr float MaxDistance = std::numeric_limits<float>::max();

// exp(-σt d) per channel; a channel with σt = 0 transmits everything, even over an infinite
// distance (where σt d would be 0 · ∞).
RGB ExpNeg(const RGB &sigmaT, float d) {
    RGB r;
    for (int c = 0; c < 3; ++c) r[c] = sigmaT[c] == 0 ? 1.f : std::exp(-sigmaT[c] * d);
    return r;
}

}  // namespace

float PhaseHG(float cosTheta, float g) {
    const float denom = 1 + g * g + 2 * g * cosTheta;
    return float(1 / (4 * Pi)) * (1 - g * g) / (denom * std::sqrt(denom));
}

float HenyeyGreenstein::Sample_p(const Vec3f &wo, Vec3f *wi, Vec2f u) const {
    // cosθ about the forward direction -wo, by inverting the HG distribution's CDF.
    float cosTheta;
    if (std::abs(g_) < 1e-3f) {
        cosTheta = 1 - 2 * u.x;
    } else {
        const float sqrTerm = (1 - g_ * g_) / (1 - g_ + 2 * g_ * u.x);
        cosTheta = (1 + g_ * g_ - sqrTerm * sqrTerm) / (2 * g_);
    }
    cosTheta = std::clamp(cosTheta, -1.f, 1.f);
    const float sinTheta = std::sqrt(std::max(0.f, 1 - cosTheta * cosTheta));
    const float phi = float(2 * Pi) * u.y;
    const Vec3f w = -wo;
    Vec3f v1, v2;
    CoordinateSystem(w, &v1, &v2);
    *wi = v1 * (sinTheta * std::cos(phi)) + v2 * (sinTheta * std::sin(phi)) + w * cosTheta;
    return PhaseHG(-cosTheta, g_);
}

bool ClipToBox(const Ray &r, const Vec3f &lo, const Vec3f &hi, float *t0, float *t1) {
    float a = 0, b = r.tMax;
    for (int i = 0; i < 3; ++i) {
        const float inv = 1 / r.d[i];
        float tn = (lo[i] - r.o[i]) * inv, tf = (hi[i] - r.o[i]) * inv;
        if (tn > tf) std::swap(tn, tf);
        if (std::isnan(tn) || std::isnan(tf)) {  // parallel to the slab, on its plane
            if (r.o[i] < lo[i] || r.o[i] > hi[i]) return false;
            continue;
        }
        a = std::max(a, tn);
        b = std::min(b, tf);
        if (a > b) return false;
    }
    *t0 = a;
    *t1 = b;
    return b > a;
}

// Homogeneous.

RGB HomogeneousMedium::Tr(const Ray &ray, MediumSampler &) const {
    return ExpNeg(sigmaT_, std::min(ray.tMax * Length(ray.d), MaxDistance));
}

RGB HomogeneousMedium::Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
                              bool *scattered) const {
    // pbrt-v3: a channel chosen uniformly, a distance from its exponential distribution, and
    // the pdf averaged over the channels (one-sample MIS over the three).
    const int channel = std::min(int(sampler.Get1D() * 3), 2);
    const float u = sampler.Get1D();
    const float len = Length(ray.d);
    // A channel that does not interact never scatters (an infinite distance, even when the ray
    // itself is unbounded).
    const float dist = sigmaT_[channel] > 0 ? -std::log(1 - u) / sigmaT_[channel] : Infinity;
    const float t = std::min(dist / len, ray.tMax);
    *scattered = t < ray.tMax;
    if (*scattered) *mi = {ray.At(t), t};
    const RGB tr = ExpNeg(sigmaT_, std::min(t * len, MaxDistance));
    const RGB density = *scattered ? sigmaT_ * tr : tr;
    const float pdf = density.Average();
    if (!(pdf > 0)) return RGB(0);
    return *scattered ? tr * sigmaS_ / pdf : tr / pdf;
}

bool HomogeneousMedium::Extent(const Ray &ray, float *t0, float *t1) const {
    *t0 = 0;
    *t1 = ray.tMax;
    return ray.tMax > 0;
}

float HomogeneousMedium::DefaultStep() const {
    const float s = sigmaT_.MaxComponent();
    return s > 0 ? 1 / (8 * s) : Infinity;
}

RGB HomogeneousMedium::Tau(const Ray &ray, float t0, float t1) const {
    return sigmaT_ * ((t1 - t0) * Length(ray.d));
}

// Grid.

GridDensityMedium::GridDensityMedium(const RGB &sigmaA, const RGB &sigmaS, float g, float stepSize,
                                     int nx, int ny, int nz, std::vector<float> density,
                                     const Vec3f &p0, const Vec3f &p1,
                                     const Transform &renderFromMedium)
    : Medium(sigmaA, sigmaS, g, stepSize), nx_(nx), ny_(ny), nz_(nz), density_(std::move(density)) {
    // pbrt-v3: the grid's [0,1]^3 maps to the box [p0, p1] of the medium's space.
    const Transform mediumFromGrid =
        Translate(Vec3d(p0)) * Scale(double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z);
    const Transform renderFromGrid = renderFromMedium * mediumFromGrid;
    gridFromRender_ = renderFromGrid.Inverse();
    voxelSize_ = std::min({Length(renderFromGrid.Vector(Vec3d(1.0 / nx, 0, 0))),
                           Length(renderFromGrid.Vector(Vec3d(0, 1.0 / ny, 0))),
                           Length(renderFromGrid.Vector(Vec3d(0, 0, 1.0 / nz)))});
    sigmaT_ = sigmaA[0] + sigmaS[0];
    float maxDensity = 0;
    for (float d : density_) maxDensity = std::max(maxDensity, d);
    invMaxDensity_ = maxDensity > 0 ? 1 / maxDensity : 0;
}

float GridDensityMedium::DensityGrid(const Vec3f &pg) const {
    // Samples sit at voxel centres (pbrt-v3 GridDensityMedium::Density).
    return VoxelLerp<float>(nx_, ny_, nz_, pg, [&](int x, int y, int z) {
        return density_[(size_t(z) * size_t(ny_) + size_t(y)) * size_t(nx_) + size_t(x)];
    });
}

float GridDensityMedium::Density(const Vec3f &pRender) const {
    return DensityGrid(gridFromRender_.Point(pRender));
}

bool GridDensityMedium::GridSegment(const Ray &ray, Ray *rg, float *t0, float *t1) const {
    rg->o = gridFromRender_.Point(ray.o);
    rg->d = gridFromRender_.Vector(ray.d);
    rg->tMax = ray.tMax;
    return ClipToBox(*rg, Vec3f(0, 0, 0), Vec3f(1, 1, 1), t0, t1);
}

bool GridDensityMedium::Extent(const Ray &ray, float *t0, float *t1) const {
    Ray rg;
    return GridSegment(ray, &rg, t0, t1);
}

RGB GridDensityMedium::Tr(const Ray &ray, MediumSampler &sampler) const {
    Ray rg;
    float t0, t1;
    if (!GridSegment(ray, &rg, &t0, &t1) || !(sigmaT_ > 0) || invMaxDensity_ == 0) return RGB(1);
    // Ratio tracking (pbrt-v3 GridDensityMedium::Tr) in units of the render-space distance,
    // with Russian roulette once the estimate is small.
    const float len = Length(ray.d), step = invMaxDensity_ / (sigmaT_ * len);
    float tr = 1, t = t0;
    for (;;) {
        t -= std::log(1 - sampler.Get1D()) * step;
        if (!(t < t1)) break;
        tr *= 1 - std::max(0.f, DensityGrid(rg.At(t)) * invMaxDensity_);
        if (tr < .1f) {
            const float q = std::max(.05f, 1 - tr);
            if (sampler.Get1D() < q) return RGB(0);
            tr /= 1 - q;
        }
    }
    return RGB(tr);
}

RGB GridDensityMedium::Sample(const Ray &ray, MediumSampler &sampler, MediumInteraction *mi,
                              bool *scattered) const {
    *scattered = false;
    Ray rg;
    float t0, t1;
    if (!GridSegment(ray, &rg, &t0, &t1) || !(sigmaT_ > 0) || invMaxDensity_ == 0) return RGB(1);
    // Delta tracking: tentative collisions against the majorant; a real one with probability
    // density / max density.
    const float len = Length(ray.d), step = invMaxDensity_ / (sigmaT_ * len);
    float t = t0;
    for (;;) {
        t -= std::log(1 - sampler.Get1D()) * step;
        if (!(t < t1)) break;
        if (DensityGrid(rg.At(t)) * invMaxDensity_ > sampler.Get1D()) {
            *scattered = true;
            *mi = {ray.At(t), t};
            return sigmaS_ / sigmaT_;
        }
    }
    return RGB(1);
}

RGB GridDensityMedium::Tau(const Ray &ray, float t0, float t1) const {
    const float d = DensityGrid(gridFromRender_.Point(ray.At(0.5f * (t0 + t1))));
    return RGB(sigmaT_ * d * (t1 - t0) * Length(ray.d));
}

RGB GridDensityMedium::SigmaS(const Vec3f &p) const { return sigmaS_ * Density(p); }

float GridDensityMedium::DefaultStep() const {
    const float s = sigmaT_ * (invMaxDensity_ > 0 ? 1 / invMaxDensity_ : 0);
    return std::min(s > 0 ? 1 / (8 * s) : Infinity, 0.5f * voxelSize_);
}

}  // namespace prism
