#include "render/subsurface.h"

#include <algorithm>
#include <vector>

#include "render/bsdf.h"
#include "render/bssrdf.h"
#include "render/ray_counters.h"
#include "render/render_scene.h"

namespace prism {

namespace {

// The most rays one probe traces: a probe through a stack of thin layers stops there rather
// than tracing without end (pbrt-v3 has no limit).
constexpr int MaxProbeRays = 64;

}  // namespace

bool SampleSubsurfaceExit(const RenderScene &scene, const Material &mat,
                          const SeparableBssrdf &bssrdf, float time, float u1, Vec2f u2,
                          SurfaceInteraction *pi, RGB *weight, RayCounters &counters) {
    Vec3f from, to;
    float uChoice;
    if (!bssrdf.Probe(u1, u2, &from, &to, &uChoice)) return false;
    thread_local std::vector<SurfaceInteraction> hits;
    hits.clear();
    Ray ray{from, to - from, 1, 0, time};
    for (int traced = 0; traced < MaxProbeRays; ++traced) {
        SurfaceInteraction si;
        counters.subsurface++;
        if (!scene.accel->Intersect(ray, &si)) break;
        if (&scene.materials[size_t(scene.Info(si).material)] == &mat) hits.push_back(si);
        ray = si.SpawnRayTo(to, scene.offset);
    }
    if (hits.empty()) return false;
    const int n = int(hits.size());
    *pi = hits[size_t(std::min(int(uChoice * float(n)), n - 1))];
    const float pdf = bssrdf.PdfSp(pi->p, pi->n) / float(n);
    if (!(pdf > 0)) return false;
    *weight = bssrdf.Sp(pi->p) / pdf;
    pi->wo = pi->ns;
    return weight->IsFinite() && !weight->IsBlack();
}

void SubsurfaceExitBsdf(const SurfaceInteraction &pi, float eta, BSDF *bsdf) {
    bsdf->SetFrame(pi.ns, pi.dpdu, pi.n);
    bsdf->AddPart().subsurfaceEta = eta;
}

}  // namespace prism
