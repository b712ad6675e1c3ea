// The ray tree's budget (issue 25). Whitted-style integrators (the effect kernel's specular and
// glossy rays, directlighting's specular recursion) spawn several secondary rays at a hit, so
// the rays traced for one camera sample can grow exponentially with the depth: nested glass
// at maxdepth 1000 spawns about 1.8 times as many rays at each level as at the one before.
//
// Each camera sample's tree therefore has a budget of kRayTreeBudget secondary rays, shared
// out from the top: a hit that spawns k rays (after the ray-weight cutoff) with a budget of b
// rays below it traces the first min(k, b) of them, and each traced ray's own tree gets
// (b - traced) / traced, so no tree ever holds more than its budget and no branch starves its
// siblings (the even split cuts a binary tree at depth ~log2(budget) everywhere, rather than
// spending it all down the first branch). A chain (a mirror hall, total internal reflection)
// spawns one ray per hit and goes as deep as maxdepth allows. Rays left out are counted
// (RayCounters::treeBudget) and the render says so; a scene that stays under the budget
// renders exactly as without it.
#pragma once

#include <algorithm>
#include <cstdint>

namespace prism {

// Secondary rays (reflection, refraction, glossy) one camera sample may trace: 2^20, far
// beyond what a scene needs at the depths it renders well (a tree of glass spheres that
// branches at every hit reaches it at depth 20) and about a second of tracing.
inline constexpr uint64_t kRayTreeBudget = uint64_t(1) << 20;

struct RayTreeShare {
    uint64_t traced = 0;  // how many of the hit's rays are traced (the first ones)
    uint64_t each = 0;    // the budget of each traced ray's own tree
};

// The share of a hit that spawns `rays` rays with `budget` rays allowed below it.
inline RayTreeShare ShareRayTree(uint64_t budget, uint64_t rays) {
    RayTreeShare s;
    s.traced = std::min(budget, rays);
    if (s.traced > 0) s.each = (budget - s.traced) / s.traced;
    return s;
}

}  // namespace prism
