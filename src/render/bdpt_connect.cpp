// Strategy (s, t) of the bidirectional integrator: the connection of a light subpath's first s
// vertices with a camera subpath's first t, and its multiple importance sampling weight
// (render/bdpt_vertex.h).
#include <cmath>
#include <vector>

#include "render/area_light.h"
#include "render/bdpt_vertex.h"
#include "render/medium_tracking.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

float AreaDensity(float pdf, const BdptVertex &from, const BdptVertex &to);
float ShadingCorrection(const BdptVertex &v, const Vec3f &wo, const Vec3f &wi);

namespace {

// The unit direction from `from` to `to` (at infinity: the direction light travels, or the one
// toward the light).
Vec3f Direction(const BdptVertex &from, const BdptVertex &to) {
    if (from.infinite) return -from.wo;
    if (to.infinite) return to.wo;
    return Normalize(to.p - from.p);
}

// f at surface or medium vertex v toward wi: the BSDF for radiance (camera paths), its adjoint
// with the shading-normal correction for importance (light paths); in a medium the phase
// function, its own adjoint.
RGB VertexF(const BdptVertex &v, const Vec3f &wi, bool importance) {
    if (v.type == BdptVertexType::Medium) return RGB(v.phase->p(v.wo, wi));
    if (importance) return v.bsdf->f(wi, v.wo) * ShadingCorrection(v, v.wo, wi);
    return v.bsdf->f(v.wo, wi);
}

// The density with which surface or medium vertex v scatters toward `to` when it was reached
// from `from`, per unit area at `to`.
float ScatterDensity(const BdptVertex &v, const BdptVertex &from, const BdptVertex &to) {
    const Vec3f wo = Direction(v, from), wi = Direction(v, to);
    const float pdf =
        v.type == BdptVertexType::Medium ? v.phase->p(wo, wi) : v.bsdf->Pdf(wo, wi, true);
    return AreaDensity(pdf, v, to);
}

// The light of light vertex (or emitting surface) v and the densities with which the light
// subpaths start there: the origin's (area, or direction at infinity, times the light choice)
// and the next vertex's, `next`.
struct LightDensities {
    float origin = 0, next = 0;
};
LightDensities EmitterDensities(const BdptContext &ctx, const BdptVertex &v, int light,
                                const BdptVertex *next) {
    const Light &l = *ctx.scene.lights[size_t(light)];
    const float prob = ctx.chooser.Prob(light);
    LightDensities d;
    const Vec3f w = next ? Direction(v, *next) : -v.wo;
    float pdfPos = 0, pdfDir = 0;
    l.PdfLe(v.p, v.ng, w, ctx.sphere, &pdfPos, &pdfDir);
    if (l.IsArea()) pdfPos = static_cast<const DiffuseAreaLight &>(l).PdfPosition(v.ng, v.si.prim);
    d.origin = prob * (v.infinite ? pdfDir : pdfPos);
    if (next) d.next = AreaDensity(v.infinite ? pdfPos : pdfDir, v, *next);
    return d;
}

// The densities of every vertex of the path of strategy (s, t), light end first.
struct PathDensities {
    std::vector<float> light, camera;  // pl[i], pc[i]
    std::vector<uint8_t> delta;
};

float Remap0(float f) { return f != 0 ? f : 1.f; }

// Veach's MIS weight of strategy (s, t) by the balance heuristic (as pbrt-v3's bdpt) over every
// strategy that could make the same path: the ratio of the densities of neighbouring
// strategies is the light over the camera density of the vertex that changes sides. lightDelta:
// the light cannot be hit (point, spot, distant); lightArea: it can be seen by the camera
// through light tracing (strategy s = 1, t = 1).
float MisWeight(const PathDensities &d, int s, int n, bool lightDelta, bool lightArea) {
    auto allowed = [&](int k) {
        if (k == 0) return !lightDelta && !d.delta[0];
        if (k == 1 && n == 2) return lightArea;
        return !d.delta[size_t(k - 1)] && !d.delta[size_t(k)];
    };
    float sum = 1, r = 1;
    for (int k = s + 1; k <= n - 1; ++k) {
        r *= Remap0(d.light[size_t(k - 1)]) / Remap0(d.camera[size_t(k - 1)]);
        if (allowed(k)) sum += r;
    }
    r = 1;
    for (int k = s - 1; k >= 0; --k) {
        r *= Remap0(d.camera[size_t(k)]) / Remap0(d.light[size_t(k)]);
        if (allowed(k)) sum += r;
    }
    return std::isfinite(sum) ? 1 / sum : 0.f;
}

// Fills d for strategy (s, t) with the connection's own densities; lightV and cameraV are the
// path's vertices at the light end (x_{s-1}) and the camera end (x_s) of the connection, which
// may be the sampled ones (s = 1, t = 1); light: the light of the path.
void FillDensities(const BdptContext &ctx, const std::vector<BdptVertex> &lightPath,
                   const std::vector<BdptVertex> &cameraPath, int s, int t,
                   const BdptVertex *lightV, const BdptVertex *cameraV, int light,
                   PathDensities &d) {
    const size_t n = size_t(s + t);
    d.light.resize(n), d.camera.resize(n), d.delta.resize(n);
    for (int i = 0; i < s; ++i) {
        const BdptVertex &v = i == s - 1 ? *lightV : lightPath[size_t(i)];
        d.light[size_t(i)] = v.pdfFwd, d.camera[size_t(i)] = v.pdfRev;
        d.delta[size_t(i)] = v.delta;
    }
    for (int j = 0; j < t; ++j) {
        const BdptVertex &v = j == t - 1 ? *cameraV : cameraPath[size_t(j)];
        const size_t i = size_t(s + t - 1 - j);
        d.light[i] = v.pdfRev, d.camera[i] = v.pdfFwd, d.delta[i] = v.delta;
    }
    const BdptVertex &pt = *cameraV;
    const BdptVertex *ptMinus = t >= 2 ? &cameraPath[size_t(t - 2)] : nullptr;
    if (s > 0) d.delta[size_t(s - 1)] = false;
    d.delta[size_t(s)] = false;
    if (s == 0) {
        // The camera path's last vertex is the emitter.
        const LightDensities e = EmitterDensities(ctx, pt, light, ptMinus);
        d.light[0] = e.origin;
        if (ptMinus) d.light[1] = e.next;
        return;
    }
    const BdptVertex &qs = *lightV;
    // The camera side's density of qs, and of the light vertex before it.
    if (t == 1) {
        float pdfPos, pdfDir;
        ctx.camera.Pdf(Direction(pt, qs), &pdfPos, &pdfDir);
        d.camera[size_t(s - 1)] = AreaDensity(pdfDir, pt, qs);
    } else {
        d.camera[size_t(s - 1)] = ScatterDensity(pt, *ptMinus, qs);
    }
    if (s >= 2) d.camera[size_t(s - 2)] = ScatterDensity(qs, pt, lightPath[size_t(s - 2)]);
    // The light side's density of pt, and of the camera vertex before it.
    if (s == 1)
        d.light[size_t(s)] = EmitterDensities(ctx, qs, light, &pt).next;
    else
        d.light[size_t(s)] = ScatterDensity(qs, lightPath[size_t(s - 2)], pt);
    if (ptMinus) d.light[size_t(s + 1)] = ScatterDensity(pt, qs, *ptMinus);
}

// The transmittance of the connection from `from` to `to`: 0 when a surface blocks it, else
// that of the media on the way (through invisible boundaries, as the walks pass them, and as
// pbrt-v3's bdpt connects through them with or without media). Grids' ratio tracking draws
// from a stream the camera vertex's sample `seedDim` and the strategy seed.
RGB Transmittance(const BdptContext &ctx, const BdptVertex &from, const BdptVertex &to,
                  const BdptSamples &ps, uint32_t seedDim, int s, RayCounters &rc) {
    const RenderScene &scene = ctx.scene;
    rc.shadow++;
    const Ray ray = to.infinite ? from.si.SpawnRay(to.wo, scene.offset)
                                : from.si.SpawnRayTo(to.p, scene.offset);
    if (scene.media.empty()) {
        // Without media or invisible surfaces, anything in the way blocks the connection.
        if (!scene.passThrough) return scene.accel->Occluded(ray) ? RGB(0) : RGB(1);
        MediumSampler unused(0);
        return ShadowTransmittance(scene, ray, -1, to.infinite, unused, rc);
    }
    MediumSampler sampler(SampleSeed(ps, seedDim, uint32_t(s)));
    return ShadowTransmittance(scene, ray, MediumToward(scene, from, ray.d), to.infinite, sampler,
                               rc);
}

thread_local PathDensities densities;

// s = 0: the camera path's last vertex, pt, emits (an area light, or infinite lights).
RGB HitEmitter(const BdptContext &ctx, const std::vector<BdptVertex> &camera, int t) {
    const BdptVertex &pt = camera[size_t(t - 1)];
    const RenderScene &scene = ctx.scene;
    RGB L;
    if (pt.infinite) {
        // Each infinite light is its own emitter, weighted with its own densities.
        const Ray ray{pt.p, pt.wo};
        for (size_t l = 0; l < scene.lights.size(); ++l) {
            const Light &light = *scene.lights[l];
            if (!light.IsInfinite() || light.IsDelta()) continue;
            const RGB Le = light.Le(ray);
            if (Le.IsBlack()) continue;
            FillDensities(ctx, {}, camera, 0, t, nullptr, &pt, int(l), densities);
            L += pt.beta * Le * MisWeight(densities, 0, t, false, false);
        }
        return L;
    }
    if (pt.type != BdptVertexType::Surface) return L;
    L = pt.beta * pt.emitted;  // emission no light samples: this is its only strategy
    if (pt.light < 0) return L;
    const auto &area = static_cast<const DiffuseAreaLight &>(*scene.lights[size_t(pt.light)]);
    const RGB Le = area.L(pt.si, pt.wo);
    if (Le.IsBlack()) return L;
    FillDensities(ctx, {}, camera, 0, t, nullptr, &pt, pt.light, densities);
    return L + pt.beta * Le * MisWeight(densities, 0, t, false, true);
}

}  // namespace

