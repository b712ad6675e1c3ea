#include "render/light_bvh.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "render/light.h"

namespace prism {

namespace {

constexpr float kPi = float(Pi);

// v rotated by angle theta about the unit axis k perpendicular to it.
Vec3f RotatePerpendicular(const Vec3f &v, const Vec3f &k, float theta) {
    return v * std::cos(theta) + Cross(k, v) * std::sin(theta);
}

float SurfaceArea(const Bounds3f &b) {
    const Vec3f d = b.Diagonal();
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The measure of the directions a cone of normals (theta_o) emitting within theta_e of each
// normal reaches, each weighted by the cosine to the nearest normal (the orientation term of
// Conty Estevez and Kulla's surface area orientation heuristic).
float OrientationMeasure(float cosTheta_o, float cosTheta_e) {
    const float thetaO = SafeACos(cosTheta_o);
    const float thetaE = SafeACos(cosTheta_e);
    const float thetaW = std::min(thetaO + thetaE, kPi);
    const float sinO = SafeSqrt(1 - cosTheta_o * cosTheta_o);
    return 2 * kPi * (1 - cosTheta_o) +
           kPi / 2 *
               (2 * thetaW * sinO - std::cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + cosTheta_o);
}

}  // namespace

double LightBounds::Importance(const Vec3f &p, const Vec3f &n) const {
    return CompactLightBounds(*this).Importance(p, n);
}

CompactLightBounds::CompactLightBounds(const LightBounds &lb)
    : centre(Vec3d(lb.bounds.pMin) * 0.5 + Vec3d(lb.bounds.pMax) * 0.5),
      r2(LengthSquared(Vec3d(lb.bounds.pMax) - Vec3d(lb.bounds.pMin)) * 0.25),
      r(float(std::sqrt(r2))),
      w(lb.w),
      phi(lb.phi),
      cosTheta_o(std::clamp(lb.cosTheta_o, -1.f, 1.f)),
      sinTheta_o(SafeSqrt(1 - cosTheta_o * cosTheta_o)),
      cosTheta_e(lb.cosTheta_e),
      twoSided(lb.twoSided) {}

double CompactLightBounds::Importance(const Vec3f &p, const Vec3f &n) const {
    if (!(phi > 0)) return 0;
    // Distances in double: a scene's far and huge lights neither overflow nor vanish.
    const Vec3d toP = Vec3d(p) - centre;
    const double dist2 = LengthSquared(toP);
    // Inside the bounding sphere the distance is the sphere's radius (no 1/d^2 blow-up).
    const double d2 = std::max(dist2, r2);
    const bool inside = !(dist2 > r2);
    const double invDist = dist2 > 0 ? 1 / std::sqrt(dist2) : 0;
    // The direction from the box toward p, against the cone's axis.
    const Vec3f wi = dist2 > 0 ? Vec3f(toP * invDist) : w;
    float cosW = Dot(w, wi);
    if (twoSided) cosW = std::abs(cosW);
    cosW = std::clamp(cosW, -1.f, 1.f);
    // The smallest angle between p's direction and a normal of the cone (x), less the angle
    // the box's bounding sphere subtends from p (b: pi inside it), each taken only if needed.
    float cosX = 1, sinX = 0;
    if (cosW < cosTheta_o) {
        const float sinW = SafeSqrt(1 - cosW * cosW);
        cosX = cosW * cosTheta_o + sinW * sinTheta_o;
        sinX = sinW * cosTheta_o - cosW * sinTheta_o;
    }
    float cosB = -1, sinB = 0;
    bool haveB = false;
    auto boxAngle = [&] {
        haveB = true;
        if (inside) return;
        sinB = std::min(float(double(r) * invDist), 1.f);
        cosB = SafeSqrt(1 - sinB * sinB);
    };
    float cosP = 1;
    if (cosX < 1) {
        boxAngle();
        if (cosX < cosB) cosP = cosX * cosB + sinX * sinB;
    }
    if (cosP < cosTheta_e) return 0;
    double importance = double(phi) * double(cosP) / (d2 > 0 ? d2 : 1e-300);
    if (n != Vec3f(0, 0, 0)) {
        // The incident cosine at p, the box's angle allowing (either side: transmission).
        const float cosI = std::min(AbsDot(wi, n), 1.f);
        if (!haveB) boxAngle();
        if (cosI < cosB) importance *= double(cosI * cosB + SafeSqrt(1 - cosI * cosI) * sinB);
    }
    return std::max(importance, 0.0);
}

LightBounds Union(const LightBounds &a, const LightBounds &b) {
    if (!(a.phi > 0)) return b;
    if (!(b.phi > 0)) return a;
    LightBounds u;
    u.bounds = a.bounds;
    u.bounds.Expand(b.bounds);
    u.phi = a.phi + b.phi;
    u.cosTheta_e = std::min(a.cosTheta_e, b.cosTheta_e);
    u.twoSided = a.twoSided || b.twoSided;
    // The smallest cone holding both: one of them if it holds the other, else the cone whose
    // edge touches both far edges.
    const float thetaA = SafeACos(a.cosTheta_o);
    const float thetaB = SafeACos(b.cosTheta_o);
    const float thetaD = SafeACos(Dot(a.w, b.w));
    if (std::min(thetaD + thetaB, kPi) <= thetaA) {
        u.w = a.w;
        u.cosTheta_o = a.cosTheta_o;
        return u;
    }
    if (std::min(thetaD + thetaA, kPi) <= thetaB) {
        u.w = b.w;
        u.cosTheta_o = b.cosTheta_o;
        return u;
    }
    const float thetaO = (thetaA + thetaD + thetaB) / 2;
    const Vec3f axis = Cross(a.w, b.w);
    if (thetaO >= kPi || LengthSquared(axis) == 0) {
        u.w = a.w;
        u.cosTheta_o = -1;
        return u;
    }
    u.w = Normalize(RotatePerpendicular(a.w, Normalize(axis), thetaO - thetaA));
    u.cosTheta_o = std::cos(thetaO);
    return u;
}

LightBVH::LightBVH(const std::vector<const Light *> &lights,
                   const std::vector<double> &infiniteImportance) {
    std::vector<Part> parts;
    std::vector<LightPartBounds> lb;
    slot_.assign(lights.size() + 1, 0);
    for (size_t i = 0; i < lights.size(); ++i) {
        lb.clear();
        lights[i]->Bounds(&lb);
        if (lb.empty() && !lights[i]->IsArea()) infinite_.push_back(int(i));
        int64_t slots = 1;
        for (const LightPartBounds &b : lb) {
            slots = std::max<int64_t>(slots, int64_t(b.prim) + 1);
            if (b.lb.phi > 0 && std::isfinite(b.lb.phi)) parts.push_back({int(i), b.prim, b.lb});
        }
        slot_[i + 1] = slot_[i] + slots;
    }
    if (!parts.empty()) {
        nodes_.reserve(2 * parts.size() - 1);
        Build(parts, 0, parts.size(), 1);
        parts_ = std::move(parts);
    }
    leafOfPart_.assign(parts_.size(), -1);
    parent_.assign(nodes_.size(), -1);
    for (size_t i = 0; i < nodes_.size(); ++i) {
        const Node &nd = nodes_[i];
        if (nd.IsLeaf()) {
            leafOfPart_[size_t(nd.part)] = int32_t(i);
        } else {
            parent_[i + 1] = int32_t(i);
            parent_[size_t(nd.second)] = int32_t(i);
        }
    }
    if (infiniteImportance.size() == lights.size()) {
        double run = 0;
        for (int i : infinite_) {
            const double w = infiniteImportance[size_t(i)];
            if (!(w > 0) || !std::isfinite(w)) {
                infiniteCdf_.clear();
                break;
            }
            infiniteCdf_.push_back(run += w);
        }
    }
    partIndex_.assign(size_t(slot_.back()), -1);
    for (size_t i = 0; i < parts_.size(); ++i)
        partIndex_[size_t(slot_[size_t(parts_[i].light)] + std::max(parts_[i].prim, 0))] =
            int32_t(i);
}

// Builds the subtree of parts [begin, end) top-down, splitting where the surface area
// orientation heuristic is least over 12 bins per axis of the parts' centres; returns its root.
int LightBVH::Build(std::vector<Part> &parts, size_t begin, size_t end, int depth) {
    depth_ = std::max(depth_, depth);
    const int index = int(nodes_.size());
    nodes_.emplace_back();
    if (end - begin == 1) {
        nodes_[size_t(index)].lb = CompactLightBounds(parts[begin].lb);
        nodes_[size_t(index)].part = int32_t(begin);
        return index;
    }
    LightBounds all;
    Bounds3f centres;
    for (size_t i = begin; i < end; ++i) {
        all = Union(all, parts[i].lb);
        centres.Expand(parts[i].lb.bounds.Center());
    }
    const Vec3f extent = centres.Diagonal();
    const float maxExtent = MaxComponent(all.bounds.Diagonal());
    constexpr int kBins = 12;
    float bestCost = INFINITY;
    int bestAxis = -1, bestBin = -1;
    auto binOf = [&](const Part &pt, int axis) {
        const float t = (pt.lb.bounds.Center()[axis] - centres.pMin[axis]) / extent[axis];
        return std::clamp(int(t * kBins), 0, kBins - 1);
    };
    // Splits that deep are unbalanced: fall back to halves by count to bound the depth.
    if (depth < 64) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0)) continue;
            LightBounds bins[kBins];
            for (size_t i = begin; i < end; ++i) {
                LightBounds &b = bins[binOf(parts[i], axis)];
                b = Union(b, parts[i].lb);
            }
            const float kr = maxExtent / std::max(all.bounds.Diagonal()[axis], 1e-30f);
            auto cost = [&](const LightBounds &b) {
                return b.phi * OrientationMeasure(b.cosTheta_o, b.cosTheta_e) *
                       SurfaceArea(b.bounds) * kr;
            };
            LightBounds below[kBins];
            for (int i = 0; i < kBins; ++i)
                below[i] = Union(i > 0 ? below[i - 1] : LightBounds{}, bins[i]);
            LightBounds above;
            for (int i = kBins - 1; i > 0; --i) {
                above = Union(above, bins[i]);
                if (!(below[i - 1].phi > 0) || !(above.phi > 0)) continue;
                const float c = cost(below[i - 1]) + cost(above);
                if (c < bestCost) {
                    bestCost = c;
                    bestAxis = axis;
                    bestBin = i;
                }
            }
        }
    }
    size_t mid;
    if (bestAxis >= 0 && bestCost > 0 && std::isfinite(bestCost)) {
        mid = size_t(std::partition(parts.begin() + long(begin), parts.begin() + long(end),
                                    [&](const Part &pt) { return binOf(pt, bestAxis) < bestBin; }) -
                     parts.begin());
    } else {
        // No useful split (coincident parts, or costs all zero): halves along the widest axis.
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (extent[a] > extent[axis]) axis = a;
        mid = (begin + end) / 2;
        std::nth_element(parts.begin() + long(begin), parts.begin() + long(mid),
                         parts.begin() + long(end), [&](const Part &x, const Part &y) {
                             return x.lb.bounds.Center()[axis] < y.lb.bounds.Center()[axis];
                         });
    }
    if (mid == begin || mid == end) mid = (begin + end) / 2;
    Build(parts, begin, mid, depth + 1);
    const int second = Build(parts, mid, end, depth + 1);
    nodes_[size_t(index)].second = second;
    nodes_[size_t(index)].lb = CompactLightBounds(all);
    return index;
}

