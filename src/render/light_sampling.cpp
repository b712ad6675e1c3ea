#include "render/light_sampling.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/estimate_direct.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

namespace {

Bounds3f SceneBounds(const RenderScene &scene) {
    Bounds3f b;
    for (int s = 0; s < scene.accel->NumShapes(); ++s) {
        if (const TriangleMesh *m = scene.accel->Mesh(s)) {
            for (size_t i = 0; i < m->NumVertices(); ++i) b.Expand(m->Position(uint32_t(i)));
        } else if (const AnalyticShape *a = scene.accel->Analytic(s)) {
            b.Expand(a->RenderBounds());
        } else if (const CurveSet *c = scene.accel->Curves(s)) {
            b.Expand(c->RenderBounds());
        }
    }
    return b;
}

// The scene's bounding sphere radius (for the power of distant and infinite lights).
double SceneRadius(const RenderScene &scene) {
    const Bounds3f b = SceneBounds(scene);
    if (b.IsEmpty()) return 1;
    return std::max(0.5 * double(Length(b.Diagonal())), 1e-3);
}

}  // namespace

SceneSphere BoundingSphere(const RenderScene &scene) {
    SceneSphere s;
    if (!scene.accel) return s;
    const Bounds3f b = SceneBounds(scene);
    s.radius = float(SceneRadius(scene));
    if (!b.IsEmpty()) s.center = (b.pMin + b.pMax) * 0.5f;
    return s;
}

void ComputeLightPower(RenderScene &scene) {
    scene.lightPower.clear();
    if (scene.lights.empty() || !scene.accel) return;
    const double radius = SceneRadius(scene);
    for (const auto &light : scene.lights) scene.lightPower.push_back(light->Power(radius));
}

LightChooser::LightChooser(const RenderScene &scene, LightChoice choice)
    : n_(int(scene.lights.size())) {
    if (choice == LightChoice::BVH && n_ > 0) {
        std::vector<const Light *> lights;
        for (const auto &light : scene.lights) lights.push_back(light.get());
        // Lights from infinitely far: their power over the scene sphere's squared radius (pi
        // times the irradiance they give), against the parts' importance.
        std::vector<double> infinite;
        if (scene.lightPower.size() == size_t(n_) && scene.accel) {
            const double r = SceneRadius(scene);
            for (double power : scene.lightPower) infinite.push_back(power / (r * r));
        }
        bvh_ = std::make_shared<const LightBVH>(lights, infinite);
    }
    if (choice == LightChoice::Uniform || scene.lightPower.size() != size_t(n_)) return;
    auto power = [&](int i) {
        double p = scene.lightPower[size_t(i)];
        return std::isfinite(p) ? std::max(0.0, p) : 0.0;
    };
    double sum = 0;
    for (int i = 0; i < n_; ++i) sum += power(i);
    if (!(sum > 0)) return;
    cdf_.resize(size_t(n_));
    double run = 0;
    for (int i = 0; i < n_; ++i) {
        run += power(i) / sum;
        cdf_[size_t(i)] = run;
    }
    cdf_.back() = 1;
}

std::string LightChooser::Summary() const {
    if (n_ == 0) return {};
    if (bvh_) {
        std::string s = "lights: chosen by the light BVH (" + std::to_string(bvh_->NumParts()) +
                        (bvh_->NumParts() == 1 ? " part" : " parts") + ", depth " +
                        std::to_string(bvh_->Depth());
        if (bvh_->NumInfinite() > 0)
            s += "; " + std::to_string(bvh_->NumInfinite()) + " from infinitely far";
        return s + ")";
    }
    return cdf_.empty() ? "lights: chosen uniformly" : "lights: chosen by power";
}

int LightChooser::Choose(float u, float *prob) const {
    if (n_ == 0) return -1;
    if (cdf_.empty()) {
        *prob = 1.f / float(n_);
        return std::min(int(u * float(n_)), n_ - 1);
    }
    int i = int(std::upper_bound(cdf_.begin(), cdf_.end(), double(u)) - cdf_.begin());
    i = std::min(i, n_ - 1);
    // A light of power 0 is never chosen (a u on its empty interval moves to the next one).
    while (i < n_ - 1 && cdf_[size_t(i)] == (i > 0 ? cdf_[size_t(i) - 1] : 0.0)) ++i;
    *prob = float(cdf_[size_t(i)] - (i > 0 ? cdf_[size_t(i) - 1] : 0.0));
    return i;
}

float LightChooser::Prob(int i) const {
    if (i < 0 || i >= n_) return 0;
    if (cdf_.empty()) return 1.f / float(n_);
    return float(cdf_[size_t(i)] - (i > 0 ? cdf_[size_t(i) - 1] : 0.0));
}

RGB EstimateDirect(const RenderScene &scene, const SurfaceInteraction &si, const BSDF &bsdf,
                   int lightIndex, Vec2f uLight, Vec2f uScatter, float uLobe,
                   RayCounters &counters) {
    return EstimateDirectWith(scene, si, BsdfScatter{bsdf}, lightIndex, uLight, uScatter, uLobe,
                              counters, NoMediaVisibility{});
}

RGB SampleOneLight(const RenderScene &scene, const LightChooser &chooser,
                   const SurfaceInteraction &si, const BSDF &bsdf, const PixelSamples &ps,
                   int bounce, RayCounters &counters) {
    return SampleOneLightWith(scene, chooser, si, BsdfScatter{bsdf}, ps, bounce, counters,
                              NoMediaVisibility{});
}

RGB SampleAllLights(const RenderScene &scene, const SurfaceInteraction &si, const BSDF &bsdf,
                    const PixelSamples &ps, int depth, RayCounters &counters) {
    RGB L;
    for (size_t j = 0; j < scene.lights.size(); ++j) {
        const Light &light = *scene.lights[j];
        const uint32_t n = light.IsDelta() ? 1u : uint32_t(light.NumSamples());
        // Each light has dimensions of its own (a stratified pattern over spp × n).
        const uint32_t base = VertexDim(depth, 0) + 0x10000u * uint32_t(j + 1);
        RGB Lj;
        for (uint32_t k = 0; k < n; ++k) {
            const Vec2f uLight = ps.Get2D(base + DimLight, k, n);
            const Vec2f uScatter = ps.Get2D(base + DimScatter, k, n);
            const float uLobe = ps.Get2D(base + DimScatterLobe, k, n).x;
            Lj += EstimateDirect(scene, si, bsdf, int(j), uLight, uScatter, uLobe, counters);
        }
        L += n == 1 ? Lj : Lj / float(n);
    }
    return L;
}

bool SampleNextDirection(const BSDF &bsdf, const Vec3f &wo, const PixelSamples &ps, int bounces,
                         RGB &beta, bool &specularBounce, float &etaScale, Vec3f *wi,
                         RayCounters &counters, uint32_t dimShift) {
    BSDFSample bs;
    if (!bsdf.Sample_f(wo, ps.Get2D(VertexDim(bounces, DimBsdf + dimShift)),
                       ps.Get1D(VertexDim(bounces, DimBsdfLobe + dimShift)), true, &bs))
        return false;
    beta *= bs.weight;
    specularBounce = bs.specular;
    if (bs.specular && bs.transmission) etaScale *= bs.eta * bs.eta;
    *wi = bs.wi;
    if (bs.transmission)
        counters.refraction++;
    else
        counters.reflection++;
    return true;
}

}  // namespace prism
