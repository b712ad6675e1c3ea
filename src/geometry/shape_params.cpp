#include "geometry/shape_params.h"

#include <cmath>

namespace prism {

float ShapeParams::PositiveFloat(const char *name, float def) const {
    float v = Float(name, def);
    if (!(v > 0) || !std::isfinite(v))
        throw SceneError(Loc(name), Type() + " " + name + " must be positive");
    return v;
}

float ShapeParams::FiniteFloat(const char *name, float def) const {
    float v = Float(name, def);
    if (!std::isfinite(v)) throw SceneError(Loc(name), Type() + " " + name + " must be finite");
    return v;
}

float ShapeParams::PhiMax() const {
    float v = Float("phimax", 360.f);
    if (!(v > 0) || !(v <= 360))
        throw SceneError(Loc("phimax"), Type() + " phimax must be in (0, 360]");
    return v;
}

}  // namespace prism