double LightBVH::InfiniteShare(const Vec3f &p, const Vec3f &n) const {
    if (infinite_.empty()) return 0;
    if (nodes_.empty()) return 1;
    if (infiniteCdf_.empty()) {
        const double count = double(infinite_.size());
        return count / (count + 1);
    }
    const double root = nodes_[0].lb.Importance(p, n);
    if (!(root > 0)) return 1;  // no part can light p
    // Half by importance, half even.
    const double sum = infiniteCdf_.back();
    return 0.25 + 0.5 * (sum / (sum + root));
}

double LightBVH::InfiniteProb(size_t k) const {
    if (infiniteCdf_.empty()) return 1.0 / double(infinite_.size());
    return (infiniteCdf_[k] - (k > 0 ? infiniteCdf_[k - 1] : 0.0)) / infiniteCdf_.back();
}

LightPick LightBVH::Sample(float u, const Vec3f &p, const Vec3f &n) const {
    LightPick pick;
    const double pInf = InfiniteShare(p, n);
    if (u < pInf) {
        const double v = double(u) / pInf;
        size_t k;
        if (infiniteCdf_.empty()) {
            k = std::min(size_t(v * double(infinite_.size())), infinite_.size() - 1);
        } else {
            const double x = v * infiniteCdf_.back();
            k = size_t(std::upper_bound(infiniteCdf_.begin(), infiniteCdf_.end(), x) -
                       infiniteCdf_.begin());
            k = std::min(k, infinite_.size() - 1);
        }
        pick.light = infinite_[k];
        pick.prob = float(pInf * InfiniteProb(k));
        return pick;
    }
    if (nodes_.empty()) return pick;
    if (nodes_.size() == 1 && pInf == 0) {
        // One part: chosen always (its importance would only tell whether it gives nothing,
        // which its estimate finds anyway).
        pick.light = parts_[0].light;
        pick.prim = parts_[0].prim;
        pick.prob = 1;
        return pick;
    }
    // u, rescaled at each step into the chosen child's interval (in double: a deep tree would
    // otherwise run out of float bits).
    double v =
        pInf > 0 ? std::min((double(u) - pInf) / (1.0 - pInf), 0x1.fffffffffffffp-1) : double(u);
    double pmf = 1 - double(pInf);
    int node = 0;
    if (nodes_[0].IsLeaf() && !(nodes_[0].lb.Importance(p, n) > 0)) return pick;
    while (!nodes_[size_t(node)].IsLeaf()) {
        const Node &nd = nodes_[size_t(node)];
        const double i0 = nodes_[size_t(node) + 1].lb.Importance(p, n);
        const double i1 = nodes_[size_t(nd.second)].lb.Importance(p, n);
        // Both zero where the node's bounds allowed light that its children's do not.
        if (!(i0 > 0) && !(i1 > 0)) return pick;
        const double p0 = i0 / (i0 + i1);
        if (v < p0) {
            v = std::min(v / p0, 0x1.fffffffffffffp-1);
            pmf *= p0;
            node = node + 1;
        } else {
            v = std::min((v - p0) / (1 - p0), 0x1.fffffffffffffp-1);
            pmf *= 1 - p0;
            node = nd.second;
        }
    }
    const Part &part = parts_[size_t(nodes_[size_t(node)].part)];
    pick.light = part.light;
    pick.prim = part.prim;
    pick.prob = float(pmf);
    return pick;
}

