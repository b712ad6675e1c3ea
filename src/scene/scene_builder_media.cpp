// Participating media in the pbrt graphics state (pbrt-v3 api.cpp): MakeNamedMedium defines a
// named medium with the CTM, MediumInterface sets the inside and outside media of the shapes
// that follow (and the camera's, its outside one). Types and parameters are checked when the
// scene is built (assembly/media.cpp).
#include "scene/scene_builder.h"

namespace prism {

void SceneBuilder::MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                                   const FileLoc &loc) {
    MediumDesc m;
    m.name = name;
    Observe("MakeNamedMedium", "", params, loc);
    m.params = Params(std::move(params));
    AddAttributes(m.params, AttributeTarget::Medium);
    m.loc = loc;
    m.worldFromMedium = ctm_;
    const Param *type = m.params.Find("type");
    if (!type || type->type != ParamType::String || type->strings.size() != 1)
        throw SceneError(loc,
                         "MakeNamedMedium " + Quote(name) + " needs a \"string type\" parameter");
    m.type = type->strings[0];
    m.params.MarkUsed("type");
    if (name.empty()) throw SceneError(loc, "MakeNamedMedium needs a non-empty name");
    if (namedMedia_.count(name)) diag_.Warn(loc, "named medium " + Quote(name) + " redefined");
    namedMedia_[name] = int(scene_.media.size());
    scene_.media.push_back(std::move(m));
}

void SceneBuilder::MediumInterface(const std::string &inside, const std::string &outside,
                                   const FileLoc &loc) {
    gs_.mediumInside = inside;
    gs_.mediumOutside = outside;
    gs_.mediumLoc = loc;
}

int SceneBuilder::MediumIndex(const std::string &name, const FileLoc &loc) const {
    if (name.empty()) return -1;
    auto it = namedMedia_.find(name);
    if (it == namedMedia_.end()) throw SceneError(loc, "unknown medium " + Quote(name));
    return it->second;
}

}  // namespace prism
