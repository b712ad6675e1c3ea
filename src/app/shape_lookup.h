// Which declaration of the scene description a hit belongs to: the Shape directive (or OBJ
// object / glTF primitive), its CSG node or ObjectInstance, and its material. `prism pick` and
// the AOV ids (render/aov.h) number declarations the same way.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/interaction.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace prism {

struct ShapeDeclaration {
    const ShapeDesc *shape = nullptr;        // nullptr: not found (should not happen)
    const CsgDesc *csg = nullptr;            // the CSG node of an operand
    const InstanceDesc *instance = nullptr;  // the ObjectInstance of a hit inside an object
    const ObjectDesc *object = nullptr;      // and its ObjectBegin group
    int shapeId = 0;     // 1-based declaration number (ShapeLookup::Declarations order)
    int materialId = 0;  // 1: the default matte; 2 + index into SceneDescription::materials
    int instanceId = 0;  // 1 + index into SceneDescription::instances; 0 outside instances
};

class ShapeLookup {
  public:
    ShapeLookup(const SceneDescription &desc, const RenderScene &scene);
    // The declaration of the shape `si` hit (si.shape and si.instanceShape).
    ShapeDeclaration Find(const SurfaceInteraction &si) const;
    // Every Shape declaration, in id order (id = index + 1): top-level shapes, then CSG
    // operands, then the shapes of ObjectBegin groups.
    const std::vector<const ShapeDesc *> &Declarations() const { return shapes_; }
    // "sphere at scene.pbrt:12:1" and the like, for manifests and messages.
    std::string ShapeLabel(int shapeId) const;
    std::string MaterialLabel(int materialId) const;
    std::string InstanceLabel(int instanceId) const;

  private:
    const SceneDescription &desc_;
    const RenderScene &scene_;
    std::vector<const ShapeDesc *> shapes_;
    std::unordered_map<const ShapeDesc *, int> idOf_;
    std::unordered_map<int, const ShapeDesc *> byDirective_;  // top-level and CSG operands
    std::unordered_map<const ShapeDesc *, const CsgDesc *> csgOf_;
};

}  // namespace prism
