#include "app/shape_lookup.h"

namespace prism {

ShapeLookup::ShapeLookup(const SceneDescription &desc, const RenderScene &scene)
    : desc_(desc), scene_(scene) {
    for (const ShapeDesc &s : desc.shapes) {
        shapes_.push_back(&s);
        byDirective_[s.directiveIndex] = &s;
    }
    auto addCsg = [&](auto &self, const CsgDesc &node) -> void {
        for (const ShapeDesc &s : node.shapes) {
            shapes_.push_back(&s);
            byDirective_[s.directiveIndex] = &s;
            csgOf_[&s] = &node;
        }
        for (const CsgDesc &child : node.children) self(self, child);
    };
    for (const CsgDesc &node : desc.csg) addCsg(addCsg, node);
    for (const ObjectDesc &obj : desc.objects)
        for (const ShapeDesc &s : obj.shapes) shapes_.push_back(&s);
    for (size_t i = 0; i < shapes_.size(); ++i) idOf_[shapes_[i]] = int(i) + 1;
}

ShapeDeclaration ShapeLookup::Find(const SurfaceInteraction &si) const {
    ShapeDeclaration d;
    if (si.shape < 0 || size_t(si.shape) >= scene_.shapes.size()) return d;
    const ShapeInfo &top = scene_.shapes[size_t(si.shape)];
    const ShapeInfo &info = scene_.Info(si);
    if (top.instance >= 0) {
        d.instance = &desc_.instances[size_t(top.instance)];
        d.instanceId = top.instance + 1;
        d.object = FindObject(desc_, d.instance->object);
        if (d.object && info.directiveIndex >= 0 &&
            size_t(info.directiveIndex) < d.object->shapes.size())
            d.shape = &d.object->shapes[size_t(info.directiveIndex)];
    } else if (auto it = byDirective_.find(info.directiveIndex); it != byDirective_.end()) {
        d.shape = it->second;
        if (auto c = csgOf_.find(d.shape); c != csgOf_.end()) d.csg = c->second;
    }
    if (d.shape) {
        d.shapeId = idOf_.at(d.shape);
        d.materialId = d.shape->material < 0 ? 1 : d.shape->material + 2;
    }
    return d;
}

std::string ShapeLookup::ShapeLabel(int shapeId) const {
    if (shapeId < 1 || size_t(shapeId) > shapes_.size()) return "";
    const ShapeDesc &s = *shapes_[size_t(shapeId) - 1];
    return (s.name.empty() ? s.type : "\"" + s.name + "\" (" + s.type + ")") + " at " +
           s.loc.ToString();
}

std::string ShapeLookup::MaterialLabel(int materialId) const {
    if (materialId == 1) return "default matte";
    if (materialId < 2 || size_t(materialId - 2) >= desc_.materials.size()) return "";
    const MaterialDesc &m = desc_.materials[size_t(materialId - 2)];
    return (m.name.empty() ? m.type : "\"" + m.name + "\" (" + m.type + ")") + " at " +
           m.loc.ToString();
}

std::string ShapeLookup::InstanceLabel(int instanceId) const {
    if (instanceId < 1 || size_t(instanceId - 1) >= desc_.instances.size()) return "";
    const InstanceDesc &i = desc_.instances[size_t(instanceId - 1)];
    return "ObjectInstance \"" + i.object + "\" at " + i.loc.ToString();
}

}  // namespace prism
