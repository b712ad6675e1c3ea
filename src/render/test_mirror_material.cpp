// Scratch (reverted in a later commit): a material added through docs/ARCHITECTURE.md's
// checklist only, a copy of "mirror" under another name.
#include "core/params.h"
#include "render/bsdf.h"
#include "render/material.h"

namespace prism {

namespace {
class TestMirrorMaterial final : public MaterialModel {
  public:
    explicit TestMirrorMaterial(TexturePtr Kr) : Kr_(std::move(Kr)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override {
        BxDFLobes &l = b.AddPart(weight);
        l.kr = Kr_->Evaluate(tc).Clamped(0.f);
        l.specularFresnel.kind = FresnelKind::None;
    }
    bool MayReflectSpecularly() const override { return true; }
    std::vector<const Texture *> Textures() const override { return {Kr_.get()}; }

  private:
    TexturePtr Kr_;
};
}  // namespace

// Material "testmirror" (material_list.inc). Parameters:
//   Kr  spectrum texture  0.9  reflectance (no Fresnel)
std::shared_ptr<const MaterialModel> CreateTestMirrorMaterial(const MaterialParams &p,
                                                              const FileLoc &) {
    return std::make_shared<TestMirrorMaterial>(p.SpectrumTex("Kr", RGB(0.9f)));
}

}  // namespace prism
