// The media part of Kernel<K> (render/kernel.h), compiled only into KernelMediaMask (included by
// kernel_impl.h). A ray carries its medium (SampleContext::medium): the camera's for camera
// rays, and across a surface with a MediumInterface the inside or outside medium by the side
// it leaves toward; other surfaces keep the current medium (pbrt-v3). Every segment in a
// medium is attenuated by its transmittance and adds the light the medium scatters toward the
// ray's origin from the delta lights (point, spot, distant), ray-marched with a jittered
// offset per pixel sample as pbrt-v2's SingleScatteringIntegrator does; shadow rays pass
// through media and "none" surfaces (pbrt-v3's VisibilityTester::Tr).
#pragma once

#include <algorithm>
#include <cmath>

#include "render/kernel.h"
#include "render/medium_tracking.h"

namespace prism {

// A ray march takes at most this many steps per segment (the step grows beyond it), and at
// least MinMarchSteps when the medium chooses its step (no "stepsize").
inline constexpr int MaxMarchSteps = 1 << 14, MinMarchSteps = 32;
// An unbounded segment (a ray escaping inside a homogeneous medium) is marched until the
// transmittance of every scattering channel falls below this.
inline constexpr float MarchMinTransmittance = 1e-4f;

template <uint32_t K>
RGB Kernel<K>::LiMedia(Ray ray, bool hit, SurfaceInteraction si, int depth, RayCounters &counters,
                       const SampleContext &sc, bool emitted) const {
    int medium = sc.medium;
    RGB L, T(1);
    Vec3f from = ray.o;
    bool crossed = false;
    for (int pass = 0;; ++pass) {
        if (medium >= 0) {
            const Ray segment = MediumSegment(ray, from, hit ? &si.p : nullptr);
            L += T * InScattered(segment, segment.tMax, medium, depth, counters, sc);
            MediumSampler sampler(MediumSeed(
                sc, MediumShadowPurpose ^ uint32_t(depth * 977 + pass * 31 + 1), params_.seed));
            T *= scene_.media[size_t(medium)]->Tr(segment, sampler);
            if (T.IsBlack()) return L;
        }
        if (!hit) return L + T * Escaped(ray);
        const ShapeInfo &shape = scene_.Info(si);
        if (!scene_.materials[size_t(shape.material)].IsPassThrough()) break;
        // An invisible surface (a medium boundary): the ray continues, maybe in another medium.
        if (pass >= MaxPassThrough) return L;
        medium = MediumAfter(shape, si, ray.d, medium);
        ray = si.SpawnRay(ray.d, scene_.offset);
        from = si.p;
        crossed = true;
        counters.passThrough++;
        hit = scene_.accel->Intersect(ray, &si);
    }
    SampleContext next = sc;
    next.medium = medium;
    // As the kernel's pass-through loop: a ray continued through a surface has no differentials.
    if (crossed) next.diff = nullptr;
    return L + T * Shade(ray, si, depth, counters, next, emitted);
}

template <uint32_t K>
RGB Kernel<K>::InScattered(const Ray &ray, float tEnd, int mediumIndex, int depth,
                           RayCounters &counters, const SampleContext &sc) const {
    const Medium &m = *scene_.media[size_t(mediumIndex)];
    if (m.SigmaScatter().IsBlack()) return RGB(0);
    Ray segment = ray;
    segment.tMax = tEnd;
    float t0, t1;
    if (!m.Extent(segment, &t0, &t1)) return RGB(0);
    const float len = Length(ray.d);
    if (!(t1 < Infinity)) {
        const RGB sigmaT = m.SigmaA() + m.SigmaScatter();
        float s = Infinity;
        for (int c = 0; c < 3; ++c)
            if (m.SigmaScatter()[c] > 0 && sigmaT[c] > 0) s = std::min(s, sigmaT[c]);
        if (!(s < Infinity)) return RGB(0);
        t1 = t0 + -std::log(MarchMinTransmittance) / (s * len);
    }
    if (!(t1 > t0)) return RGB(0);
    const float step = m.StepSize() > 0 ? m.StepSize() : m.DefaultStep();
    const float minSteps = m.StepSize() > 0 ? 1.f : float(MinMarchSteps);
    const float steps = std::ceil((t1 - t0) * len / step);
    const int n = int(std::clamp(steps, minSteps, float(MaxMarchSteps)));
    const float dt = (t1 - t0) / float(n);
    // One jittered offset per sample, stratified over the pixel's samples.
    const float u = CMJSample(sc.sample, sc.spp,
                              PatternSeed(sc.x, sc.y, MediumMarchPurpose + uint32_t(depth) * 977u,
                                          params_.seed))
                        .x;
    SurfaceInteraction at;
    at.wo = -ray.d / len;
    at.time = ray.time;
    RGB Ls, tau;
    float tPrev = t0;
    for (int i = 0; i < n; ++i) {
        const float t = t0 + (float(i) + u) * dt;
        tau += m.Tau(ray, tPrev, t);
        tPrev = t;
        at.p = ray.At(t);
        const RGB ss = m.SigmaS(at.p);
        if (ss.IsBlack()) continue;
        RGB T;
        for (int c = 0; c < 3; ++c) T[c] = std::exp(-tau[c]);
        if (T.IsBlack()) break;
        for (size_t j = 0; j < scene_.lights.size(); ++j) {
            const Light &light = *scene_.lights[j];
            if (light.UsesSample()) continue;  // area and infinite lights are not marched
            LightSample ls;
            if (!light.SampleLi(at, Vec2f(0.5f, 0.5f), &ls) || ls.Li.IsBlack() || !(ls.pdf > 0))
                continue;
            const float phase = m.Phase().p(at.wo, ls.wi);
            Ray shadow{at.p, ls.infinite ? ls.wi : ls.pLight - at.p,
                       ls.infinite ? Infinity : 1 - ShadowEpsilon, 0, ray.time};
            counters.shadow++;
            const uint32_t purpose = MediumShadowPurpose + uint32_t(i) * 0x9e3779b9u +
                                     uint32_t(j * 131 + 17) + uint32_t(depth) * 7919u;
            MediumSampler sampler(MediumSeed(sc, purpose, params_.seed));
            const RGB tr =
                ShadowTransmittance(scene_, shadow, mediumIndex, ls.infinite, sampler, counters);
            Ls += T * ss * ls.Li * tr * (phase / ls.pdf);
        }
    }
    return Ls * (dt * len);
}

}  // namespace prism
