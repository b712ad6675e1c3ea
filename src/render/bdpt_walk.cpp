// The bidirectional integrator's subpaths: the camera's and the light's random walks
// (render/bdpt_vertex.h).
#include <algorithm>
#include <cmath>

#include "render/area_light.h"
#include "render/bdpt_vertex.h"
#include "render/differentials.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

uint32_t BdptCameraDim(int vertex, uint32_t d) { return 16 + uint32_t(vertex) * 8 + d; }
uint32_t BdptLightDim(int vertex, uint32_t d) { return (1u << 16) + uint32_t(vertex) * 8 + d; }

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

// Follows `ray` from path.back() for at most `surfaces` more surface vertices, each sampling
// its BSDF for the next (importance: the adjoint BSDF, for light paths). pdfDir: the density
// of ray's direction at path.back(). Camera paths that escape end at the infinite lights.
void Walk(const BdptContext &ctx, Ray ray, RGB beta, float pdfDir, bool importance, int surfaces,
          const BdptSamples &ps, const RayDifferential *diff, std::vector<BdptVertex> &path,
          RayCounters &rc) {
    const RenderScene &scene = ctx.scene;
    int passes = 0, made = 0;
    bool anyNonSpecular = false;  // for regularize
    while (made < surfaces) {
        SurfaceInteraction si;
        if (!scene.accel->Intersect(ray, &si, importance ? ShadowRays : CameraRays)) {
            if (!importance && HasInfiniteLight(scene)) {
                BdptVertex &v = path.emplace_back();
                v.type = BdptVertexType::Light;
                v.infinite = true;
                v.wo = ray.d;  // toward the light, as a light vertex at infinity keeps it
                v.beta = beta;
                v.pdfFwd = pdfDir;
            }
            return;
        }
        const ShapeInfo &info = scene.Info(si);
        const Material &mat = scene.materials[size_t(info.material)];
        if (mat.IsPassThrough()) {
            // pbrt: a surface without a BSDF continues the ray without counting a bounce.
            if (++passes > MaxPassThrough) return;
            ray = si.SpawnRay(ray.d, scene.offset);
            rc.passThrough++;
            continue;
        }
        const bool cameraHit = passes == 0 && made == 0 && diff;
        passes = 0;
        const size_t i = path.size();
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
        TextureContext tc = SurfaceTextureContext(si);
        if (cameraHit) ComputeDifferentials(si, *diff, &tc);
        if (!importance && mat.HasEmission()) v.emitted = mat.Emitted(tc);
        v.bsdf.emplace(mat.GetBSDF(v.si, tc));
        if (ctx.regularize && anyNonSpecular) v.bsdf->Regularize();
        v.bsdf->MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
        v.pdfFwd = AreaDensity(pdfDir, path[i - 1], v);
        if (++made >= surfaces) return;
        // The next direction.
        const int vertex = int(i);
        const uint32_t d0 = importance ? BdptLightDim(vertex, 0) : BdptCameraDim(vertex, 0);
        const uint32_t d1 = importance ? BdptLightDim(vertex, 1) : BdptCameraDim(vertex, 1);
        BSDFSample bs;
        if (!v.bsdf->Sample_f(v.wo, ps.Get2D(d0), ps.Get1D(d1), true, &bs)) return;
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
        ray = v.si.SpawnRay(bs.wi, scene.offset);
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
    Walk(ctx, ray, RGB(1), pdfDir, false, ctx.maxDepth + 1, ps, diff, path, rc);
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
    const RGB beta = ls.Le * (cosLight / (prob * ls.pdfPos * ls.pdfDir));
    if (beta.IsBlack() || !beta.IsFinite()) return;
    // Point and spot lights (no normal) keep their ray as drawn, with its tMin.
    const Ray ray =
        y0.infinite || ls.n == Vec3f(0, 0, 0) ? ls.ray : y0.si.SpawnRay(ls.ray.d, scene.offset);
    rc.shadow++;  // light rays are counted with the shadow rays
    // The next vertex's density: the direction's, or the disk's at infinity.
    Walk(ctx, ray, beta, y0.infinite ? ls.pdfPos : ls.pdfDir, true, ctx.maxDepth, ps, nullptr, path,
         rc);
}

}  // namespace prism
