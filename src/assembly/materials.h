// Material directives → render/ materials (pbrt-v3 and v4 names, approximations in
// docs/MATERIALS.md). Shapes ask for their material here: a shape's own parameters may override
// its material's (pbrt), which then makes a material of its own.
#pragma once

#include <memory>
#include <vector>

#include "assembly/build_context.h"

namespace prism {

class MaterialBuilder : BuildStep {
  public:
    // Adds material 0, pbrt's default (matte, Kd 0.5), to ctx.scene.
    explicit MaterialBuilder(BuildContext &ctx);
    // The RenderScene material index for a shape; materials are created when first used.
    int MaterialForShape(const ShapeDesc &s);

  private:
    class SceneMaterialParams;
    friend class SceneMaterialParams;
    // Each material through its model's Create (render/material_list.inc).
    Material MakeMaterial(const MaterialDesc &m, int descIndex, const ParamSet *shapeParams,
                          bool *usedShape, int depth = 0);
    int ResolveNamedMaterial(const std::string &name, int from) const;
    std::shared_ptr<const Material> NamedMaterialRef(const std::string &name, int from,
                                                     const FileLoc &loc, int depth);
    void ShadingPerturbation(Material &mat, const SceneMaterialParams &mp, const MaterialDesc &m);

    std::vector<int> sharedMaterial_;  // desc material index → scene material index (-1: not yet)
    // Named materials referenced by mix materials, built once each (by desc index); the state
    // detects reference cycles: 0 not built, 1 being built, 2 built.
    std::vector<std::shared_ptr<const Material>> namedMaterialCache_;
    std::vector<char> namedMaterialState_;
};

}  // namespace prism
