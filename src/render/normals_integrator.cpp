// Scratch (reverted in a later commit): an integrator added through docs/ARCHITECTURE.md's
// checklist only. It returns the first hit's shading normal mapped to [0,1]^3.
#include "core/params.h"
#include "render/integrator.h"
#include "render/render_scene.h"

namespace prism {

namespace {
class NormalsIntegrator final : public Integrator {
  public:
    const char *Name() const override { return "normals"; }
    IntegratorTraits Traits() const override {
        IntegratorTraits t;
        t.roughGlass = true;
        return t;
    }
    RGB Li(const RenderScene &scene, const Ray &ray, const PixelSamples &, RayCounters &,
           RGB *direct) const override {
        if (direct) *direct = RGB(0);
        SurfaceInteraction si;
        if (!scene.accel->Intersect(ray, &si)) return RGB(0);
        const Vec3f n = FaceForward(si.ns, -ray.d);
        return RGB(0.5f * (n.x + 1), 0.5f * (n.y + 1), 0.5f * (n.z + 1));
    }
};
}  // namespace

// Integrator "normals" (integrator_list.inc). No parameters.
std::unique_ptr<Integrator> CreateNormalsIntegrator(const IntegratorInputs &in) {
    in.params.WarnUnread("the normals integrator has no parameters");
    return std::make_unique<NormalsIntegrator>();
}

}  // namespace prism
