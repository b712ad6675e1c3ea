#include "tools/bench/ceiling.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "assembly/build_scene.h"
#include "image/film.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "scene/load_scene.h"

namespace prism {

namespace {

struct PassCounters {
    uint64_t camera = 0, hits = 0, shadow = 0, occluded = 0;
};

struct Scratch {
    std::vector<Ray> rays;
    std::vector<RawHit> hits;
    std::vector<int> packets;  // rays per camera packet, in order
};

// One shadow ray from p toward each light (one sample for area and infinite lights). The
// origin is not offset along the normal (that needs the shading geometry the pass skips): a
// tiny tMin keeps the ray off its own surface instead.
inline void TraceShadowRays(const RenderScene &scene, const Ray &ray, float t, PassCounters &pc) {
    SurfaceInteraction si;
    si.p = ray.At(t);
    Vec3f w = -Normalize(ray.d);
    si.n = si.ns = si.wo = w;
    si.t = t;
    for (const auto &light : scene.lights) {
        LightSample ls;
        if (!light->SampleLi(si, Vec2f(0.5f, 0.5f), &ls)) continue;
        Ray s;
        s.o = si.p;
        if (ls.infinite) {
            s.d = ls.wi;
            s.tMax = Infinity;
            s.tMin = 1e-4f * (1 + std::max({std::abs(si.p.x), std::abs(si.p.y), std::abs(si.p.z)}));
        } else {
            s.d = ls.pLight - si.p;
            s.tMax = 1 - ShadowEpsilon;
            s.tMin = 1e-4f;
        }
        pc.shadow++;
        pc.occluded += scene.accel->Occluded(s);
    }
}

// The ceiling pass: the render loop's tiles (ForEachTile over the film's tile grid) and camera
// rays (the render's CameraSampler), traversal only.
PassCounters TraceCeiling(const RenderScene &scene, CeilingTraversal traversal) {
    const TiledFilm grid(scene.resolution, scene.pixelBounds, scene.filter, RenderTileSize);
    tbb::enumerable_thread_specific<PassCounters> counters;
    tbb::enumerable_thread_specific<Scratch> scratch;
    const Accel &accel = *scene.accel;
    const CameraSampler camera(scene, scene.sampler);
    const uint32_t spp = camera.Spp();
    ForEachTile(0, grid.NumTiles(), [&](int t) {
        PassCounters &pc = counters.local();
        Scratch &sc = scratch.local();
        const Bounds2i tb = grid.TilePixels(t);
        sc.rays.clear();
        sc.packets.clear();
        // The render loop's order (render/kernel_impl.h): blocks of RenderPacketW x
        // RenderPacketH pixels, one packet per sample index, so Packet16 traces the render's
        // own camera packets.
        for (int by = tb.pMin.y; by < tb.pMax.y; by += RenderPacketH) {
            for (int bx = tb.pMin.x; bx < tb.pMax.x; bx += RenderPacketW) {
                const int ex = std::min(bx + RenderPacketW, tb.pMax.x),
                          ey = std::min(by + RenderPacketH, tb.pMax.y);
                CameraSampler::Seeds seeds[RenderPacketW * RenderPacketH];
                int m = 0;
                for (int y = by; y < ey; ++y)
                    for (int x = bx; x < ex; ++x) seeds[m++] = camera.PixelSeeds(x, y);
                for (uint32_t s = 0; s < spp; ++s) {
                    const size_t first = sc.rays.size();
                    m = 0;
                    for (int y = by; y < ey; ++y)
                        for (int x = bx; x < ex; ++x)
                            sc.rays.push_back(
                                camera.GenerateRay(camera.Sample(x, y, s, seeds[m++])));
                    sc.packets.push_back(int(sc.rays.size() - first));
                }
            }
        }
        const size_t n = sc.rays.size();
        pc.camera += n;
        if (traversal == CeilingTraversal::Packet16) {
            sc.hits.resize(n);
            // Each packet's shadow rays right after it, as the render shades a packet.
            size_t first = 0;
            for (int m : sc.packets) {
                accel.IntersectCameraPacket(&sc.rays[first], m, &sc.hits[first]);
                for (size_t i = first; i < first + size_t(m); ++i) {
                    if (sc.hits[i].shape < 0) continue;
                    pc.hits++;
                    TraceShadowRays(scene, sc.rays[i], sc.hits[i].t, pc);
                }
                first += size_t(m);
            }
        } else {
            for (size_t i = 0; i < n; ++i) {
                RawHit hit;
                if (!accel.IntersectRaw(sc.rays[i], &hit)) continue;
                pc.hits++;
                TraceShadowRays(scene, sc.rays[i], hit.t, pc);
            }
        }
    });
    PassCounters total;
    for (const PassCounters &c : counters) {
        total.camera += c.camera;
        total.hits += c.hits;
        total.shadow += c.shadow;
        total.occluded += c.occluded;
    }
    return total;
}

}  // namespace

double Median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

CeilingResult RunCeiling(const CeilingOptions &o, std::FILE *log) {
    std::unique_ptr<tbb::global_control> threadLimit;
    if (o.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    MemoryBudget budget;  // the default limit, for the scene and its render together
    BuildSettings ro;
    ro.spp = o.spp;
    ro.resolution = Vec2i(o.width, o.height);
    ro.budget = &budget;
    Diagnostics diag(false);
    LoadOptions loadOpts;
    loadOpts.budget = &budget;
    SceneDescription desc = LoadScene(o.scene, diag, loadOpts);
    RenderScene scene = BuildRenderScene(desc, ro, diag);

    CeilingResult res;
    res.width = scene.pixelBounds.pMax.x - scene.pixelBounds.pMin.x;
    res.height = scene.pixelBounds.pMax.y - scene.pixelBounds.pMin.y;
    res.spp = scene.sampler.spp;
    res.threads =
        int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    res.triangles = scene.features.triangles;
    if (log)
        std::fprintf(
            log, "%s: %dx%d, %d spp, %d threads, %zu triangles, %zu lights, %s\n", o.scene.c_str(),
            res.width, res.height, res.spp, res.threads, res.triangles, scene.lights.size(),
            o.traversal == CeilingTraversal::Packet16
                ? "ceiling: camera rays in the render's 4x4-pixel packets, shadow rays rtcOccluded1"
                : "ceiling: rtcIntersect1 + rtcOccluded1 per ray");
    std::vector<double> ceil, rend;
    for (int k = 0; k < std::max(1, o.repeats); ++k) {
        CeilingRepeat rep;
        RenderStats stats;
        Render(scene, &stats);
        rep.renderSeconds = stats.renderSeconds;
        rep.renderRays = stats.rays.Total();

        auto t0 = std::chrono::steady_clock::now();
        PassCounters pc = TraceCeiling(scene, o.traversal);
        rep.ceilingSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        rep.ceilingRays = pc.camera + pc.shadow;
        res.hitFraction = pc.camera ? double(pc.hits) / double(pc.camera) : 0;
        if (log)
            std::fprintf(log,
                         "repeat %d: ceiling %.2f Mrays/s (%llu rays, %.3f s, %.0f%% hit), "
                         "render %.2f Mrays/s (%llu rays, %.3f s)\n",
                         k + 1, rep.CeilingMrays(), (unsigned long long)rep.ceilingRays,
                         rep.ceilingSeconds, 100 * res.hitFraction, rep.RenderMrays(),
                         (unsigned long long)rep.renderRays, rep.renderSeconds);
        ceil.push_back(rep.CeilingMrays());
        rend.push_back(rep.RenderMrays());
        res.repeats.push_back(rep);
    }
    res.ceilingMrays = Median(ceil);
    res.renderMrays = Median(rend);
    return res;
}

std::string CeilingSummary(const CeilingResult &r) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "ceiling %.2f Mrays/s, render %.2f Mrays/s, ratio %.2f",
                  r.ceilingMrays, r.renderMrays, r.Ratio());
    return buf;
}

}  // namespace prism
