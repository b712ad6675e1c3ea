#include "render/light_sampling.h"

#include <algorithm>
#include <cmath>

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/render_scene.h"
#include "render/whitted.h"

namespace prism {

namespace {

// Consecutive "none" surfaces a BSDF-sampled ray may cross on its way to a light.
constexpr int MaxPassThroughCrossings = 256;

// The scene's bounding sphere radius (for the power of distant and infinite lights).
double SceneRadius(const RenderScene &scene) {
    Bounds3f b;
    for (int s = 0; s < scene.accel->NumShapes(); ++s) {
        if (const TriangleMesh *m = scene.accel->Mesh(s)) {
            for (size_t i = 0; i < m->NumVertices(); ++i) b.Expand(m->Position(uint32_t(i)));
        } else if (const AnalyticShape *a = scene.accel->Analytic(s)) {
            b.Expand(a->RenderBounds());
        }
    }
    if (b.IsEmpty()) return 1;
    return std::max(0.5 * double(Length(b.Diagonal())), 1e-3);
}

}  // namespace

void ComputeLightPower(RenderScene &scene) {
    scene.lightPower.clear();
    if (scene.lights.empty() || !scene.accel) return;
    const double radius = SceneRadius(scene);
    for (const auto &light : scene.lights) scene.lightPower.push_back(light->Power(radius));
}

LightChooser::LightChooser(const RenderScene &scene) : n_(int(scene.lights.size())) {
    if (scene.lightChoice == LightChoice::Uniform || scene.lightPower.size() != size_t(n_)) return;
    auto power = [&](int i) {
        double p = scene.lightPower[size_t(i)];
        return std::isfinite(p) ? std::max(0.0, p) : 0.0;
    };
    double sum = 0;
    for (int i = 0; i < n_; ++i) sum += power(i);
    if (!(sum > 0)) return;
    // Spatial's stand-in: half the choices by power, half uniform (defensive sampling).
    const double uniformShare = scene.lightChoice == LightChoice::Spatial ? 0.5 : 0.0;
    cdf_.resize(size_t(n_));
    double run = 0;
    for (int i = 0; i < n_; ++i) {
        run += (1 - uniformShare) * power(i) / sum + uniformShare / n_;
        cdf_[size_t(i)] = run;
    }
    cdf_.back() = 1;
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

RGB EstimateDirect(const RenderScene &scene, const SurfaceInteraction &si, const BSDF &bsdf,
                   int lightIndex, Vec2f uLight, Vec2f uScatter, float uLobe,
                   RayCounters &counters) {
    const Light &light = *scene.lights[size_t(lightIndex)];
    const Vec3f &wo = si.wo;
    RGB Ld;
    // The light sample, weighted against the BSDF's density.
    LightSample ls;
    if (light.SampleLi(si, uLight, &ls) && ls.pdf > 0 && !ls.Li.IsBlack()) {
        const RGB f = bsdf.f(wo, ls.wi) * AbsDot(ls.wi, bsdf.ns);
        if (!f.IsBlack()) {
            Ray shadow = ls.infinite ? si.SpawnRay(ls.wi, scene.offset)
                                     : si.SpawnRayTo(ls.pLight, scene.offset);
            counters.shadow++;
            if (!scene.accel->Occluded(shadow)) {
                if (light.IsDelta()) {
                    Ld += f * ls.Li / ls.pdf;
                } else {
                    const float w = PowerHeuristic(1, ls.pdf, 1, bsdf.Pdf(wo, ls.wi));
                    Ld += f * ls.Li * (w / ls.pdf);
                }
            }
        }
    }
    if (light.IsDelta()) return Ld;
    // The BSDF sample, weighted against the light's density; it counts only if the ray meets
    // this light first.
    BSDFSample bs;
    if (!bsdf.Sample_f(wo, uScatter, uLobe, false, &bs)) return Ld;
    Ray ray = si.SpawnRay(bs.wi, scene.offset);
    counters.shadow++;
    SurfaceInteraction hit;
    for (int pass = 0;; ++pass) {
        if (!scene.accel->Intersect(ray, &hit)) {
            const RGB Le = light.Le(ray);
            if (Le.IsBlack()) return Ld;
            const float lightPdf = light.PdfLi(si, bs.wi, nullptr);
            return Ld + bs.weight * Le * PowerHeuristic(1, bs.pdf, 1, lightPdf);
        }
        const ShapeInfo &info = scene.Info(hit);
        if (!scene.materials[size_t(info.material)].IsPassThrough()) break;
        if (pass >= MaxPassThroughCrossings) return Ld;
        ray = hit.SpawnRay(ray.d, scene.offset);
        counters.passThrough++;
    }
    if (scene.Info(hit).areaLight != lightIndex) return Ld;
    const RGB Le = static_cast<const DiffuseAreaLight &>(light).L(hit, -bs.wi);
    if (Le.IsBlack()) return Ld;
    const float lightPdf = light.PdfLi(si, bs.wi, &hit);
    if (!(lightPdf > 0)) return Ld;
    return Ld + bs.weight * Le * PowerHeuristic(1, bs.pdf, 1, lightPdf);
}

RGB SampleOneLight(const RenderScene &scene, const LightChooser &chooser,
                   const SurfaceInteraction &si, const BSDF &bsdf, const PixelSamples &ps,
                   int bounce, RayCounters &counters) {
    float prob = 0;
    const int j = chooser.Choose(ps.Get1D(VertexDim(bounce, DimLightChoice)), &prob);
    if (j < 0 || !(prob > 0)) return RGB(0);
    return EstimateDirect(scene, si, bsdf, j, ps.Get2D(VertexDim(bounce, DimLight)),
                          ps.Get2D(VertexDim(bounce, DimScatter)),
                          ps.Get1D(VertexDim(bounce, DimScatterLobe)), counters) /
           prob;
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

}  // namespace prism
