// The tile loop of the path and directlighting integrators: for every pixel of a tile and
// every sample, a camera ray (film position, lens and time stratified as the Whitted kernel
// draws them) whose radiance the integrator returns, added to the tile in pixel-then-sample
// order. Every sample is a pure function of (pixel, sample index), so images do not depend on
// the thread count.
#pragma once

#include <algorithm>
#include <cmath>

#include "image/film.h"
#include "render/camera.h"
#include "render/light_sampling.h"
#include "render/render_scene.h"
#include "render/sampler.h"
#include "render/whitted.h"

namespace prism {

// li(ray, samples, counters) -> RGB: the integrator's radiance along a camera ray.
template <class LiFn>
void RenderTileSamples(const RenderScene &scene, Bounds2i tb, RayCounters &rc, FilmTile *tile,
                       const LiFn &li) {
    const uint32_t spp = uint32_t(scene.spp);
    const bool lens = scene.features.lens;
    const bool motion = scene.features.effects.Has(Effect::MotionBlur);
    const CMJPattern cmj(spp);
    const bool jitter = scene.JitterFilmSamples();
    // Ray differentials for filtered textures (as the kernel's tile loop).
    const float diffScale = std::max(.125f, 1 / std::sqrt(float(spp)));
    for (int y = tb.pMin.y; y < tb.pMax.y; ++y) {
        for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
            const uint32_t filmSeed = PatternSeed(x, y, FilmPurpose, scene.sampleSeed);
            const uint32_t lensSeed = lens ? PatternSeed(x, y, LensPurpose, scene.sampleSeed) : 0;
            const uint32_t timeSeed = motion ? PatternSeed(x, y, TimePurpose, scene.sampleSeed) : 0;
            for (uint32_t s = 0; s < spp; ++s) {
                const Vec2f u = jitter ? cmj.Sample(s, filmSeed) : Vec2f(0.5f, 0.5f);
                const Vec2f pFilm = FilmPosition(x, y, u);
                Vec2f uLens(0.5f, 0.5f);
                if (lens) {
                    uLens = cmj.Sample(s, lensSeed);
                    rc.lensSamples++;
                }
                const float time = motion ? cmj.Sample(s, timeSeed).x : 0.f;
                const Ray ray = scene.camera->GenerateRay(pFilm, uLens, time);
                rc.camera++;
                PixelSamples ps{x, y, s, spp, scene.samplePattern, scene.sampleSeed};
                RayDifferential rd;
                if (scene.differentials) {
                    rd = scene.camera->GenerateDifferential(ray, pFilm, uLens, time, diffScale);
                    ps.diff = &rd;
                }
                RGB L = li(ray, ps, rc) * scene.filmScale;
                if (scene.maxSampleLuminance < Infinity && L.IsFinite()) {
                    const float lum = L.Luminance();
                    if (lum > scene.maxSampleLuminance) L *= scene.maxSampleLuminance / lum;
                }
                tile->AddSample(pFilm, L);
            }
        }
    }
}

// The tile loop of an integrator constructed from the scene whose Li(ray, samples, counters)
// gives a camera ray's radiance.
template <class Integrator>
void RenderTileWith(const RenderScene &scene, Bounds2i tb, RayCounters &rc, FilmTile *tile) {
    const Integrator integrator(scene);
    RenderTileSamples(scene, tb, rc, tile,
                      [&](const Ray &ray, const PixelSamples &ps, RayCounters &c) {
                          return integrator.Li(ray, ps, c);
                      });
}

}  // namespace prism
