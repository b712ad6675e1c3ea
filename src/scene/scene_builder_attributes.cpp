// pbrt-v4's graphics-state directives beyond pbrt-v3's: ColorSpace and Attribute.
//
// ColorSpace "srgb" | "rec2020" | "dci-p3" | "aces2065-1" sets the space the RGB parameters
// that follow are written in (core/color_space.h: mapped to sRGB where they are read), scoped
// by AttributeBegin/End as pbrt-v4's graphics state is; the Film takes the one in effect at
// its directive as its output space.
//
// Attribute: default parameters for the shapes, lights (LightSource and
// AreaLightSource), materials, media or textures that follow in the same attribute scope.
// An entity's own parameter of the same name wins, and a later Attribute of the same name
// replaces an earlier one (pbrt-v4 looks an entity's parameters up before its attributes, the
// last one written first). Attributes are converted where they are written, so their
// locations are the Attribute line's, and they are never reported unused (a "float radius"
// default is no fault of a triangle mesh).
#include <algorithm>
#include <iterator>
#include <utility>

#include "core/memory.h"
#include "scene/scene_builder.h"

namespace prism {

void SceneBuilder::ColorSpace(const std::string &name, const FileLoc &loc) {
    version_.Note(4, "ColorSpace", loc);
    const std::optional<ColorSpaceId> cs = ColorSpaceByName(name);
    if (!cs)
        throw SceneError(loc, "unknown color space " + Quote(name) +
                                  " (expected \"srgb\", \"rec2020\", \"dci-p3\" or "
                                  "\"aces2065-1\")");
    gs_.colorSpace = *cs;
}

void SceneBuilder::Attribute(const std::string &target, ParsedParameterVector params,
                             const FileLoc &loc) {
    version_.Note(4, "Attribute", loc);
    static constexpr std::pair<const char *, AttributeTarget> kTargets[] = {
        {"shape", AttributeTarget::Shape},
        {"light", AttributeTarget::Light},
        {"material", AttributeTarget::Material},
        {"medium", AttributeTarget::Medium},
        {"texture", AttributeTarget::Texture}};
    const auto *found = std::find_if(std::begin(kTargets), std::end(kTargets),
                                     [&](const auto &t) { return target == t.first; });
    if (found == std::end(kTargets))
        throw SceneError(loc, "unknown Attribute target " + Quote(target) +
                                  " (expected \"shape\", \"light\", \"material\", \"medium\" or "
                                  "\"texture\")");
    Observe("Attribute", "", params, loc);
    const ParamSet added = Params(std::move(params));
    std::shared_ptr<const std::vector<Param>> &slot = gs_.attributes[size_t(found->second)];
    ParamSet merged;
    if (slot)
        for (const Param &p : *slot) merged.Add(p);
    for (const Param &p : added.Params()) {
        merged.Add(p);
        if (opts_.budget)
            opts_.budget->Charge(sizeof(Param) + p.numbers.size() * 8 + p.name.size(),
                                 "Attribute " + Quote(target), p.loc);
    }
    auto list = std::make_shared<std::vector<Param>>(merged.Params());
    for (const Param &p : *list) p.lookedUp = true;
    slot = std::move(list);
}

void SceneBuilder::AddAttributes(ParamSet &ps, AttributeTarget target) const {
    const std::shared_ptr<const std::vector<Param>> &list = gs_.attributes[size_t(target)];
    if (!list) return;
    for (const Param &p : *list)
        if (!ps.Has(p.name)) ps.Add(p);
}

}  // namespace prism
