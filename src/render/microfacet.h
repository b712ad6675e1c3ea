// Trowbridge–Reitz (GGX) helpers of bsdf.cpp shared with the glTF material's full sampling
// (render/gltf_sampling.h) and the layered BSDF (render/layered_bxdf.h), in the shading frame.
#pragma once

#include "core/vecmath.h"

namespace prism {

// The distribution of normals D(wh) (wh on either side) and Smith's Λ(w) for alphas ax, ay.
float TrowbridgeReitzD(const Vec3f &wh, float ax, float ay);
float TrowbridgeReitzLambda(const Vec3f &w, float ax, float ay);

// A microfacet normal sampled from the distribution of normals visible from w (w.z > 0;
// Heitz 2018) and its density.
Vec3f TrowbridgeReitzSampleVisible(const Vec3f &w, float ax, float ay, Vec2f u);
float TrowbridgeReitzVisiblePdf(const Vec3f &w, const Vec3f &wh, float ax, float ay);

}  // namespace prism
