// core/params.h's Params over one directive's ParamSet: how the classes of render/ read their
// parameters in their own Create without depending on scene/.
#pragma once

#include <string>

#include "core/params.h"
#include "scene/paramset.h"

namespace prism {

// Base: Params, or an interface that extends it (render/light.h LightParams), whose own
// readers a subclass adds.
template <class Base = Params>
class DirectiveParamsOf : public Base {
  public:
    // context: the directive for messages ("integrator \"path\""); loc: the directive's.
    DirectiveParamsOf(const ParamSet &ps, Diagnostics &diag, std::string context, FileLoc loc)
        : ps_(ps), diag_(diag), context_(std::move(context)), loc_(std::move(loc)) {}
    const std::string &Context() const override { return context_; }
    bool Has(const char *name) const override { return ps_.Find(name) != nullptr; }
    int Int(const char *name, int def) const override { return ps_.GetInt(name, def); }
    float Float(const char *name, float def) const override { return ps_.GetFloat(name, def); }
    bool Bool(const char *name, bool def) const override { return ps_.GetBool(name, def); }
    std::string String(const char *name, const std::string &def) const override {
        return ps_.GetString(name, def);
    }
    FileLoc Loc(const char *name) const override {
        const Param *p = ps_.Find(name);
        return p ? p->loc : loc_;
    }
    void Warn(const FileLoc &loc, const std::string &message) const override {
        diag_.Warn(loc, message);
    }
    void WarnUnread(const std::string &why) const override {
        WarnIgnoredRest(ps_, diag_, context_, why);
    }

  protected:
    const ParamSet &ps_;
    Diagnostics &diag_;
    std::string context_;
    FileLoc loc_;
};
using DirectiveParams = DirectiveParamsOf<>;

}  // namespace prism
