// The bidirectional integrator's subpaths: the camera's and the light's random walks
// (render/bdpt_vertex.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "render/area_light.h"
#include "render/bdpt_vertex.h"
#include "render/differentials.h"
#include "render/medium_tracking.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

uint32_t BdptCameraDim(int vertex, uint32_t d) { return 16 + uint32_t(vertex) * 8 + d; }
uint32_t BdptLightDim(int vertex, uint32_t d) { return (1u << 16) + uint32_t(vertex) * 8 + d; }

uint64_t SampleSeed(const BdptSamples &ps, uint32_t dim, uint32_t salt) {
    const float u = ps.Get1D(dim);
    uint32_t bits;
    std::memcpy(&bits, &u, sizeof bits);
    return MixBits64(uint64_t(bits) << 32 | salt);
}

int MediumToward(const RenderScene &scene, const BdptVertex &v, const Vec3f &w) {
    if (v.type == BdptVertexType::Surface) return MediumAfter(*v.shape, v.si, w, v.medium);
    if (v.type == BdptVertexType::Light && !v.infinite) return scene.LightMedium(v.light, v.ng, w);
    return v.medium;
}

// The density pdf of a direction leaving `from` as a density per unit area at `to` (per unit
// solid angle when `to` is at infinity). From an infinite light, pdf is the density per unit
// area of its disk, which parallel rays carry onto `to` by the cosine alone.
float AreaDensity(float pdf, const BdptVertex &from, const BdptVertex &to) {
    if (to.infinite) return pdf;
    if (from.infinite) return pdf * (to.ng == Vec3f(0, 0, 0) ? 1.f : AbsDot(to.ng, from.wo));
    const Vec3f w = to.p - from.p;
    const float d2 = LengthSquared(w);
    if (!(d2 > 0)) return 0;
    const float c = to.ng == Vec3f(0, 0, 0) ? 1.f : AbsDot(to.ng, w) / std::sqrt(d2);
    return pdf * c / d2;
}

// Light paths carry importance: with shading normals the adjoint BSDF needs this factor
// (Veach 5.3.2), pbrt-v3's CorrectShadingNormal.
float ShadingCorrection(const BdptVertex &v, const Vec3f &wo, const Vec3f &wi) {
    const float den = AbsDot(wo, v.ng) * AbsDot(wi, v.ns);
    if (!(den > 0)) return 0;
    return AbsDot(wo, v.ns) * AbsDot(wi, v.ng) / den;
}

