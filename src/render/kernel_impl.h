// The definitions of Kernel<K> (render/kernel.h) and of the tile loop that runs it; included
// only by the kernel_*.cpp files that instantiate the masks (and nowhere else, so the
// instantiations compile once, in parallel).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/differentials.h"
#include "render/distribution_integrator.h"
#include "render/kernel.h"
#include "render/medium.h"
#include "render/medium_tracking.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/sampler.h"

namespace prism {

// Media (render/kernel_media.h): the purposes of the march offsets and of the random streams
// of shadow rays through heterogeneous media, and the seed of such a stream for a sample.
enum MediumPurpose : uint32_t { MediumMarchPurpose = 0x6d617263, MediumShadowPurpose = 0x73686477 };
inline uint64_t MediumSeed(const SampleContext &sc, uint32_t purpose, uint32_t sampleSeed) {
    return (uint64_t(PatternSeed(sc.x, sc.y, purpose, sampleSeed)) << 32) | sc.sample;
}

template <uint32_t K>
RGB Kernel<K>::Escaped(const Ray &ray) const {
    RGB L;
    // Only infinite lights give radiance to escaping rays; without them (no light-sample bit)
    // the sum over the lights is 0.
    if (lightSamples_)
        for (const auto &light : scene_.lights) L += light->Le(ray);
    return L;
}

template <uint32_t K>
RGB Kernel<K>::Li(const Ray &ray, int depth, RayCounters &counters, const SampleContext &sc,
                  bool emitted) const {
    SurfaceInteraction si;
    if constexpr (Media) {
        const bool hit = scene_.accel->Intersect(ray, &si);
        return LiMedia(ray, hit, si, depth, counters, sc, emitted);
    } else {
        if (!scene_.accel->Intersect(ray, &si)) return Escaped(ray);
        return Shade(ray, si, depth, counters, sc, emitted);
    }
}

template <uint32_t K>
RGB Kernel<K>::LiCamera(const Ray &ray, const RawHit &hit, RayCounters &counters,
                        const SampleContext &sc) const {
    if constexpr (Media) {
        // Camera rays start in the camera's medium.
        SampleContext c = sc;
        c.medium = scene_.cameraMedium;
        if (hit.shape < 0) return LiMedia(ray, false, SurfaceInteraction{}, 0, counters, c, true);
        return LiMedia(ray, true, scene_.accel->Interaction(ray, hit), 0, counters, c, true);
    }
    if (hit.shape < 0) return Escaped(ray);
    return Shade(ray, scene_.accel->Interaction(ray, hit), 0, counters, sc, true);
}

template <uint32_t K>
bool Kernel<K>::AboveCutoff(const RGB &beta) const {
    return !(params_.trace.rayCutoff > 0 &&
             !(beta.MaxComponent() * scene_.filmScale > params_.trace.rayCutoff));
}

template <uint32_t K>
RGB Kernel<K>::Shade(const Ray &rayIn, SurfaceInteraction si, int depth, RayCounters &counters,
                     const SampleContext &sc, bool emitted) const {
    const ShapeInfo *shape = &scene_.Info(si);
    const Material *mat = &scene_.materials[size_t(shape->material)];
    const RayDifferential *diff = sc.diff;
    if (passThrough_) {
        Ray ray = rayIn;
        for (int pass = 0; mat->IsPassThrough(); ++pass) {
            if (pass >= MaxPassThrough) return RGB(0);
            diff = nullptr;  // as pbrt-v3: the continued ray has no differentials
            // pbrt: a surface without a BSDF continues the ray without counting a bounce.
            ray = si.SpawnRay(ray.d, scene_.offset);
            counters.passThrough++;
            if (!scene_.accel->Intersect(ray, &si)) return Escaped(ray);
            shape = &scene_.Info(si);
            mat = &scene_.materials[size_t(shape->material)];
        }
    }

    // Bump and normal maps move the shading normal before anything reads it (one test of a
    // flag per hit for scenes without them: no kernel bit).
    if (mat->PerturbsShading()) mat->PerturbShading(si);
    TextureContext tc = SurfaceTextureContext(si);
    // The footprint, where the ray carries differentials (only in scenes whose textures
    // filter: RenderScene::differentials); specular bounces pass it on.
    if (diff) ComputeDifferentials(si, *diff, &tc);
    const Vec3f &wo = si.wo;
    RGB L;
    // Emission of an area light seen directly or through specular paths.
    if (lightSamples_)
        if (shape->areaLight >= 0 && (!glossy_ || emitted))
            L += static_cast<const DiffuseAreaLight &>(*scene_.lights[size_t(shape->areaLight)])
                     .L(si, wo);
    // Emission a material carries itself ("gltf" emissive in .pbrt files): seen by every ray.
    if (mat->HasEmission()) L += mat->Emitted(tc);

    if constexpr (!GeneralBsdf) {
        // Only Lambertian matte materials (KernelMaskFor): f = kd/π, or 0 where the geometric
        // normal says wi is transmission, without building a BSDF. Nothing is specular or
        // glossy. The same bits as BSDF::f of one Lambertian part of weight 1.
        const RGB kd = mat->LambertianKd(tc);
        if (kd.IsBlack()) return L;
        const RGB f = kd * float(InvPi);
        const float cosO = Dot(wo, si.ns), woNg = Dot(wo, si.n);
        auto lambert = [&](const Vec3f &wi, bool) {
            return cosO == 0 || !(Dot(wi, si.n) * woNg > 0) ? RGB(0) : f;
        };
        AddDirect(si, si.ns, lambert, GlossyRays::None, false, depth, counters, sc, L);
        return L;
    } else {
        BSDF bsdf = mat->GetBSDF(si, tc);
        // Distribution: rough glass becomes glossy, and glossy rays sample the glossy lobes; the
        // lights those rays bring back are not light-sampled through them (GlossyRays).
        GlossyRays glossy = GlossyRays::None;
        if (glossy_ && params_.glossyRays) glossy = PrepareGlossy(bsdf, depth);
        // glTF occlusion: scales the environment's light and the indirect paths (1 elsewhere).
        const float ambient = mat->AmbientOcclusion(tc);
        // Direct lighting through the non-specular lobes.
        if (bsdf.HasNonSpecular()) {
            const bool hasDiffuse = glossy != GlossyRays::None && bsdf.HasDiffuse();
            auto general = [&](const Vec3f &wi, bool byGlossyRays) {
                return byGlossyRays ? bsdf.fDiffuse(wo, wi) : bsdf.f(wo, wi);
            };
            AddDirect(si, bsdf.ns, general, glossy, hasDiffuse, depth, counters, sc, L, ambient);
        }
        // Indirect paths, summed apart only when occlusion scales them (else straight into L,
        // in the same order as always).
        RGB indirect;
        RGB &Lind = ambient == 1 ? L : indirect;
        // The specular and glossy rays share the hit's ray-tree budget (render/ray_tree.h).
        uint64_t glossyRays = 0, specularRays = 0;
        if (glossy != GlossyRays::None) glossyRays = GlossyRayCount(bsdf, sc);
        if constexpr (Specular)
            specularRays = AddSpecular(si, tc, diff, bsdf, depth, counters, sc, glossyRays, Lind);
        if (glossy != GlossyRays::None)
            AddGlossy(si, bsdf, glossy, depth, counters, sc, specularRays, Lind);
        if (ambient != 1) L += indirect * ambient;
        return L;
    }
}

// Direct lighting: one shadow ray per delta light, and a stratified set of shadow rays per
// area or environment light (distribution ray tracing). f(wi, byGlossyRays) is the BSDF.
template <uint32_t K>
template <class F>
inline void Kernel<K>::AddDirect(const SurfaceInteraction &si, const Vec3f &ns, const F &f,
                                 GlossyRays glossy, bool hasDiffuse, int depth,
                                 RayCounters &counters, const SampleContext &sc, RGB &L,
                                 float ambient) const {
    if (!lightSamples_) {
        // Only delta lights: one sample each, which ignores u.
        for (size_t j = 0; j < scene_.lights.size(); ++j) {
            const Light &light = *scene_.lights[j];
            LightSample ls;
            if (!light.SampleLi(si, Vec2f(0.5f, 0.5f), &ls) || ls.Li.IsBlack() || !(ls.pdf > 0))
                continue;
            RGB fj = f(ls.wi, false);
            if (fj.IsBlack()) continue;
            Ray shadow = ls.infinite ? si.SpawnRay(ls.wi, scene_.offset)
                                     : si.SpawnRayTo(ls.pLight, scene_.offset);
            counters.shadow++;
            if (scene_.accel->Occluded(shadow)) continue;
            L += fj * ls.Li * (AbsDot(ls.wi, ns) / ls.pdf);
        }
    } else {
        AddDirectSampled(si, ns, f, glossy, hasDiffuse, depth, counters, sc, L, ambient);
    }
}

// The stratified light samples of AddDirect (lightSamples_), out of line so that the
// delta-light loop stays small enough to inline.
template <uint32_t K>
template <class F>
void Kernel<K>::AddDirectSampled(const SurfaceInteraction &si, const Vec3f &ns, const F &f,
                                 GlossyRays glossy, bool hasDiffuse, int depth,
                                 RayCounters &counters, const SampleContext &sc, RGB &L,
                                 float ambient) const {
    for (size_t j = 0; j < scene_.lights.size(); ++j) {
        const Light &light = *scene_.lights[j];
        int n = light.NumSamples();
        // Delta lights ignore u: the stratified pattern (a hash chain) only where it is used.
        const bool usesSample = light.UsesSample();
        // Whether this light reaches the glossy lobes through glossy rays only.
        const bool byGlossyRays =
            usesSample && (glossy == GlossyRays::AllLights ||
                           (glossy == GlossyRays::Environment && !light.IsArea()));
        if (byGlossyRays && !hasDiffuse) continue;
        uint32_t seed = usesSample
                            ? PatternSeed(sc.x, sc.y, uint32_t(2 + j * 131 + size_t(depth) * 7919),
                                          params_.seed)
                            : 0;
        RGB Lj;
        for (int k = 0; k < n; ++k) {
            Vec2f u = usesSample ? CMJSample(sc.sample * uint32_t(n) + uint32_t(k),
                                             sc.spp * uint32_t(n), seed)
                                 : Vec2f(0.5f, 0.5f);
            LightSample ls;
            if (!light.SampleLi(si, u, &ls) || ls.Li.IsBlack() || !(ls.pdf > 0)) continue;
            RGB fj = f(ls.wi, byGlossyRays);
            if (fj.IsBlack()) continue;
            Ray shadow = ls.infinite ? si.SpawnRay(ls.wi, scene_.offset)
                                     : si.SpawnRayTo(ls.pLight, scene_.offset);
            counters.shadow++;
            if constexpr (Media) {
                // Through the media and invisible boundaries toward the light.
                const int medium = MediumAfter(scene_.Info(si), si, ls.wi, sc.medium);
                MediumSampler sampler(MediumSeed(
                    sc,
                    uint32_t(MediumShadowPurpose + j * 131 + size_t(k) * 7 + size_t(depth) * 7919),
                    params_.seed));
                const RGB tr =
                    ShadowTransmittance(scene_, shadow, medium, ls.infinite, sampler, counters);
                if (tr.IsBlack()) continue;
                Lj += fj * ls.Li * tr * (AbsDot(ls.wi, ns) / ls.pdf);
            } else {
                if (scene_.accel->Occluded(shadow)) continue;
                Lj += fj * ls.Li * (AbsDot(ls.wi, ns) / ls.pdf);
            }
        }
        // The environment (sampled, not an area light) is scaled by the ambient occlusion.
        if (usesSample && !light.IsArea() && ambient != 1) Lj = Lj * ambient;
        L += n == 1 ? Lj : Lj / float(n);
    }
}

template <uint32_t K>
uint64_t Kernel<K>::AddSpecular(const SurfaceInteraction &si, const TextureContext &tc,
                                const RayDifferential *diff, const BSDF &bsdf, int depth,
                                RayCounters &counters, const SampleContext &sc, uint64_t glossyRays,
                                RGB &L) const {
    const Vec3f &wo = si.wo;
    // Specular recursion, for the delta lobes of every BSDF part (mix materials have several).
    if (depth + 1 >= params_.trace.maxDepth) return 0;
    // The rays of the lobes, in lobe order, that the ray-weight cutoff leaves: a ray "can
    // change the pixel by more than the cutoff" when its throughput (max RGB component, times
    // the Film's scale) exceeds the cutoff, as if it brought back radiance 1 (pbrt-style ray
    // weights; the pixel filter's share of the sample is ignored). Cutoff 0 traces every ray,
    // exactly as without the cutoff.
    struct SpecularRay {
        Vec3f wi;
        RGB weight;
        float eta;  // the part's eta (refraction)
        bool reflect;
    };
    SpecularRay rays[2 * BSDF::MaxParts];
    int n = 0;
    auto keep = [&](const Vec3f &wi, const RGB &weight, float eta, bool reflect) {
        if (!AboveCutoff(sc.beta * weight)) {
            counters.cutoff++;
            return;
        }
        rays[n++] = {wi, weight, eta, reflect};
    };
    for (int part = 0; part < bsdf.NumParts(); ++part) {
        Vec3f wi;
        RGB weight;
        if (bsdf.SampleSpecularReflection(part, wo, &wi, &weight)) keep(wi, weight, 0.f, true);
        if (bsdf.SampleSpecularTransmission(part, wo, &wi, &weight))
            keep(wi, weight, bsdf.Part(part).eta, false);
    }
    // The first rays of the hit within its ray-tree budget, each with an even share of it.
    const RayTreeShare share = ShareRayTree(sc.treeRays, uint64_t(n) + glossyRays);
    // The surface's curvature across the footprint, once per hit whose rays carry
    // differentials (render/differentials.h).
    NormalDifferentials dn;
    if (diff && n > 0 && share.traced > 0)
        dn = FootprintNormalDifferentials(*scene_.accel, si, tc, bsdf.ns);
    for (int i = 0; i < n; ++i) {
        if (uint64_t(i) >= share.traced) {
            counters.treeBudget += uint64_t(n - i);
            break;
        }
        const SpecularRay &r = rays[i];
        SampleContext next = sc;
        next.beta = sc.beta * r.weight;
        next.treeRays = share.each;
        if constexpr (Media) next.medium = MediumAfter(scene_.Info(si), si, r.wi, sc.medium);
        (r.reflect ? counters.reflection : counters.refraction)++;
        // The reflected or refracted ray's differentials (pbrt-v3 SpecularReflect/Transmit).
        RayDifferential rd;
        next.diff = nullptr;
        if (diff) {
            rd = r.reflect ? ReflectDifferential(si, tc, *diff, bsdf.ns, dn, r.wi)
                           : RefractDifferential(si, tc, *diff, bsdf.ns, dn, r.wi, r.eta);
            next.diff = &rd;
        }
        L += r.weight * Li(si.SpawnRay(r.wi, scene_.offset), depth + 1, counters, next);
    }
    return uint64_t(n);
}

template <uint32_t K>
GlossyRays Kernel<K>::PrepareGlossy(BSDF &bsdf, int depth) const {
    if (!bsdf.MakeRoughSpecularGlossy() || depth + 1 >= params_.trace.maxDepth)
        return GlossyRays::None;
    for (int i = 0; i < bsdf.NumParts(); ++i) {
        const BxDFLobes &l = bsdf.Part(i);
        if (!bsdf.Weight(i).IsBlack() && l.HasGlossy() &&
            std::min(l.alphaX, l.alphaY) < GlossyLightSampleAlpha)
            return GlossyRays::AllLights;
    }
    return GlossyRays::Environment;
}

template <uint32_t K>
uint64_t Kernel<K>::GlossyRayCount(const BSDF &bsdf, const SampleContext &sc) const {
    uint64_t parts = 0;
    for (int part = 0; part < bsdf.NumParts(); ++part)
        if (!bsdf.Weight(part).IsBlack() && bsdf.Part(part).HasGlossy()) ++parts;
    return parts * (sc.afterGlossy ? 1u : uint64_t(params_.glossySamples));
}

template <uint32_t K>
void Kernel<K>::AddGlossy(const SurfaceInteraction &si, const BSDF &bsdf, GlossyRays mode,
                          int depth, RayCounters &counters, const SampleContext &sc,
                          uint64_t specularRays, RGB &L) const {
    const bool emitted = mode == GlossyRays::AllLights;
    const uint32_t n = sc.afterGlossy ? 1u : uint32_t(params_.glossySamples);
    // The hit's share of the ray tree (render/ray_tree.h): its specular rays came first.
    const RayTreeShare share = ShareRayTree(sc.treeRays, specularRays + GlossyRayCount(bsdf, sc));
    uint64_t nth = specularRays;  // this ray's place among the hit's rays
    // The rays below sample the pixel's samples × n further: the hits they reach stratify
    // their own samples over that larger set (while the count stays small).
    const bool refine = uint64_t(sc.spp) * n <= (1u << 24);
    for (int part = 0; part < bsdf.NumParts(); ++part) {
        if (bsdf.Weight(part).IsBlack() || !bsdf.Part(part).HasGlossy()) continue;
        // A stratified pattern over the pixel's samples × n, per pixel, depth and part.
        const uint32_t seed =
            PatternSeed(sc.x, sc.y, uint32_t(0x6c6f7373u + uint32_t(depth) * 977u + uint32_t(part)),
                        (sc.afterGlossy ? 0x9e3779b9u : 0u) + params_.seed);
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t index = sc.sample * n + k;
            Vec2f u = CMJSample(index, sc.spp * n, seed);
            float uc = HashFloat(index, seed ^ 0x5bd1e995u);
            Vec3f wi;
            RGB weight;
            if (!bsdf.SampleGlossy(part, si.wo, u, uc, &wi, &weight)) continue;
            if (n > 1) weight = weight / float(n);
            SampleContext next = sc;
            next.beta = sc.beta * weight;
            next.afterGlossy = true;
            next.diff = nullptr;  // glossy rays filter nothing (pbrt-v3 drops them too)
            if constexpr (Media) next.medium = MediumAfter(scene_.Info(si), si, wi, sc.medium);
            if (refine) {
                next.sample = index;
                next.spp = sc.spp * n;
            }
            if (!AboveCutoff(next.beta)) {
                counters.cutoff++;
                continue;
            }
            if (nth++ >= share.traced) {
                counters.treeBudget++;
                continue;
            }
            next.treeRays = share.each;
            counters.glossy++;
            L += weight * Li(si.SpawnRay(wi, scene_.offset), depth + 1, counters, next, emitted);
        }
    }
}

