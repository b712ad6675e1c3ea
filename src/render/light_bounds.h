// What a light (or one part of it: a triangle of an emissive mesh) can send where, bounded for
// the light BVH (render/light_bvh.h): a box, a cone of emission directions and a power. The
// cone is two angles about an axis w (Conty Estevez and Kulla 2018, "Importance Sampling of
// Many Lights with Adaptive Tree Splitting"): every surface normal of the part lies within
// theta_o of w, and each point emits within theta_e of its normal (pi/2 for a diffuse emitter).
#pragma once

#include <vector>

#include "core/vecmath.h"

namespace prism {

struct LightBounds {
    Bounds3f bounds;
    Vec3f w{0, 0, 1};       // the cone's axis (unit)
    float phi = 0;          // the emitted power, its largest RGB component (a weight: units free)
    float cosTheta_o = 1;   // the normals' spread about w
    float cosTheta_e = 0;   // the emission's spread about each normal (1: along it only)
    bool twoSided = false;  // emits on both sides: the cone and its mirror image

    // An upper estimate of the part's contribution to a point p with unit normal n (zero n: a
    // point in a medium, which receives from every direction): phi over the squared distance,
    // times the cosines of the smallest angles the box and cones allow. Zero only where the
    // part cannot light p (p is behind every normal of the cone, beyond the emission spread):
    // the BVH never chooses a part of importance zero, so zero must mean no light. In double:
    // phi / d^2 of a far or huge scene fits no float.
    double Importance(const Vec3f &p, const Vec3f &n) const;
};

// LightBounds as Importance reads them, with what it needs precomputed (the light BVH's nodes).
struct CompactLightBounds {
    CompactLightBounds() = default;
    explicit CompactLightBounds(const LightBounds &lb);
    double Importance(const Vec3f &p, const Vec3f &n) const;

    Vec3d centre;   // of the box
    double r2 = 0;  // the squared radius of the box's bounding sphere
    float r = 0;    // its radius
    Vec3f w{0, 0, 1};
    float phi = 0;
    float cosTheta_o = 1, sinTheta_o = 0, cosTheta_e = 0;
    bool twoSided = false;
};

// The bounds of two parts together: the boxes' union, the smallest cone holding both cones
// (all directions when none smaller does), the powers' sum.
LightBounds Union(const LightBounds &a, const LightBounds &b);

// One part of a light, as a light gives it to the BVH (Light::Bounds): prim is the triangle of
// an emissive mesh, -1 for a light chosen whole.
struct LightPartBounds {
    int prim = -1;
    LightBounds lb;
};

}  // namespace prism