namespace {

bool HasInfiniteLight(const RenderScene &scene) {
    for (const auto &l : scene.lights)
        if (l->IsInfinite() && !l->IsDelta()) return true;
    return false;
}

// Dimension d of vertex `vertex` of a light (importance) or camera subpath.
uint32_t SubpathDim(bool importance, int vertex, uint32_t d) {
    return importance ? BdptLightDim(vertex, d) : BdptCameraDim(vertex, d);
}

// The random numbers of the medium sampling of the segment leaving vertex `vertex` of a
// subpath: the first two from the path's samples, the rest from a stream a third one seeds.
MediumSampler SegmentSampler(const BdptSamples &ps, bool importance, int vertex) {
    return MediumSampler(SampleSeed(ps, SubpathDim(importance, vertex, 5), 0),
                         ps.Get2D(SubpathDim(importance, vertex, 4)));
}

// Follows `ray`, in `medium`, from path.back() for at most `vertices` more surface or medium
// vertices, each sampling its BSDF or phase function for the next (importance: the adjoint
// BSDF, for light paths). pdfDir: the density of ray's direction at path.back(). Camera paths
// that escape end at the infinite lights.
void Walk(const BdptContext &ctx, Ray ray, int medium, RGB beta, float pdfDir, bool importance,
          int vertices, const BdptSamples &ps, const RayDifferential *diff,
          std::vector<BdptVertex> &path, RayCounters &rc) {
    const RenderScene &scene = ctx.scene;
    int passes = 0, made = 0;
    bool anyNonSpecular = false;  // for regularize
    Vec3f from = path.back().p;   // where the current medium segment begins
    // The medium sampling of the segments from path.back() (more than one when the ray
    // crosses boundaries): one stream, made when a medium first needs it.
    std::optional<MediumSampler> sampler;
    while (made < vertices) {
        SurfaceInteraction si;
        const bool found = scene.accel->Intersect(ray, &si, importance ? ShadowRays : CameraRays);
        const size_t i = path.size();
        const int vertex = int(i);
        auto dim = [&](uint32_t d) { return SubpathDim(importance, vertex, d); };
        if (medium >= 0) {
            // The medium up to the hit: a scattering point, or the transmittance to the hit.
            if (!sampler) sampler = SegmentSampler(ps, importance, vertex - 1);
            MediumInteraction mi;
            bool scattered = false;
            const Medium &m = *scene.media[size_t(medium)];
            beta *= m.Sample(MediumSegment(ray, from, found ? &si.p : nullptr), *sampler, &mi,
                             &scattered);
            if (beta.IsBlack() || !beta.IsFinite()) return;
            if (scattered) {
                passes = 0;
                BdptVertex &v = path.emplace_back();
                v.type = BdptVertexType::Medium;
                v.p = mi.p;
                v.si.p = mi.p;
                v.si.time = ray.time;
                v.wo = -Normalize(ray.d);
                v.beta = beta;
                v.medium = medium;
                v.phase = &m.Phase();
                v.pdfFwd = AreaDensity(pdfDir, path[i - 1], v);
                if (++made >= vertices) return;
                Vec3f wi;
                const float pdf = m.Phase().Sample_p(v.wo, &wi, ps.Get2D(dim(0)));
                if (!(pdf > 0)) return;
                pdfDir = pdf;  // the phase function is its own density: beta is unchanged
                path[i - 1].pdfRev = AreaDensity(pdf, v, path[i - 1]);
                anyNonSpecular = true;
                rc.reflection++;
                ray = v.si.SpawnRay(wi, scene.offset);
                from = v.p;
                sampler.reset();
                continue;
            }
        }
        if (!found) {
            if (!importance && HasInfiniteLight(scene)) {
                BdptVertex &v = path.emplace_back();
                v.type = BdptVertexType::Light;
                v.infinite = true;
                // Toward the light, as a light vertex at infinity keeps it.
                v.wo = Normalize(ray.d);
                v.beta = beta;
                v.pdfFwd = pdfDir;
                v.medium = medium;
            }
            return;
        }
        const ShapeInfo &info = scene.Info(si);
        const Material &mat = scene.materials[size_t(info.material)];
        if (mat.IsPassThrough()) {
            // pbrt: a surface without a BSDF continues the ray without counting a bounce.
            if (++passes > MaxPassThrough) return;
            medium = MediumAfter(info, si, ray.d, medium);
            ray = si.SpawnRay(ray.d, scene.offset);
            from = si.p;
            rc.passThrough++;
            continue;
        }
        const bool cameraHit = passes == 0 && made == 0 && diff;
        passes = 0;
        BdptVertex &v = path.emplace_back();
        v.type = BdptVertexType::Surface;
        v.si = si;
        if (mat.PerturbsShading()) mat.PerturbShading(v.si);
        v.p = si.p;
        v.ng = si.n;
        v.ns = v.si.ns;
        v.wo = -ray.d;
        v.beta = beta;
        v.light = info.areaLight;
        v.medium = medium;
        v.shape = &info;
        TextureContext tc = SurfaceTextureContext(si);
        if (cameraHit) ComputeDifferentials(si, *diff, &tc);
        if (!importance && mat.HasEmission()) v.emitted = mat.Emitted(tc);
        v.bsdf.emplace(mat.GetBSDF(v.si, tc));
        if (ctx.regularize && anyNonSpecular) v.bsdf->Regularize();
        v.bsdf->MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
        v.pdfFwd = AreaDensity(pdfDir, path[i - 1], v);
        if (++made >= vertices) return;
        // The next direction.
        BSDFSample bs;
        if (!v.bsdf->Sample_f(v.wo, ps.Get2D(dim(0)), ps.Get1D(dim(1)), true, &bs)) return;
        RGB w = bs.weight;
        anyNonSpecular = anyNonSpecular || !bs.specular;
        float pdfRev = 0;
        if (bs.specular) {
            // Delta lobes: radiance is scaled by 1/eta^2 through a refraction, importance not.
            if (importance && bs.transmission && bs.eta != 1) w *= bs.eta * bs.eta;
            v.delta = true;
            pdfDir = 0;
        } else {
            if (importance)
                w = v.bsdf->f(bs.wi, v.wo) * (AbsDot(bs.wi, v.ns) / bs.pdf) *
                    ShadingCorrection(v, v.wo, bs.wi);
            pdfDir = bs.pdf;
            pdfRev = v.bsdf->Pdf(bs.wi, v.wo, true);
        }
        path[i - 1].pdfRev = AreaDensity(pdfRev, v, path[i - 1]);
        if (bs.transmission)
            rc.refraction++;
        else
            rc.reflection++;
        beta = beta * w;
        if (beta.IsBlack() || !beta.IsFinite()) return;
        medium = MediumAfter(info, v.si, bs.wi, medium);
        ray = v.si.SpawnRay(bs.wi, scene.offset);
        from = v.p;
        sampler.reset();
    }
}

}  // namespace

