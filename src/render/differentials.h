// Ray differentials at hits (pbrt-v3 §10.1): the screen-space derivatives of the hit point and
// of (u, v) that filtered texture lookups read, and the differentials of specularly reflected
// and refracted rays (Igehy's ray differentials, as pbrt-v3's SpecularReflect and
// SpecularTransmit form them), with the surface's curvature: the derivatives dn/dx, dn/dy of
// the shading normal across the footprint. A curved mirror or lens thus widens (or narrows) the
// footprint of what it shows as it bends the neighbouring rays. The curvature comes from the
// shape at the hit on request (Accel::NormalDerivatives), only where a specular bounce carries
// differentials: hits carry no dndu/dndv, and renders without differentials do no extra work.
#pragma once

#include "geometry/accel.h"
#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "render/texture.h"

namespace prism {

// pbrt-v3 SurfaceInteraction::ComputeDifferentials: where the offset rays of `rd` meet the
// tangent plane at si.p, giving tc->dpdx/dpdy, and (u, v) derivatives from si.dpdu/dpdv
// (zero when those are zero or degenerate). Without usable offset rays, everything is zero.
void ComputeDifferentials(const SurfaceInteraction &si, const RayDifferential &rd,
                          TextureContext *tc);

// The derivatives of the unit shading normal across the footprint (pbrt-v3's dndx, dndy:
// dndu dudx + dndv dvdx, which is the Weingarten map applied to dpdx), oriented as ns.
struct NormalDifferentials {
    Vec3f dndx, dndy;
};
// From the shape that si is on, along tc.dpdx/dpdy. The surface's own curvature: behind a
// bump or normal map the perturbed normal turns with the unperturbed one (the map's own second
// derivatives are left out, as pbrt-v3's Bump keeps the surface's dndu/dndv).
NormalDifferentials FootprintNormalDifferentials(const Accel &accel, const SurfaceInteraction &si,
                                                 const TextureContext &tc, const Vec3f &ns);

// The differentials of the ray reflected specularly about the shading normal ns (wo, wi: the
// unit directions away from the surface) at a hit whose derivatives tc and dn hold
// (dn zero: a flat mirror's).
RayDifferential ReflectDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, const Vec3f &ns,
                                    const NormalDifferentials &dn, const Vec3f &wi);
// The same for specular refraction into wi through an interface of relative index eta
// (inside over outside, as BxDFLobes::eta).
RayDifferential RefractDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, Vec3f ns, NormalDifferentials dn,
                                    const Vec3f &wi, float eta);

}  // namespace prism
