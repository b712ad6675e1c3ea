// sppm's camera pass (pbrt-v3 SPPMIntegrator::Render, "generate SPPM visible points"): per
// pixel one camera path through specular and glossy bounces to its first diffuse surface (or a
// glossy one at the last bounce), with emission and one-light direct lighting at every vertex
// it meets, which becomes the pixel's visible point for the photon pass.
#include <algorithm>

#include "render/area_light.h"
#include "render/differentials.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/sppm_integrator.h"

namespace prism {

namespace {

// pbrt-v3's BSDF_DIFFUSE components: Lambertian (or Oren–Nayar) reflection and transmission.
// FresnelBlend is glossy there, as it is here (BxDFLobes::HasGlossy).
bool HasDiffuseLobe(const BSDF &b) {
    for (int i = 0; i < b.NumParts(); ++i)
        if (!b.Weight(i).IsBlack() && (!b.Part(i).kd.IsBlack() || !b.Part(i).kdTransmit.IsBlack()))
            return true;
    return false;
}

void StoreVisiblePoint(const SurfaceInteraction &si, const BSDF &bsdf, const RGB &beta,
                       std::vector<SppmPart> &lobes, SppmVisiblePoint *vp) {
    vp->p = si.p;
    vp->wo = si.wo;
    vp->ss = bsdf.ss;
    vp->ts = bsdf.ts;
    vp->ns = bsdf.ns;
    vp->ng = bsdf.ng;
    vp->beta = beta;
    vp->firstPart = uint32_t(lobes.size());
    for (int i = 0; i < bsdf.NumParts(); ++i)
        if (!bsdf.Weight(i).IsBlack() && bsdf.Part(i).HasNonSpecular())
            lobes.push_back({bsdf.Weight(i), bsdf.Part(i)});
    vp->numParts = uint32_t(lobes.size()) - vp->firstPart;
}

}  // namespace

void SppmIntegrator::CameraPass(const FrameContext &frame, int iter, SppmPass &pass,
                                std::vector<SppmPixel> &pixels) const {
    const RenderScene &scene = frame.scene;
    const Bounds2i &pb = frame.Pixels();
    const size_t width = size_t(pb.Width());
    pass.points.resize(pixels.size());
    pass.tileOfPoint.resize(pixels.size());
    pass.lobes.resize(size_t(frame.NumTiles()));
    // Iteration k is camera sample k of numiterations (stratified over the iterations).
    SamplerSettings ss = frame.sampler;
    ss.spp = params_.iterations;
    const CameraSampler camera(scene, ss);
    const int maxDepth = frame.trace.maxDepth;
    frame.ForEach(0, frame.NumTiles(), [&](int t, RayCounters &rc) {
        std::vector<SppmPart> &lobes = pass.lobes[size_t(t)];
        lobes.clear();
        const Bounds2i tb = frame.TilePixels(t);
        for (int y = tb.pMin.y; y < tb.pMax.y; ++y)
            for (int x = tb.pMin.x; x < tb.pMax.x; ++x) {
                const size_t idx = size_t(y - pb.pMin.y) * width + size_t(x - pb.pMin.x);
                SppmVisiblePoint &vp = pass.points[idx];
                vp.beta = RGB(0);
                pass.tileOfPoint[idx] = uint32_t(t);
                const CameraSample cs =
                    camera.Sample(x, y, uint32_t(iter), camera.PixelSeeds(x, y));
                if (camera.Lens()) rc.lensSamples++;
                Ray ray = camera.GenerateRay(cs);
                rc.camera++;
                PixelSamples ps = PixelSamplesOf(ss, x, y, uint32_t(iter),
                                                 uint32_t(params_.iterations), frame.trace);
                RayDifferential rd;
                if (camera.Differentials()) rd = camera.GenerateDifferential(ray, cs);
                const Vec3f cameraOrigin = ray.o;
                RGB beta(camera.RayWeight(cs)), Ld;
                bool specularBounce = false;
                float etaScale = 1;
                int passes = 0;
                for (int depth = 0; depth < maxDepth; ++depth) {
                    SurfaceInteraction si;
                    if (!scene.accel->Intersect(ray, &si)) {
                        // Only specular and glossy bounces get here: no light sample covered it.
                        for (const auto &light : scene.lights) Ld += beta * light->Le(ray);
                        break;
                    }
                    const ShapeInfo &info = scene.Info(si);
                    const Material &mat = scene.materials[size_t(info.material)];
                    if (mat.IsPassThrough()) {
                        if (++passes > MaxPassThrough) break;
                        ray = si.SpawnRay(ray.d, scene.offset);
                        rc.passThrough++;
                        --depth;
                        continue;
                    }
                    passes = 0;
                    if ((depth == 0 || specularBounce) && info.areaLight >= 0)
                        Ld += beta * static_cast<const DiffuseAreaLight &>(
                                         *scene.lights[size_t(info.areaLight)])
                                         .L(si, si.wo);
                    if (mat.PerturbsShading()) mat.PerturbShading(si);
                    TextureContext tc = SurfaceTextureContext(si);
                    if (depth == 0 && camera.Differentials() && ray.o == cameraOrigin)
                        ComputeDifferentials(si, rd, &tc);
                    if (mat.HasEmission()) Ld += beta * mat.Emitted(tc);
                    BSDF bsdf = mat.GetBSDF(si, tc);
                    bsdf.MakeRoughSpecularGlossy();  // pbrt-v3: rough glass is a microfacet BSDF
                    // Direct lighting at every vertex, one light chosen uniformly (pbrt-v3).
                    if (bsdf.HasNonSpecular())
                        Ld += beta * SampleOneLight(scene, uniform_, si, bsdf, ps, depth, rc);
                    const bool glossy = bsdf.HasGlossy();
                    if (HasDiffuseLobe(bsdf) || (glossy && depth == maxDepth - 1)) {
                        StoreVisiblePoint(si, bsdf, beta, lobes, &vp);
                        break;
                    }
                    if (depth + 1 >= maxDepth) break;
                    Vec3f wi;
                    if (!SampleNextDirection(bsdf, si.wo, ps, depth, beta, specularBounce, etaScale,
                                             &wi, rc))
                        break;
                    // pbrt-v3's roulette of camera paths: below a throughput of 1/4.
                    const float lum = beta.Luminance();
                    if (lum < 0.25f) {
                        const float q = std::min(1.f, lum);
                        if (!(q > 0) || ps.Get1D(VertexDim(depth, DimRoulette)) > q) break;
                        beta = beta / q;
                    }
                    ray = si.SpawnRay(wi, scene.offset);
                }
                pixels[idx].Ld += Ld;
            }
    });
}

}  // namespace prism
