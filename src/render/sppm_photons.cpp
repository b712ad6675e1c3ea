// sppm's visible-point grid and photon pass (pbrt-v3 SPPMIntegrator::Render, "trace photons and
// accumulate contributions"): photons leave the lights (chosen by power, pbrt-v3's
// Light::Sample_Le), bounce by their BSDF's adjoint with pbrt-v3's Russian roulette, and from
// their second surface on deposit into every visible point within its pixel's radius. Chunks of
// photons sum their deposits apart and are merged in chunk order: the same sums for any thread
// count.
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rng.h"
#include "render/light.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/sppm_integrator.h"

namespace prism {

void SppmGrid::Build(const std::vector<SppmVisiblePoint> &points,
                     const std::vector<SppmPixel> &pixels) {
    start_.clear();
    entries_.clear();
    // The bounds of every visible point's sphere, and the largest radius.
    constexpr float Inf = std::numeric_limits<float>::infinity();
    lo_ = Vec3f(Inf, Inf, Inf);
    hi_ = Vec3f(-Inf, -Inf, -Inf);
    float maxRadius = 0;
    size_t n = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        if (points[i].beta.IsBlack()) continue;
        const float r = pixels[i].radius;
        const Vec3f &p = points[i].p;
        lo_ = Vec3f(std::min(lo_.x, p.x - r), std::min(lo_.y, p.y - r), std::min(lo_.z, p.z - r));
        hi_ = Vec3f(std::max(hi_.x, p.x + r), std::max(hi_.y, p.y + r), std::max(hi_.z, p.z + r));
        maxRadius = std::max(maxRadius, r);
        ++n;
    }
    if (n == 0 || !(maxRadius > 0)) return;
    // Cells about a diameter wide along the longest axis, proportionally fewer along the others.
    const Vec3f diag = hi_ - lo_;
    const float maxDiag = std::max({diag.x, diag.y, diag.z});
    const float base = maxDiag / (2 * maxRadius);
    const float extent[3] = {diag.x, diag.y, diag.z};
    for (int a = 0; a < 3; ++a) res_[a] = std::clamp(int(base * extent[a] / maxDiag), 1, 1 << 20);
    // Count, then fill, each point once per bucket its cells hash to (buckets as many as
    // points); points fill in index order, so a repeat in a bucket is its last entry.
    const size_t buckets = n;
    start_.assign(buckets + 1, 0);
    std::vector<uint32_t> last(buckets, std::numeric_limits<uint32_t>::max());
    const auto forEachBucket = [&](size_t i, auto &&add) {
        const float r = pixels[i].radius;
        const Vec3f &p = points[i].p;
        int c0[3], c1[3];
        Cell(p - Vec3f(r, r, r), c0);
        Cell(p + Vec3f(r, r, r), c1);
        for (int z = c0[2]; z <= c1[2]; ++z)
            for (int y = c0[1]; y <= c1[1]; ++y)
                for (int x = c0[0]; x <= c1[0]; ++x) {
                    const uint32_t b = Bucket(x, y, z);
                    if (last[b] == uint32_t(i)) continue;
                    last[b] = uint32_t(i);
                    add(b);
                }
    };
    for (size_t i = 0; i < points.size(); ++i)
        if (!points[i].beta.IsBlack()) forEachBucket(i, [&](uint32_t b) { ++start_[b + 1]; });
    for (size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    entries_.resize(start_[buckets]);
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    std::fill(last.begin(), last.end(), std::numeric_limits<uint32_t>::max());
    for (size_t i = 0; i < points.size(); ++i)
        if (!points[i].beta.IsBlack())
            forEachBucket(i, [&](uint32_t b) { entries_[fill[b]++] = uint32_t(i); });
}

bool SppmGrid::Cell(const Vec3f &p, int c[3]) const {
    const float v[3] = {p.x, p.y, p.z}, lo[3] = {lo_.x, lo_.y, lo_.z},
                hi[3] = {hi_.x, hi_.y, hi_.z};
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
        inside &= v[a] >= lo[a] && v[a] <= hi[a];
        const float t = (v[a] - lo[a]) / (hi[a] - lo[a]);
        // Clamped (NaN too) into the grid.
        c[a] = t > 0 ? std::min(int(t * float(res_[a])), res_[a] - 1) : 0;
    }
    return inside;
}