float LightBVH::Pmf(const Vec3f &p, const Vec3f &n, int light, int prim) const {
    if (light < 0 || size_t(light) + 1 >= slot_.size()) return 0;
    const double pInf = InfiniteShare(p, n);
    const auto inf = std::find(infinite_.begin(), infinite_.end(), light);
    if (inf != infinite_.end()) return float(pInf * InfiniteProb(size_t(inf - infinite_.begin())));
    const int64_t slot = slot_[size_t(light)] + std::max(prim, 0);
    if (slot >= slot_[size_t(light) + 1]) return 0;
    const int32_t part = partIndex_[size_t(slot)];
    if (part < 0) return 0;
    int node = leafOfPart_[size_t(part)];
    if (node == 0) return pInf == 0 || nodes_[0].lb.Importance(p, n) > 0 ? 1 - pInf : 0;
    double pmf = 1 - double(pInf);
    while (parent_[size_t(node)] >= 0) {
        const int par = parent_[size_t(node)];
        const int sibling = node == par + 1 ? nodes_[size_t(par)].second : par + 1;
        const double in = nodes_[size_t(node)].lb.Importance(p, n);
        const double is = nodes_[size_t(sibling)].lb.Importance(p, n);
        if (!(in > 0)) return 0;
        pmf *= in / (in + is);
        node = par;
    }
    return float(pmf);
}

}  // namespace prism
