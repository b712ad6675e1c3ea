// Importance sampling of a whole glTF BSDF (render/gltf_material.h) as a path tracer would
// use it: a mixture of cosine-weighted sampling of the diffuse lobe and visible-normal sampling
// of each glossy part (the same draws as BSDF::SampleGlossy), with the mixture's density.
// Prism's integrators sample the glossy lobes with SampleGlossy and reach the diffuse lobe
// through light samples; this is the complete Sample_f / Pdf for tests and tools. Delta lobes
// (the polished limit) are not sampled here.
#pragma once

#include "render/bsdf.h"

namespace prism {

// Samples wi (world) for wo; returns f(wo, wi) over the non-delta lobes and sets *pdf (0 when
// nothing was sampled). u drives the chosen lobe, uc chooses the lobe.
RGB GltfSampleF(const BSDF &b, const Vec3f &wo, Vec2f u, float uc, Vec3f *wi, float *pdf);
// The density GltfSampleF samples wi with.
float GltfPdf(const BSDF &b, const Vec3f &wo, const Vec3f &wi);

}  // namespace prism