uint32_t SppmGrid::Bucket(int x, int y, int z) const {
    uint64_t h = uint64_t(uint32_t(x)) * 0x9e3779b97f4a7c15ull;
    h ^= uint64_t(uint32_t(y)) * 0xc2b2ae3d27d4eb4full;
    h ^= uint64_t(uint32_t(z)) * 0x165667b19e3779f9ull;
    h ^= h >> 31;
    return uint32_t(h % uint64_t(start_.size() - 1));
}

std::pair<const uint32_t *, const uint32_t *> SppmGrid::Candidates(const Vec3f &p) const {
    int c[3];
    if (start_.empty() || !Cell(p, c)) return {nullptr, nullptr};
    const uint32_t b = Bucket(c[0], c[1], c[2]);
    return {entries_.data() + start_[b], entries_.data() + start_[b + 1]};
}

uint64_t SppmGrid::Bytes() const {
    return (start_.capacity() + entries_.capacity()) * sizeof(uint32_t);
}

namespace {

// The deposits of one chunk of photons into one visible point.
struct Deposit {
    uint32_t point;
    uint32_t count;
    RGB phi;
};

// A worker's per-visible-point sums for the chunk it traces, and the points it touched.
struct ChunkSums {
    std::vector<RGB> phi;
    std::vector<uint32_t> count;
    std::vector<uint32_t> touched;
};

struct PhotonTracer {
    const RenderScene &scene;
    const LightChooser &chooser;
    const SceneSphere &sphere;
    const SppmPass &pass;
    const SppmGrid &grid;
    const std::vector<SppmPixel> &pixels;
    int maxDepth;

    void Deposit(const Vec3f &p, const Vec3f &wi, const RGB &beta, ChunkSums &sums) const {
        const auto [begin, end] = grid.Candidates(p);
        for (const uint32_t *e = begin; e != end; ++e) {
            const uint32_t j = *e;
            const float r = pixels[j].radius;
            if (LengthSquared(pass.points[j].p - p) > r * r) continue;
            if (sums.count[j]++ == 0) sums.touched.push_back(j);
            sums.phi[j] += beta * pass.f(j, wi);
        }
    }

    // Photon `index` of an iteration, its random numbers drawn from rng alone.
    void Trace(PCG32 &rng, ChunkSums &sums, RayCounters &rc) const {
        float prob;
        const int li = chooser.Choose(rng.Uniform(), &prob);
        if (li < 0 || !(prob > 0)) return;
        const Vec2f uPos(rng.Uniform(), rng.Uniform()), uDir(rng.Uniform(), rng.Uniform());
        LightLeSample ls;
        if (!scene.lights[size_t(li)]->SampleLe(uPos, uDir, sphere, &ls)) return;
        if (!(ls.pdfPos > 0) || !(ls.pdfDir > 0) || ls.Le.IsBlack()) return;
        const bool hasNormal = ls.n.x != 0 || ls.n.y != 0 || ls.n.z != 0;
        const float cosLight = hasNormal ? AbsDot(ls.n, ls.ray.d) : 1.f;
        RGB beta = ls.Le * (cosLight / (prob * ls.pdfPos * ls.pdfDir));
        if (beta.IsBlack() || !beta.IsFinite()) return;
        Ray ray = ls.ray;
        int passes = 0;
        for (int depth = 0; depth < maxDepth; ++depth) {
            SurfaceInteraction si;
            if (!scene.accel->Intersect(ray, &si, ShadowRays)) break;
            const Material &mat = scene.materials[size_t(scene.Info(si).material)];
            if (mat.IsPassThrough()) {
                if (++passes > MaxPassThrough) break;
                ray = si.SpawnRay(ray.d, scene.offset);
                rc.passThrough++;
                --depth;
                continue;
            }
            passes = 0;
            // The first surface's light is the camera pass's direct lighting.
            if (depth > 0) Deposit(si.p, si.wo, beta, sums);
            if (mat.PerturbsShading()) mat.PerturbShading(si);
            const TextureContext tc = SurfaceTextureContext(si);
            BSDF bsdf = mat.GetBSDF(si, tc);
            bsdf.MakeRoughSpecularGlossy();
            BSDFSample bs;
            const Vec2f u(rng.Uniform(), rng.Uniform());
            const float uc = rng.Uniform();
            if (!bsdf.Sample_f(si.wo, u, uc, true, &bs)) break;
            // Photons carry importance: the adjoint BSDF, f(wi, wo), which for delta
            // refraction is radiance's without its 1/eta^2 scaling (pbrt-v3
            // TransportMode::Importance).
            RGB w = bs.weight;
            if (bs.specular) {
                if (bs.transmission && bs.eta != 1) w *= bs.eta * bs.eta;
            } else {
                w = bsdf.f(bs.wi, si.wo) * (AbsDot(bs.wi, bsdf.ns) / bs.pdf);
            }
            const RGB next = beta * w;
            // pbrt-v3's roulette: survive with the ratio of the new throughput to the old.
            const float old = beta.Luminance();
            if (!(old > 0)) break;
            const float q = std::max(0.f, 1 - next.Luminance() / old);
            if (rng.Uniform() < q) break;
            beta = next / (1 - q);
            if (beta.IsBlack() || !beta.IsFinite()) break;
            if (bs.transmission)
                rc.refraction++;
            else
                rc.reflection++;
            ray = si.SpawnRay(bs.wi, scene.offset);
        }
    }
};

}  // namespace