// Camera rays are traced in packets of up to RenderPacketW x RenderPacketH pixels at one sample
// index (coherent rays through Embree's 16-wide packet path), then shaded one by one from their
// hits, each sample's radiance into its slot of `out` (the driver adds them to the film in
// pixel-then-sample order).
template <uint32_t K>
void RenderTileKernel(const TileContext &ctx, const KernelParams &params, TileSamples &out,
                      RayCounters &rc) {
    constexpr int PacketW = RenderPacketW, PacketH = RenderPacketH;
    const RenderScene &scene = ctx.scene;
    const CameraSampler &camera = ctx.camera;
    const Kernel<K> kernel(scene, params);
    const Bounds2i tb = out.bounds;
    const uint32_t spp = out.spp;
    const bool lens = camera.Lens();
    const bool differentials = camera.Differentials();
    Ray rays[16];
    RayDifferential diffs[16];
    RawHit hits[16];
    size_t slot[16];
    int pixelX[16], pixelY[16];
    CameraSampler::Seeds seeds[16];
    const bool seeded = camera.Seeded();
    for (int by = tb.pMin.y; by < tb.pMax.y; by += PacketH) {
        for (int bx = tb.pMin.x; bx < tb.pMax.x; bx += PacketW) {
            const int ex = std::min(bx + PacketW, tb.pMax.x),
                      ey = std::min(by + PacketH, tb.pMax.y);
            // The packet's pattern seeds, once for all its samples.
            int m = 0;
            if (seeded)
                for (int y = by; y < ey; ++y)
                    for (int x = bx; x < ex; ++x, ++m) seeds[m] = camera.PixelSeeds(x, y);
            for (uint32_t s = 0; s < spp; ++s) {
                // Once per packet of camera rays: a deep packet (1600 spp of mirror chains in
                // Hostile.InterruptStopsARenderInsideItsOnlyTile) took 25 s between checks.
                if (ctx.Cancelled()) return;
                m = 0;
                for (int y = by; y < ey; ++y) {
                    for (int x = bx; x < ex; ++x, ++m) {
                        const CameraSample cs = camera.Sample(x, y, s, seeds[m]);
                        rays[m] = camera.GenerateRay(cs);
                        if (differentials) diffs[m] = camera.GenerateDifferential(rays[m], cs);
                        slot[m] = out.Index(x, y, s);
                        pixelX[m] = x;
                        pixelY[m] = y;
                        if (out.wantPositions) out.pFilm[slot[m]] = cs.pFilm;
                    }
                }
                if (lens) rc.lensSamples += uint64_t(m);
                scene.accel->IntersectCameraPacket(rays, m, hits);
                scene.accel->PrefetchHits(hits, m);
                rc.camera += uint64_t(m);
                for (int i = 0; i < m; ++i) {
                    SampleContext sc{pixelX[i], pixelY[i], s, spp};
                    if (differentials) sc.diff = &diffs[i];
                    out.L[slot[i]] = kernel.LiCamera(rays[i], hits[i], rc, sc);
                    if (out.wantDirect)
                        out.direct[slot[i]] =
                            KernelDirectLiCamera(scene, params, rays[i], hits[i], rc, sc);
                }
            }
        }
    }
}

}  // namespace prism

#include "render/kernel_media.h"

namespace prism {

// Explicit instantiation of one mask (kernel_*.cpp).
#define PRISM_INSTANTIATE_KERNEL(M)                                                             \
    template class Kernel<M>;                                                                   \
    template void RenderTileKernel<M>(const TileContext &, const KernelParams &, TileSamples &, \
                                      RayCounters &);

}  // namespace prism
