#include "render/ao_integrator.h"

#include <cmath>

#include "core/params.h"
#include "render/light_sampling.h"
#include "render/render_scene.h"

namespace prism {

// The most occlusion rays per camera sample an Integrator "ao" may ask for.
inline constexpr int MaxAOSamples = 1 << 16;

// Integrator "ambientocclusion", or "ao" (integrator_list.inc). Parameters:
//   cossample    bool     true      cosine-weighted directions (else uniform over the
//                                   hemisphere)
//   nsamples     integer  64        occlusion rays per camera sample, 1 to 65536
//   maxdistance  float    infinite  pbrt-v4: occluders farther away do not count
std::unique_ptr<Integrator> CreateAOIntegrator(const IntegratorInputs &in) {
    const Params &p = in.params;
    const bool cosSample = p.Bool("cossample", true);
    const int n = p.Int("nsamples", 64);
    if (n < 1 || n > MaxAOSamples)
        throw SceneError(p.Loc("nsamples"), "nsamples " + std::to_string(n) +
                                                " out of range (1 to " +
                                                std::to_string(MaxAOSamples) + ")");
    const float maxDistance = p.Float("maxdistance", Infinity);
    if (!(maxDistance > 0)) throw SceneError(p.Loc("maxdistance"), "maxdistance must be positive");
    p.WarnUnread("Prism's ao integrator reads cossample, nsamples and maxdistance");
    // pbrt-v4 divides by pi, so that a point nothing occludes is 1.
    const float scale = in.pbrtVersion == 4 ? float(InvPi) : 1.f;
    return std::make_unique<AOIntegrator>(cosSample, n, maxDistance, scale);
}

IntegratorTraits AOIntegrator::Traits() const {
    IntegratorTraits t;
    t.samplePatterns = true;
    t.directAov = true;   // all of it is "direct": one bounce, no emission
    t.roughGlass = true;  // no material plays a part: nothing to warn about
    return t;
}

RGB AOIntegrator::Li(const RenderScene &scene, const Ray &cameraRay, const PixelSamples &ps,
                     RayCounters &counters, RGB *direct) const {
    if (direct) *direct = RGB(0);
    Ray ray = cameraRay;
    SurfaceInteraction si;
    for (int pass = 0;; ++pass) {
        if (!scene.accel->Intersect(ray, &si)) return RGB(0);
        if (!scene.materials[size_t(scene.Info(si).material)].IsPassThrough()) break;
        if (pass >= MaxPassThrough) return RGB(0);
        ray = si.SpawnRay(ray.d, scene.offset);
        counters.passThrough++;
    }
    // The hemisphere on the viewer's side of the geometric normal.
    const Vec3f n = FaceForward(si.n, -ray.d);
    Vec3f s, t;
    CoordinateSystem(n, &s, &t);
    const uint32_t count = uint32_t(nSamples_);
    float L = 0;
    for (uint32_t k = 0; k < count; ++k) {
        // Stratified over the pixel's samples × nsamples (PixelSamples).
        const Vec2f u = ps.Get2D(VertexDim(0, DimScatter), k, count);
        const float phi = float(2 * Pi) * u.y;
        float x, y, z, pdf;
        if (cosSample_) {
            // Malley's method: a uniform disk point lifted to the hemisphere.
            const float r = std::sqrt(u.x);
            x = r * std::cos(phi), y = r * std::sin(phi);
            z = std::sqrt(std::max(0.f, 1 - u.x));
            pdf = z * float(InvPi);
        } else {
            z = u.x;
            const float r = std::sqrt(std::max(0.f, 1 - z * z));
            x = r * std::cos(phi), y = r * std::sin(phi);
            pdf = float(0.5 * InvPi);
        }
        if (!(pdf > 0)) continue;
        const Vec3f wi = s * x + t * y + n * z;
        counters.shadow++;
        Ray occlusion = si.SpawnRay(wi, scene.offset);
        occlusion.tMax = std::min(occlusion.tMax, maxDistance_);
        if (!scene.accel->Occluded(occlusion)) L += z / (pdf * float(count));
    }
    L *= scale_;
    if (direct) *direct = RGB(L);
    return RGB(L);
}

}  // namespace prism