void SppmIntegrator::PhotonPass(const FrameContext &frame, int iter, int64_t photons,
                                const SppmPass &pass, const SppmGrid &grid,
                                std::vector<SppmPixel> &pixels) const {
    const RenderScene &scene = frame.scene;
    const SceneSphere sphere = BoundingSphere(scene);
    const PhotonTracer tracer{scene, power_, sphere, pass, grid, pixels, frame.trace.maxDepth};
    const size_t nPoints = pass.points.size();
    tbb::enumerable_thread_specific<ChunkSums> scratch;
    const int64_t nChunks = (photons + SppmPhotonChunk - 1) / SppmPhotonChunk;
    // Photon i of iteration k: a stream of its own, a function of (k, i) and the render's seed.
    const uint64_t iterKey = MixBits64((uint64_t(frame.sampler.seed) << 32) ^ uint64_t(iter));
    std::vector<std::vector<Deposit>> out(static_cast<size_t>(SppmChunksInFlight));
    for (int64_t first = 0; first < nChunks; first += SppmChunksInFlight) {
        const int64_t last = std::min(nChunks, first + SppmChunksInFlight);
        frame.ForEach(0, int(last - first), [&](int k, RayCounters &rc) {
            ChunkSums &sums = scratch.local();
            if (sums.phi.size() != nPoints) {
                sums.phi.assign(nPoints, RGB(0));
                sums.count.assign(nPoints, 0);
            }
            const int64_t chunk = first + k;
            const int64_t begin = chunk * SppmPhotonChunk;
            const int64_t end = std::min(photons, begin + SppmPhotonChunk);
            for (int64_t i = begin; i < end; ++i) {
                PCG32 rng(MixBits64(uint64_t(i) ^ iterKey), iterKey);
                tracer.Trace(rng, sums, rc);
            }
            std::vector<Deposit> &list = out[size_t(k)];
            list.clear();
            for (uint32_t j : sums.touched) {
                list.push_back({j, sums.count[j], sums.phi[j]});
                sums.phi[j] = RGB(0);
                sums.count[j] = 0;
            }
            sums.touched.clear();
        });
        if (frame.Cancelled()) return;
        // In chunk order: the sums do not depend on which worker traced which chunk.
        for (int64_t k = 0; k < last - first; ++k)
            for (const Deposit &d : out[size_t(k)]) {
                pixels[d.point].phi += d.phi;
                pixels[d.point].M += d.count;
            }
        frame.SetProgress((iter + 0.3 + 0.7 * double(last) / double(nChunks)) / params_.iterations);
    }
}

}  // namespace prism
