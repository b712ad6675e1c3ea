// Ray differentials at hits (pbrt-v3 §10.1): the screen-space derivatives of the hit point and
// of (u, v) that filtered texture lookups read, and the differentials of specularly reflected
// and refracted rays (pbrt-v3 SpecularReflect / SpecularTransmit). Prism's hits carry no
// normal derivatives (dndu, dndv), so the curvature term of the specular differentials is
// left out: exact for flat mirrors and glass, too narrow a footprint behind curved ones.
#pragma once

#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "render/texture.h"

namespace prism {

// pbrt-v3 SurfaceInteraction::ComputeDifferentials: where the offset rays of `rd` meet the
// tangent plane at si.p, giving tc->dpdx/dpdy, and (u, v) derivatives from si.dpdu/dpdv
// (zero when those are zero or degenerate). Without usable offset rays, everything is zero.
void ComputeDifferentials(const SurfaceInteraction &si, const RayDifferential &rd,
                          TextureContext *tc);

// The differentials of the ray reflected specularly about the shading normal ns (wo, wi: the
// unit directions away from the surface) at a hit whose derivatives tc holds.
RayDifferential ReflectDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, const Vec3f &ns, const Vec3f &wi);
// The same for specular refraction into wi through an interface of relative index eta
// (inside over outside, as BxDFLobes::eta).
RayDifferential RefractDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, Vec3f ns, const Vec3f &wi,
                                    float eta);

}  // namespace prism
