// pbrt-v3 EstimateDirect, generic over what scatters at the vertex (a surface's BSDF or a
// medium's phase function) and how light reaches it (unoccluded or not, or through media and
// invisible boundaries with their transmittance): the path and directlighting integrators
// instantiate it with BsdfScatter and NoMediaVisibility (render/light_sampling.cpp, the same
// operations as before it was generic), volpath with MediaVisibility
// (render/volpath_integrator.cpp).
#pragma once

#include "render/area_light.h"
#include "render/bsdf.h"
#include "render/light.h"
#include "render/light_sampling.h"
#include "render/medium.h"
#include "render/medium_tracking.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

// A surface vertex: the BSDF's non-delta lobes times |cos θi|.
struct BsdfScatter {
    const BSDF &bsdf;
    RGB F(const Vec3f &wo, const Vec3f &wi) const { return bsdf.f(wo, wi) * AbsDot(wi, bsdf.ns); }
    float Pdf(const Vec3f &wo, const Vec3f &wi) const { return bsdf.Pdf(wo, wi); }
    bool Sample(const Vec3f &wo, Vec2f u, float uc, BSDFSample *bs) const {
        return bsdf.Sample_f(wo, u, uc, false, bs);
    }
};

// A medium vertex: the phase function, which samples itself exactly (weight 1).
struct PhaseScatter {
    const HenyeyGreenstein &phase;
    RGB F(const Vec3f &wo, const Vec3f &wi) const { return RGB(phase.p(wo, wi)); }
    float Pdf(const Vec3f &wo, const Vec3f &wi) const { return phase.p(wo, wi); }
    bool Sample(const Vec3f &wo, Vec2f u, float, BSDFSample *bs) const {
        const float p = phase.Sample_p(wo, &bs->wi, u);
        bs->f = RGB(p);
        bs->pdf = p;
        bs->weight = RGB(1);
        return p > 0;
    }
};

// Consecutive "none" surfaces a BSDF-sampled ray may cross on its way to a light.
inline constexpr int MaxLightRayCrossings = 256;

// Light without media: a shadow ray is blocked or not; a ray toward a light passes "none"
// surfaces.
struct NoMediaVisibility {
    static constexpr bool Media = false;
};

// Light through media: shadow rays and rays toward lights start in the medium on their side of
// the vertex (a surface's MediumInterface, or the medium a medium vertex lies in) and carry the
// transmittance of every medium they cross.
struct MediaVisibility {
    static constexpr bool Media = true;
    const RenderScene &scene;
    const ShapeInfo *shape;  // the surface of the vertex; null at a medium vertex
    int medium;              // the incident ray's medium
    MediumSampler &sampler;
    int Toward(const SurfaceInteraction &si, const Vec3f &w) const {
        return shape ? MediumAfter(*shape, si, w, medium) : medium;
    }
};

