// Where subsurface light leaves (pbrt-v3 PathIntegrator's BSSRDF step): light that refracted
// into a subsurface material leaves at a point found by a probe ray through the profile's
// extent (SeparableBssrdf::Probe), chosen among the probe's hits on the same material, and
// scatters out there by the exit lobe (BxDFLobes::subsurfaceEta). The path integrators'
// surface vertex (render/path_vertex.h) takes this step after a transmission.
#pragma once

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

struct RenderScene;
struct RayCounters;
struct SurfaceInteraction;
struct BSDF;
class Material;
class SeparableBssrdf;

// Traces the probe of sample (u1, u2) at the ray time `time`, keeps its hits on `mat` (the
// material whose BSSRDF this is), and chooses one uniformly: *pi (its wo the shading normal,
// as pbrt's exit) and *weight = Sp / pdf. False when the sample finds no exit. Counts the
// probe's rays as RayCounters::subsurface.
bool SampleSubsurfaceExit(const RenderScene &scene, const Material &mat,
                          const SeparableBssrdf &bssrdf, float time, float u1, Vec2f u2,
                          SurfaceInteraction *pi, RGB *weight, RayCounters &counters);

// The exit's BSDF at pi: the exit lobe of index eta, in pi's shading frame.
void SubsurfaceExitBsdf(const SurfaceInteraction &pi, float eta, BSDF *bsdf);

}  // namespace prism