RGB ConnectStrategy(const BdptContext &ctx, const std::vector<BdptVertex> &light,
                    const std::vector<BdptVertex> &camera, int s, int t, const BdptSamples &ps,
                    Vec2f *raster, RayCounters &rc) {
    const RenderScene &scene = ctx.scene;
    if (s == 0) return HitEmitter(ctx, camera, t);
    const BdptVertex &pt0 = camera[size_t(t - 1)];
    // Next-event estimation (s = 1) samples a light of its own: it runs also when the light
    // subpath ended at once (a direction its light does not emit along, as a projection
    // light's outside its frustum), which pbrt-v3 skips, darkening such lights.
    if (s > int(light.size()) && !(s == 1 && t > 1)) return RGB(0);
    static const BdptVertex noVertex;
    const BdptVertex &qs0 = s <= int(light.size()) ? light[size_t(s - 1)] : noVertex;
    const int lightIndex = light.empty() ? -1 : light[0].light;
    RGB L;
    int l = lightIndex;
    BdptVertex sampled;  // the camera's lens point (t = 1) or the light's point (s = 1)
    const BdptVertex *lightV = &qs0, *cameraV = &pt0;
    if (t == 1) {
        // Light tracing: qs seen through a point on the lens, splatted where it lands.
        if (!qs0.Connectible()) return RGB(0);
        const Light &lt = *scene.lights[size_t(l)];
        if (s == 1 && (!lt.IsArea())) return RGB(0);  // delta and infinite lights: not seen
        CameraImportance::Sample cs;
        if (!ctx.camera.SampleWi(qs0.p, ps.Get2D(BdptLightDim(s - 1, 2)), &cs)) return RGB(0);
        const uint32_t seedDim = BdptLightDim(s - 1, 6);
        sampled.type = BdptVertexType::Camera;
        sampled.p = cs.pLens;
        sampled.beta = RGB(cs.we / cs.pdf);
        if (s == 1) {
            const auto &area = static_cast<const DiffuseAreaLight &>(lt);
            if (!area.TwoSided() && Dot(qs0.ng, cs.wi) <= 0) return RGB(0);
            L = qs0.beta * (AbsDot(qs0.ng, cs.wi) * cs.we / cs.pdf);
        } else {
            L = qs0.beta * VertexF(qs0, cs.wi, true) * (qs0.AbsCos(cs.wi) * cs.we / cs.pdf);
        }
        if (L.IsBlack()) return L;
        cameraV = &sampled;
        L *= Transmittance(ctx, qs0, sampled, ps, seedDim, s, rc);
        if (L.IsBlack()) return L;
        *raster = cs.raster;
    } else if (s == 1) {
        // A light sample seen from the camera path's pt (next-event estimation).
        if (!pt0.Connectible() || pt0.infinite) return RGB(0);
        float prob = 0;
        l = ctx.chooser.Choose(ps.Get1D(BdptCameraDim(t - 1, 2)), &prob);
        if (l < 0 || !(prob > 0)) return RGB(0);
        const Light &lt = *scene.lights[size_t(l)];
        const Vec2f u = ps.Get2D(BdptCameraDim(t - 1, 3));
        sampled.type = BdptVertexType::Light;
        sampled.light = l;
        sampled.infinite = lt.IsInfinite();
        RGB Li;
        Vec3f wi;
        float pdf;
        if (sampled.infinite && !lt.IsDelta()) {
            // The direction as the light emits it (SampleLe), so every direction that MIS
            // weighs is sampled.
            LightLeSample le;
            if (!lt.SampleLe(Vec2f(0.5f, 0.5f), u, ctx.sphere, &le)) return RGB(0);
            wi = -le.ray.d, Li = le.Le, pdf = le.pdfDir;
        } else {
            LightSample ls;
            if (!lt.SampleLi(pt0.si, u, &ls)) return RGB(0);
            wi = ls.wi, Li = ls.Li, pdf = ls.pdf;
            sampled.p = ls.pLight;
            sampled.ng = ls.n;
            sampled.si.prim = ls.prim;
        }
        if (!(pdf > 0) || Li.IsBlack()) return RGB(0);
        if (sampled.infinite) sampled.wo = wi;
        sampled.pdfFwd = EmitterDensities(ctx, sampled, l, nullptr).origin;
        L = pt0.beta * VertexF(pt0, wi, false) * Li * (pt0.AbsCos(wi) / (pdf * prob));
        if (L.IsBlack()) return L;
        lightV = &sampled;
        L *= Transmittance(ctx, pt0, sampled, ps, BdptCameraDim(t - 1, 6), s, rc);
        if (L.IsBlack()) return L;
    } else {
        // Two surface vertices joined by a shadow ray.
        if (!qs0.Connectible() || !pt0.Connectible() || pt0.infinite) return RGB(0);
        Vec3f d = qs0.p - pt0.p;
        const float d2 = LengthSquared(d);
        if (!(d2 > 0)) return RGB(0);
        d = d / std::sqrt(d2);
        const float G = pt0.AbsCos(d) * qs0.AbsCos(d) / d2;
        L = qs0.beta * VertexF(qs0, -d, true) * VertexF(pt0, d, false) * pt0.beta * G;
        if (L.IsBlack()) return L;
        L *= Transmittance(ctx, pt0, qs0, ps, BdptCameraDim(t - 1, 6), s, rc);
        if (L.IsBlack()) return L;
    }
    FillDensities(ctx, light, camera, s, t, lightV, cameraV, l, densities);
    const Light &lt = *scene.lights[size_t(l)];
    return L * MisWeight(densities, s, s + t, lt.IsDelta(), lt.IsArea());
}

}  // namespace prism