// prim >= 0: the light is an emissive mesh of which triangle prim alone is estimated (the light
// BVH chose it: render/light_bvh.h).
template <class Scatter, class Visibility>
RGB EstimateDirectWith(const RenderScene &scene, const SurfaceInteraction &si,
                       const Scatter &scatter, int lightIndex, Vec2f uLight, Vec2f uScatter,
                       float uLobe, RayCounters &counters, const Visibility &vis, int prim = -1) {
    const Light &light = *scene.lights[size_t(lightIndex)];
    const DiffuseAreaLight *triangleOf =
        prim >= 0 && light.IsArea() ? static_cast<const DiffuseAreaLight *>(&light) : nullptr;
    const Vec3f &wo = si.wo;
    RGB Ld;
    // The light sample, weighted against the scattering density.
    LightSample ls;
    const bool sampled = triangleOf ? triangleOf->SampleLiTriangle(si, prim, uLight, &ls)
                                    : light.SampleLi(si, uLight, &ls);
    if (sampled && ls.pdf > 0 && !ls.Li.IsBlack()) {
        const RGB f = scatter.F(wo, ls.wi);
        if (!f.IsBlack()) {
            Ray shadow = ls.infinite ? si.SpawnRay(ls.wi, scene.offset)
                                     : si.SpawnRayTo(ls.pLight, scene.offset);
            counters.shadow++;
            RGB Li = ls.Li;
            bool visible;
            if constexpr (Visibility::Media) {
                const RGB tr = ShadowTransmittance(scene, shadow, vis.Toward(si, ls.wi),
                                                   ls.infinite, vis.sampler, counters);
                visible = !tr.IsBlack();
                Li = Li * tr;
            } else {
                visible = !scene.accel->Occluded(shadow);
            }
            if (visible) {
                if (light.IsDelta()) {
                    Ld += f * Li / ls.pdf;
                } else {
                    const float w = PowerHeuristic(1, ls.pdf, 1, scatter.Pdf(wo, ls.wi));
                    Ld += f * Li * (w / ls.pdf);
                }
            }
        }
    }
    if (light.IsDelta()) return Ld;
    // The scattering sample, weighted against the light's density; it counts only if the ray
    // meets this light first.
    BSDFSample bs;
    if (!scatter.Sample(wo, uScatter, uLobe, &bs)) return Ld;
    Ray ray = si.SpawnRay(bs.wi, scene.offset);
    counters.shadow++;
    SurfaceInteraction hit;
    RGB weight = bs.weight;  // times the transmittance up to the light, with media
    bool found;
    if constexpr (Visibility::Media) {
        RGB tr(1);
        found =
            IntersectTr(scene, ray, vis.Toward(si, bs.wi), true, vis.sampler, counters, &hit, &tr);
        if (tr.IsBlack()) return Ld;
        weight = weight * tr;
    } else {
        for (int pass = 0;; ++pass) {
            found = scene.accel->Intersect(ray, &hit);
            if (!found) break;
            const ShapeInfo &info = scene.Info(hit);
            if (!scene.materials[size_t(info.material)].IsPassThrough()) break;
            if (pass >= MaxLightRayCrossings) return Ld;
            ray = hit.SpawnRay(ray.d, scene.offset);
            counters.passThrough++;
        }
    }
    if (!found) {
        const RGB Le = light.Le(ray);
        if (Le.IsBlack()) return Ld;
        const float lightPdf = light.PdfLi(si, bs.wi, nullptr);
        return Ld + weight * Le * PowerHeuristic(1, bs.pdf, 1, lightPdf);
    }
    if (scene.Info(hit).areaLight != lightIndex) return Ld;
    if (triangleOf && hit.prim != prim) return Ld;
    const RGB Le = static_cast<const DiffuseAreaLight &>(light).L(hit, -bs.wi);
    if (Le.IsBlack()) return Ld;
    const float lightPdf =
        triangleOf ? triangleOf->PdfLiTriangle(si, bs.wi, hit) : light.PdfLi(si, bs.wi, &hit);
    if (!(lightPdf > 0)) return Ld;
    return Ld + weight * Le * PowerHeuristic(1, bs.pdf, 1, lightPdf);
}

// pbrt-v3 UniformSampleOneLight over EstimateDirectWith: one light, chosen by `chooser`, divided
// by its probability.
template <class Scatter, class Visibility>
RGB SampleOneLightWith(const RenderScene &scene, const LightChooser &chooser,
                       const SurfaceInteraction &si, const Scatter &scatter, const PixelSamples &ps,
                       int bounce, RayCounters &counters, const Visibility &vis,
                       uint32_t dimShift = 0) {
    // dimShift moves the dimensions within the bounce's (a subsurface exit's light sample).
    const auto dim = [&](uint32_t d) { return VertexDim(bounce, d + dimShift); };
    // The shading normal at a surface (zero at a medium vertex).
    const LightPick pick = chooser.Pick(ps.Get1D(dim(DimLightChoice)), si.p, si.ns);
    if (pick.light < 0 || !(pick.prob > 0)) return RGB(0);
    return EstimateDirectWith(scene, si, scatter, pick.light, ps.Get2D(dim(DimLight)),
                              ps.Get2D(dim(DimScatter)), ps.Get1D(dim(DimScatterLobe)), counters,
                              vis, pick.prim) /
           pick.prob;
}

}  // namespace prism
