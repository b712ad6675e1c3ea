#include "render/sppm_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/memory.h"
#include "core/params.h"
#include "image/image.h"
#include "render/effects.h"
#include "render/render_scene.h"
#include "render/renderer.h"

namespace prism {

// Integrator "sppm" (integrator_list.inc). Parameters (pbrt-v3's):
//   numiterations        integer  64         camera and photon passes (--spp wins, as in
//                                            pbrt-v4, whose iterations are the spp)
//   maxdepth             integer  5          the longest camera path to a visible point and
//                                            the most bounces of a photon (--maxdepth wins)
//   photonsperiteration  integer  -1         photons per iteration (-1: the crop window's
//                                            pixel count)
//   radius               float    1          the initial search radius, in world units
//   imagewritefrequency  integer  2^31       an intermediate image every this many iterations,
//                                            written as the output is (atomically)
std::unique_ptr<Integrator> CreateSppmIntegrator(const IntegratorInputs &in) {
    const Params &p = in.params;
    SppmParams sp;
    sp.iterations = p.Int("numiterations", 64);
    if (in.spp > 0) sp.iterations = in.spp;
    if (sp.iterations < 1 || sp.iterations > (1 << 24))
        throw SceneError(p.Loc("numiterations"), "numiterations " + std::to_string(sp.iterations) +
                                                     " out of range (1 to 16777216)");
    const int photons = p.Int("photonsperiteration", -1);
    if (photons == 0 || photons < -1)
        throw SceneError(p.Loc("photonsperiteration"),
                         "photonsperiteration must be positive (or -1: the pixel count)");
    sp.photonsPerIteration = photons;
    sp.radius = p.Float("radius", 1.f);
    if (!(sp.radius > 0) || !std::isfinite(sp.radius))
        throw SceneError(p.Loc("radius"), "radius must be a finite number > 0");
    const int freq = p.Int("imagewritefrequency", 1 << 30);
    sp.writeFrequency = freq > 0 ? freq : 1 << 30;
    // Photons carry light along every path: the one effect no material or light turns on.
    in.effects.Enable(Effect::IndirectIllumination, in.why, in.whyLoc);
    p.WarnUnread(
        "Prism's sppm integrator reads numiterations, maxdepth, photonsperiteration, radius "
        "and imagewritefrequency");
    return std::make_unique<SppmIntegrator>(sp);
}

IntegratorTraits SppmIntegrator::Traits() const {
    IntegratorTraits t;
    t.samplePatterns = true;
    t.roughGlass = true;
    return t;
}

void SppmIntegrator::Prepare(const RenderScene &scene) {
    uniform_ = LightChooser(scene, LightChoice::Uniform);
    power_ = LightChooser(scene, LightChoice::Power);
}

RGB SppmIntegrator::Li(const RenderScene &, const Ray &, const PixelSamples &, RayCounters &,
                       RGB *direct) const {
    if (direct) *direct = RGB(0);
    return RGB(0);
}

RGB SppmPass::f(uint32_t i, const Vec3f &wiW) const {
    const SppmVisiblePoint &v = points[i];
    const auto local = [&](const Vec3f &w) {
        return Vec3f(Dot(w, v.ss), Dot(w, v.ts), Dot(w, v.ns));
    };
    const Vec3f wo = local(v.wo), wi = local(wiW);
    if (wo.z == 0) return RGB(0);
    // The geometric normal decides reflection or transmission, as in BSDF::f.
    const bool reflect = Dot(wiW, v.ng) * Dot(v.wo, v.ng) > 0;
    RGB result;
    for (uint32_t k = 0; k < v.numParts; ++k) {
        const SppmPart &part = Part(i, k);
        result += part.weight * part.lobes.f(wo, wi, reflect);
    }
    return result;
}

namespace {

// The memory one iteration holds beside the pixels: a visible point and one BSDF part per
// pixel (more for mixes, counted as they come), the grid (at most 8 cells per point and a
// bucket per point), and the photon chunks in flight with a deposit per visible point each.
uint64_t EstimateIterationBytes(uint64_t nPixels, int chunksInFlight) {
    const uint64_t perPoint = sizeof(SppmVisiblePoint) + sizeof(SppmPart) + sizeof(SppmPixel) +
                              sizeof(uint32_t) * (1 + 8 + 1);
    return nPixels * perPoint + uint64_t(chunksInFlight) * nPixels * 20;
}

}  // namespace

Image SppmIntegrator::RenderFrame(const FrameContext &frame) const {
    const RenderScene &scene = frame.scene;
    const Bounds2i &pb = frame.Pixels();
    const size_t nPixels = size_t(pb.Area());
    const int64_t photons =
        params_.photonsPerIteration > 0 ? params_.photonsPerIteration : int64_t(nPixels);
    // The visible points, grid and deposits against what the scene left of its budget.
    {
        MemoryBudget budget(scene.memoryLimit);
        budget.Charge(std::min(scene.memoryCommitted, budget.Limit()), "scene");
        budget.Check(
            EstimateIterationBytes(nPixels, SppmChunksInFlight + 2),
            "sppm's visible points and photon grid for " + std::to_string(nPixels) + " pixels");
    }
    std::vector<SppmPixel> pixels(nPixels);
    for (SppmPixel &px : pixels) px.radius = params_.radius;
    SppmPass pass;
    SppmGrid grid;
    const int n = params_.iterations;
    int done = 0;
    for (int iter = 0; iter < n && !frame.Cancelled(); ++iter) {
        frame.SetProgress((iter + 0.0) / n);
        CameraPass(frame, iter, pass, pixels);
        if (frame.Cancelled()) break;
        grid.Build(pass.points, pixels);
        frame.SetProgress((iter + 0.3) / n);
        PhotonPass(frame, iter, photons, pass, grid, pixels);
        if (frame.Cancelled()) break;
        // Progressive radius reduction (Hachisuka and Jensen 2009, alpha 2/3): each pixel keeps
        // a share alpha of this iteration's photons and shrinks its radius so that the density
        // of what it keeps is unchanged.
        constexpr float Alpha = 2.f / 3;
        for (size_t i = 0; i < nPixels; ++i) {
            SppmPixel &px = pixels[i];
            if (px.M > 0) {
                const float nNew = px.N + Alpha * float(px.M);
                const float rNew = px.radius * std::sqrt(nNew / (px.N + float(px.M)));
                const RGB phi = pass.points[i].beta * px.phi;
                px.tau = (px.tau + phi) * ((rNew * rNew) / (px.radius * px.radius));
                px.N = nNew;
                px.radius = rNew;
            }
            px.M = 0;
            px.phi = RGB(0);
        }
        done = iter + 1;
        frame.SetSamplesPerPixel(done);
        if (done % params_.writeFrequency == 0 && done < n && frame.WantsIntermediate())
            frame.Intermediate(MakeImage(frame, pixels, done, photons));
    }
    frame.SetProgress(1);
    return MakeImage(frame, pixels, done, photons);
}

Image SppmIntegrator::MakeImage(const FrameContext &frame, const std::vector<SppmPixel> &pixels,
                                int done, int64_t photons) const {
    const Bounds2i &pb = frame.Pixels();
    const int w = pb.Width();
    // pbrt-v3: L = Ld / iterations + tau / (photons emitted · pi r^2).
    const double emitted = double(done) * double(photons);
    return frame.MakeImage([&](int x, int y) {
        if (done == 0) return RGB(0);
        const SppmPixel &px = pixels[size_t(y - pb.pMin.y) * size_t(w) + size_t(x - pb.pMin.x)];
        const double area = Pi * double(px.radius) * double(px.radius);
        return px.Ld / float(done) + px.tau * float(1 / (emitted * area));
    });
}

}  // namespace prism
