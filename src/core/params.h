// The parameters of one scene directive (an Integrator, later a Material, Texture or
// LightSource) as the class it creates reads them in its own Create. The scene-assembly module
// implements this over scene/'s ParamSet, so render/ reads its parameters without depending on
// scene/ (as geometry/'s ShapeParams does for shapes).
#pragma once

#include <string>

#include "core/error.h"

namespace prism {

class Params {
  public:
    virtual ~Params() = default;
    // The directive, for messages: "integrator \"path\"".
    virtual const std::string &Context() const = 0;
    virtual bool Has(const char *name) const = 0;
    virtual int Int(const char *name, int def) const = 0;
    virtual float Float(const char *name, float def) const = 0;
    virtual bool Bool(const char *name, bool def) const = 0;
    virtual std::string String(const char *name, const std::string &def) const = 0;
    // Where to point a message about `name`: the parameter, else the directive.
    virtual FileLoc Loc(const char *name) const = 0;
    virtual void Warn(const FileLoc &loc, const std::string &message) const = 0;
    // Warns once about each parameter nothing read, with `why` ("Prism's path integrators read
    // maxdepth, rrthreshold and lightsamplestrategy").
    virtual void WarnUnread(const std::string &why) const = 0;
};

}  // namespace prism
