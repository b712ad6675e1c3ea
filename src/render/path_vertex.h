// The steps path and volpath share, so that volpath without media is path, bit for bit: the
// emission a path collects where no light sample covered it, and the surface vertex (shading
// normals, the texture context with the camera ray's footprint, emission, one-light direct
// lighting with MIS, and the BSDF sample that continues the path). Visibility says how light
// reaches the vertex (render/estimate_direct.h): unoccluded (path) or through media (volpath).
#pragma once

#include "render/bssrdf.h"
#include "render/differentials.h"
#include "render/estimate_direct.h"
#include "render/subsurface.h"

namespace prism {

// What a path carries from vertex to vertex.
struct PathState {
    RGB L;                        // radiance collected so far
    RGB beta{1};                  // throughput
    bool specularBounce = false;  // the last bounce was a delta lobe's
    float etaScale = 1;           // radiance scaling by refraction, undone for Russian roulette
    bool regularize = false;      // pbrt-v4's "regularize": BSDF::Regularize after ...
    bool anyNonSpecular = false;  // ... any bounce that was not a delta lobe's
    bool subsurface = true;       // follow light through subsurface materials (PathParams)
};

// Emission no light sample covered (seen by the camera, or after a delta bounce): every light's
// Le for a ray that escapes (si null), else the area light of the surface it hits.
inline void AddUnsampledEmission(const RenderScene &scene, const Ray &ray,
                                 const SurfaceInteraction *si, const ShapeInfo *info,
                                 PathState &path) {
    if (!si) {
        for (const auto &light : scene.lights) path.L += path.beta * light->Le(ray);
    } else if (info->areaLight >= 0) {
        path.L += path.beta *
                  static_cast<const DiffuseAreaLight &>(*scene.lights[size_t(info->areaLight)])
                      .L(*si, si->wo);
    }
}

// After a transmission into a subsurface material at si: the exit pi, direct lighting there
// through the exit lobe, and the direction the path leaves in (pbrt-v3 PathIntegrator's
// BSSRDF step, with the vertex's own dimensions). si becomes the exit.
template <class Visibility>
bool SubsurfaceVertex(const RenderScene &scene, const LightChooser &chooser,
                      const SeparableBssrdf &bssrdf, const Material &mat, const PixelSamples &ps,
                      int bounces, const Visibility &vis, PathState &path, SurfaceInteraction &si,
                      Vec3f *wi, RayCounters &counters) {
    SurfaceInteraction pi;
    RGB weight;
    if (!SampleSubsurfaceExit(
            scene, mat, bssrdf, si.time, ps.Get1D(VertexDim(bounces, DimSubsurface)),
            ps.Get2D(VertexDim(bounces, DimSubsurfaceProbe)), &pi, &weight, counters))
        return false;
    path.beta *= weight;
    BSDF exit;
    SubsurfaceExitBsdf(pi, bssrdf.Eta(), &exit);
    path.L += path.beta * SampleOneLightWith(scene, chooser, pi, BsdfScatter{exit}, ps, bounces,
                                             counters, vis, DimSubsurfaceExit);
    // The exit scales no radiance by refraction (pbrt-v3 leaves etaScale alone here).
    float etaScale = 1;
    if (!SampleNextDirection(exit, pi.wo, ps, bounces, path.beta, path.specularBounce, etaScale, wi,
                             counters, DimSubsurfaceExit))
        return false;
    si = pi;
    return true;
}

// The surface vertex `bounces` of a path at si (material mat, not a pass-through surface).
// diff: the camera ray's differentials at its first hit, else null. Returns false when the
// path ends there; else *wi is the direction it continues in, from si (which a subsurface
// material replaces by the point where the light leaves it).
template <class Visibility>
bool SurfaceVertex(const RenderScene &scene, const LightChooser &chooser, SurfaceInteraction &si,
                   const Material &mat, const PixelSamples &ps, int bounces,
                   const RayDifferential *diff, const Visibility &vis, PathState &path, Vec3f *wi,
                   RayCounters &counters) {
    if (mat.PerturbsShading()) mat.PerturbShading(si);
    TextureContext tc = SurfaceTextureContext(si);
    if (diff) ComputeDifferentials(si, *diff, &tc);
    // Emission a material carries itself (glTF emissive textures; no light samples it).
    if (mat.HasEmission()) path.L += path.beta * mat.Emitted(tc);
    BSDF bsdf = mat.GetBSDF(si, tc);
    if (path.regularize && path.anyNonSpecular) bsdf.Regularize();
    bsdf.MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
    // Direct lighting: one light, light and BSDF samples weighted by MIS.
    if (bsdf.HasNonSpecular())
        path.L += path.beta * SampleOneLightWith(scene, chooser, si, BsdfScatter{bsdf}, ps, bounces,
                                                 counters, vis);
    // Sample the BSDF for the next direction.
    if (!SampleNextDirection(bsdf, si.wo, ps, bounces, path.beta, path.specularBounce,
                             path.etaScale, wi, counters))
        return false;
    path.anyNonSpecular |= !path.specularBounce;
    // Light refracted into a subsurface material leaves elsewhere on it.
    if (mat.HasSubsurface() && path.subsurface && Dot(*wi, si.n) * Dot(si.wo, si.n) < 0) {
        SeparableBssrdf bssrdf;
        if (mat.Model().SubsurfaceAt(tc, si.p, si.ns, si.dpdu, &bssrdf))
            return SubsurfaceVertex(scene, chooser, bssrdf, mat, ps, bounces, vis, path, si, wi,
                                    counters);
    }
    return true;
}

}  // namespace prism
