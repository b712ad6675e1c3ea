// Integer pixel rectangle, half-open: covers pixels x in [pMin.x, pMax.x), y in [pMin.y, pMax.y).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/vecmath.h"

namespace prism {

struct Bounds2i {
    Vec2i pMin{0, 0}, pMax{0, 0};

    constexpr Bounds2i() = default;
    constexpr Bounds2i(Vec2i lo, Vec2i hi) : pMin(lo), pMax(hi) {}

    int Width() const { return std::max(0, pMax.x - pMin.x); }
    int Height() const { return std::max(0, pMax.y - pMin.y); }
    Vec2i Diagonal() const { return {Width(), Height()}; }
    int64_t Area() const { return int64_t(Width()) * int64_t(Height()); }
    bool Empty() const { return pMax.x <= pMin.x || pMax.y <= pMin.y; }
    bool Inside(Vec2i p) const {
        return p.x >= pMin.x && p.x < pMax.x && p.y >= pMin.y && p.y < pMax.y;
    }
    bool operator==(const Bounds2i &) const = default;
};

inline Bounds2i Intersect(const Bounds2i &a, const Bounds2i &b) {
    return {{std::max(a.pMin.x, b.pMin.x), std::max(a.pMin.y, b.pMin.y)},
            {std::min(a.pMax.x, b.pMax.x), std::min(a.pMax.y, b.pMax.y)}};
}

}  // namespace prism
