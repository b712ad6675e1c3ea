// Cut-outs (pbrt "alpha"/"shadowalpha" textures, glTF alphaMode MASK/BLEND, OBJ map_d): a test
// that Embree's filter functions (triangle meshes) and the user-geometry callbacks (analytic
// shapes) run on each candidate hit, so a cut-out hides the surface from camera rays and casts
// a cut-out shadow. The alpha itself is a function of the hit's uv and render-space point,
// supplied by build/ (a float texture), so geometry does not depend on render.
#pragma once

#include <bit>
#include <cstdint>
#include <functional>
#include <memory>

#include "core/vecmath.h"

namespace prism {

struct AlphaTest {
    // The alpha at a hit (uv, and p in the space the shape is traced in).
    std::function<float(const Vec2f &uv, const Vec3f &p)> alpha;
    // Cutoff: a hit is kept where alpha >= cutoff (glTF MASK: alphaCutoff), or with cutoff 0
    // (the default) where alpha > 0: pbrt-v3 cuts out where alpha is 0. (Not a denormal
    // cutoff: Embree's threads run with denormals flushed to zero.) Stochastic (glTF BLEND): kept
    // where alpha exceeds a hash of the ray and the hit in [0, 1) (deterministic, so images do not
    // depend on threads).
    bool stochastic = false;
    float cutoff = 0;
    // The texture coordinate set the alpha reads (meshes: TriangleMesh::UVAt; 1 for a glTF
    // base colour on TEXCOORD_1).
    int uvSet = 0;

    bool Keeps(const Vec2f &uv, const Vec3f &p, const Vec3f &o, const Vec3f &d,
               uint32_t prim) const {
        const float a = alpha(uv, p);
        if (!stochastic) return cutoff > 0 ? a >= cutoff : a > 0;
        if (a >= 1) return true;
        if (!(a > 0)) return false;
        return a > HashThreshold(o, d, prim);
    }
    // A hash of the ray (origin, direction) and the primitive, in [0, 1).
    static float HashThreshold(const Vec3f &o, const Vec3f &d, uint32_t prim) {
        uint64_t h = 0x9e3779b97f4a7c15ull ^ prim;
        for (float f : {o.x, o.y, o.z, d.x, d.y, d.z}) {
            h ^= std::bit_cast<uint32_t>(f);
            h *= 0xff51afd7ed558ccdull;
            h ^= h >> 33;
        }
        h *= 0xc4ceb9fe1a85ec53ull;
        h ^= h >> 33;
        return float(h >> 40) * 0x1p-24f;
    }
};

// A shape's tests for camera (and specular) rays and for shadow rays; null: opaque.
struct ShapeAlpha {
    std::shared_ptr<const AlphaTest> camera, shadow;
    bool Any() const { return camera || shadow; }
};

}  // namespace prism
