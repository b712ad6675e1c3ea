// Choosing a light for a shading point from a bounding volume hierarchy over the scene's lights
// and the triangles of its emissive meshes, in proportion to each subtree's importance at the
// point (render/light_bounds.h), as pbrt-v4's "bvh" light sampler does: a shading point near one
// lamp of thousands samples that lamp, not all of them by power.
#pragma once

#include <cstdint>
#include <vector>

#include "render/light_bounds.h"

namespace prism {

class Light;

// A chosen light: its index in the scene's list, the triangle of an emissive mesh chosen alone
// (-1: the light whole), and the probability of the choice.
struct LightPick {
    int light = -1;
    int prim = -1;
    float prob = 0;
};

class LightBVH {
  public:
    LightBVH() = default;
    // Over the lights' parts (Light::Bounds). A light with none (distant, infinite) is chosen
    // apart, among such lights in proportion to `infiniteImportance` (their importance at any
    // point: power over the squared radius of the scene's bounding sphere), against the tree
    // half in proportion to their sum and the root's importance at the point and half evenly,
    // so its share is within [1/4, 3/4] (defensive: a sky seen past an occluded lamp is not
    // starved, nor lamps under a bright sky). Without valid importances (empty, or one not
    // positive and finite): uniformly among them, with share count / (count + 1), as pbrt-v4.
    explicit LightBVH(const std::vector<const Light *> &lights,
                      const std::vector<double> &infiniteImportance = {});

    // A light for the point p with unit normal n (zero in a medium), by u in [0,1). No light
    // (light -1) when nothing can light p, and for the share of u where a node's bounds
    // allowed light its children's do not: the probabilities of the choices then sum to
    // less than 1, and what is missing is light that is not there.
    LightPick Sample(float u, const Vec3f &p, const Vec3f &n) const;
    // The probability with which Sample chooses (light, prim) at p (0 if never).
    float Pmf(const Vec3f &p, const Vec3f &n, int light, int prim) const;

    size_t NumParts() const { return parts_.size(); }
    size_t NumNodes() const { return nodes_.size(); }
    int Depth() const { return depth_; }
    size_t NumInfinite() const { return infinite_.size(); }  // lights chosen apart

  private:
    struct Part {
        int light, prim;
        LightBounds lb;
    };
    // Node i's first child is node i + 1, its second node `second`; a leaf holds part `part`.
    struct Node {
        CompactLightBounds lb;
        int32_t second = -1;
        int32_t part = -1;
        bool IsLeaf() const { return part >= 0; }
    };
    int Build(std::vector<Part> &parts, size_t begin, size_t end, int depth);
    // The probability of choosing among the lights without bounds at p.
    double InfiniteShare(const Vec3f &p, const Vec3f &n) const;
    // The probability of infinite light k (an index of infinite_) among them.
    double InfiniteProb(size_t k) const;

    std::vector<Node> nodes_;
    std::vector<Part> parts_;          // in leaf order
    std::vector<int> infinite_;        // lights without bounds
    std::vector<double> infiniteCdf_;  // their importances' running sum (empty: uniform)
    std::vector<int32_t> leafOfPart_;  // node of parts_[i]
    std::vector<int32_t> parent_;      // per node (-1 at the root)
    // The part of (light, prim): partIndex_[slot_[light] + max(prim, 0)], -1 for none.
    std::vector<int64_t> slot_;
    std::vector<int32_t> partIndex_;
    int depth_ = 0;
};

}  // namespace prism
