#include "render/fourier_material.h"

#include <stdexcept>

#include "render/bsdf.h"

namespace prism {

void FourierMaterial::AddParts(BSDF &b, const TextureContext &, const RGB &weight) const {
    b.AddPart(weight).fourier.table = table_.get();
}

// Material "fourier" (pbrt-v3; material_list.inc). Parameters:
//   bsdffile   string  —  the .bsdf file (relative to the scene); required
// The file is read when the scene is built; one that is missing, truncated or not a .bsdf file
// of the layout pbrt-v3 reads is an error at the parameter.
std::shared_ptr<const MaterialModel> CreateFourierMaterial(const MaterialParams &p,
                                                           const FileLoc &) {
    const std::string bytes = p.ReadFile("bsdffile", "tabulated BSDF");
    try {
        return std::make_shared<FourierMaterial>(std::make_shared<const FourierTable>(
            FourierTable::Parse(bytes, "\"" + p.String("bsdffile", "") + "\"")));
    } catch (const std::runtime_error &e) {
        throw SceneError(p.Loc("bsdffile"), e.what());
    }
}

}  // namespace prism
