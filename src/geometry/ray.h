// Rays and robust spawning of secondary rays from error-bounded hit points
// (pbrt-v3 §3.9.5: offset along the geometric normal by the hit point's error bound, then one
// more ulp away). No scene-scale epsilon exists anywhere in Prism.
#pragma once

#include "core/vecmath.h"

namespace prism {

// How a secondary ray's origin leaves the surface it starts on. ErrorBounds is Prism's method
// (below); FixedEpsilon and None exist to show what they cost (`prism study --knob offset`).
enum class OffsetMode { ErrorBounds, FixedEpsilon, None };
struct RayOffset {
    OffsetMode mode = OffsetMode::ErrorBounds;
    float epsilon = 1e-4f;  // FixedEpsilon: distance along the geometric normal, scene units
};

struct Ray {
    Vec3f o, d;
    float tMax = Infinity;
    float tMin = 0;  // only `prism trace` sets it; spawned rays rely on their offset origin
    // When the ray is traced, as a fraction of the camera's shutter interval in [0, 1) (0:
    // shutteropen; Embree's RTCRay::time). Camera rays draw it per sample where something
    // moves (else it stays 0); rays spawned from a hit inherit it.
    float time = 0;
    Vec3f At(float t) const { return o + d * t; }
};

// pbrt-v3's ray differentials: the rays through the neighbouring pixels (one to the right,
// one down), offset and direction, carried beside a ray only where a texture filters
// (RenderScene::differentials). Scale moves them toward the ray (pbrt-v3 ScaleDifferentials:
// with n samples per pixel the footprint of one sample is 1/sqrt(n) of a pixel).
struct RayDifferential {
    Vec3f rxOrigin, ryOrigin, rxDirection, ryDirection;
    void Scale(const Vec3f &o, const Vec3f &d, float s) {
        rxOrigin = o + (rxOrigin - o) * s;
        ryOrigin = o + (ryOrigin - o) * s;
        rxDirection = d + (rxDirection - d) * s;
        ryDirection = d + (ryDirection - d) * s;
    }
};

inline Vec3f OffsetRayOrigin(const Vec3f &p, const Vec3f &pError, const Vec3f &n, const Vec3f &w) {
    float d = Dot(Abs(n), pError);
    Vec3f offset = n * d;
    if (Dot(w, n) < 0) offset = -offset;
    Vec3f po = p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = NextFloatUp(po[i]);
        else if (offset[i] < 0)
            po[i] = NextFloatDown(po[i]);
    }
    return po;
}

// FixedEpsilon moves p by epsilon along n, to w's side; None keeps p, so the ray may hit the
// surface it leaves (acne). Out of line: only studies of the offset take this path.
[[gnu::cold, gnu::noinline]] inline Vec3f SpawnOriginUnbounded(const Vec3f &p, const Vec3f &n,
                                                               const Vec3f &w,
                                                               const RayOffset &offset) {
    if (offset.mode == OffsetMode::None) return p;
    return p + (Dot(w, n) < 0 ? -n : n) * offset.epsilon;
}

// The origin of a ray leaving p in direction w by the chosen method (`--offset`). The default,
// ErrorBounds (OffsetRayOrigin), is tested first and inline, so the default render pays one
// predictable branch.
inline Vec3f SpawnOrigin(const Vec3f &p, const Vec3f &pError, const Vec3f &n, const Vec3f &w,
                         const RayOffset &offset) {
    if (offset.mode == OffsetMode::ErrorBounds) [[likely]]
        return OffsetRayOrigin(p, pError, n, w);
    return SpawnOriginUnbounded(p, n, w, offset);
}

// Shadow rays stop this fraction short of their target (pbrt's ShadowEpsilon), so a light or
// surface exactly at the target never occludes itself.
inline constexpr float ShadowEpsilon = 1e-4f;

}  // namespace prism
