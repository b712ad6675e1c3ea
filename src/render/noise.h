// Ken Perlin's improved gradient noise (2002) and pbrt-v3's sums of octaves of it (FBm,
// Turbulence), for the procedural 3-D textures. Prism has no ray differentials, so the
// octave sums are pbrt's in the limit of a zero filter footprint (all octaves present).
#pragma once

#include "core/vecmath.h"

namespace prism {

// Noise in [-1, 1] (roughly), zero at integer lattice points; periodic with period 256.
float PerlinNoise(float x, float y, float z);
inline float PerlinNoise(const Vec3f &p) { return PerlinNoise(p.x, p.y, p.z); }
// The noise's slope along each axis by forward differences over 0.01 (pbrt-v4's DNoise, which
// its cloud medium uses to make wisps: the same step, so the same clouds).
Vec3f PerlinNoiseSlope(const Vec3f &p);

// Sum over octaves i < octaves of omega^i · Noise(1.99^i · p).
float FBm(const Vec3f &p, float omega, int octaves);
// Sum of |Noise| over the octaves, plus pbrt-v3's 0.2·omega^octaves allowance for the
// octaves beyond the last one.
float Turbulence(const Vec3f &p, float omega, int octaves);

}  // namespace prism