void CameraSubpath(const BdptContext &ctx, const Ray &ray, const BdptSamples &ps,
                   const RayDifferential *diff, std::vector<BdptVertex> &path, RayCounters &rc) {
    path.clear();
    BdptVertex &z0 = path.emplace_back();
    z0.type = BdptVertexType::Camera;
    z0.p = ray.o;
    z0.beta = RGB(1);
    z0.pdfFwd = 1;
    float pdfPos, pdfDir;
    ctx.camera.Pdf(ray.d, &pdfPos, &pdfDir);
    z0.medium = ctx.scene.cameraMedium;
    Walk(ctx, ray, z0.medium, RGB(1), pdfDir, false, ctx.maxDepth + 1, ps, diff, path, rc);
}

void LightSubpath(const BdptContext &ctx, const BdptSamples &ps, std::vector<BdptVertex> &path,
                  RayCounters &rc) {
    path.clear();
    const RenderScene &scene = ctx.scene;
    float prob = 0;
    const int l = ctx.chooser.Choose(ps.Get1D(BdptLightDim(0, 0)), &prob);
    if (l < 0 || !(prob > 0)) return;
    const Light &light = *scene.lights[size_t(l)];
    LightLeSample ls;
    if (!light.SampleLe(ps.Get2D(BdptLightDim(0, 1)), ps.Get2D(BdptLightDim(0, 2)), ctx.sphere,
                        &ls) ||
        !(ls.pdfPos > 0) || !(ls.pdfDir > 0) || ls.Le.IsBlack())
        return;
    BdptVertex &y0 = path.emplace_back();
    y0.type = BdptVertexType::Light;
    y0.light = l;
    y0.infinite = light.IsInfinite();
    y0.p = ls.ray.o;
    y0.ng = ls.n;
    y0.wo = -ls.ray.d;  // at infinity: the direction toward the light
    // A point to spawn rays from: area lights offset along their normal.
    y0.si.p = ls.ray.o;
    y0.si.n = ls.n;
    y0.si.ns = ls.n;
    const Vec3f ap(std::abs(y0.p.x), std::abs(y0.p.y), std::abs(y0.p.z));
    y0.si.pError = ls.n == Vec3f(0, 0, 0) ? Vec3f(0, 0, 0) : (ap + Vec3f(1, 1, 1)) * 0x1p-18f;
    // The origin's density: per unit area, or per unit solid angle at infinity.
    const float pdfOrigin = y0.infinite ? ls.pdfDir : ls.pdfPos;
    y0.pdfFwd = prob * pdfOrigin;
    y0.beta = ls.Le / (prob * pdfOrigin);
    const float cosLight = ls.n == Vec3f(0, 0, 0) ? 1.f : AbsDot(ls.n, ls.ray.d);
    RGB beta = ls.Le * (cosLight / (prob * ls.pdfPos * ls.pdfDir));
    // The medium the emitted ray begins in. Light from infinitely far has crossed the medium
    // around the scene on its way to the disk it starts from: none of it when that medium is
    // unbounded and absorbs (as the camera paths escaping into it see), all of it when the
    // medium is empty out there (a grid's box).
    if (y0.infinite) {
        y0.medium = ctx.infinityMedium;
        if (y0.medium >= 0) {
            MediumSampler sampler(SampleSeed(ps, BdptLightDim(0, 7), 0));
            beta *= scene.media[size_t(y0.medium)]->Tr(Ray{ls.ray.o, -ls.ray.d}, sampler);
        }
    } else {
        y0.medium = scene.LightMedium(l, ls.n, ls.ray.d);
    }
    if (beta.IsBlack() || !beta.IsFinite()) return;
    // Point and spot lights (no normal) keep their ray as drawn, with its tMin.
    const Ray ray =
        y0.infinite || ls.n == Vec3f(0, 0, 0) ? ls.ray : y0.si.SpawnRay(ls.ray.d, scene.offset);
    rc.shadow++;  // light rays are counted with the shadow rays
    // The next vertex's density: the direction's, or the disk's at infinity.
    Walk(ctx, ray, y0.medium, beta, y0.infinite ? ls.pdfPos : ls.pdfDir, true, ctx.maxDepth, ps,
         nullptr, path, rc);
}

}  // namespace prism
