// The pbrt parameters of one Shape directive as a shape's CreateShape<T> reads them. build/
// implements this over scene/'s ParamSet (assembly/shape_factory.cpp), so geometry/ does not
// depend on scene/.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/vecmath.h"

namespace prism {

class AnalyticShape;

class ShapeParams {
  public:
    virtual ~ShapeParams() = default;
    virtual const std::string &Type() const = 0;  // the shape's name, for messages
    virtual bool Has(const char *name) const = 0;
    virtual float Float(const char *name, float def) const = 0;
    virtual Vec3f Point3(const char *name, Vec3f def) const = 0;
    // Where to point an error about `name`: the parameter, else the Shape directive.
    virtual FileLoc Loc(const char *name) const = 0;

    // Checked readers; they throw SceneError at the parameter ("<type> <name> must be ...").
    float PositiveFloat(const char *name, float def) const;
    float FiniteFloat(const char *name, float def) const;
    float PhiMax() const;  // "phimax" in (0, 360], default 360

    // Runs a constructor, turning its std::invalid_argument (the backstop for invalid
    // combinations) into a SceneError at parameter `blame`.
    template <typename Make>
    std::unique_ptr<AnalyticShape> Construct(const char *blame, Make &&make) const {
        try {
            return make();
        } catch (const std::invalid_argument &e) {
            throw SceneError(Loc(blame), e.what());
        }
    }
};

}  // namespace prism
