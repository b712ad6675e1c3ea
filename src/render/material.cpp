#include "render/material.h"

namespace prism {

unsigned MaterialModel::LobeNeeds() const {
    for (const Texture *t : Textures())
        if (t && !t->IsConstant()) return NeedUV;
    return NeedNone;
}

bool MaterialModel::TexturesUseDifferentials() const {
    for (const Texture *t : Textures())
        if (t && t->UsesDifferentials()) return true;
    return false;
}

unsigned Material::TextureNeeds() const {
    if (IsPassThrough()) return NeedNone;
    // Filtered textures read the (u, v) footprint, solved from dpdu and dpdv.
    const bool all = PerturbsShading() || TexturesUseDifferentials();
    return model_->LobeNeeds() | (all ? unsigned(NeedAll) : unsigned(NeedNone));
}

BSDF Material::GetBSDF(const SurfaceInteraction &si, const TextureContext &tc) const {
    BSDF b;
    b.SetFrame(si.ns, si.dpdu, si.n);
    AddParts(b, tc, RGB(1));
    return b;
}

void Material::Prepare() {
    differentials_ = TexturesUseDifferentials();
    fixed_ = false;
    fixedParts_.clear();
    if (IsPassThrough() || ((model_->LobeNeeds() | model_->GeometryNeeds()) & NeedUV)) return;
    // Every texture is constant: the parts do not depend on the hit.
    BSDF b;
    model_->AddParts(b, TextureContext{}, RGB(1));
    for (int i = 0; i < b.NumParts(); ++i) fixedParts_.push_back({b.Weight(i), b.Part(i)});
    fixed_ = true;
}

void Material::AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const {
    if (fixed_) {
        for (const FixedPart &fp : fixedParts_) b.AddPart(weight * fp.weight, fp.lobes);
        return;
    }
    model_->AddParts(b, tc, weight);
}

// The Create functions of material_list.inc, each defined beside its class.
#define PRISM_MATERIAL(name, create) \
    std::shared_ptr<const MaterialModel> create(const MaterialParams &, const FileLoc &);
#include "render/material_list.inc"
#undef PRISM_MATERIAL

namespace {
struct RegisteredMaterial {
    const char *name;
    std::shared_ptr<const MaterialModel> (*create)(const MaterialParams &, const FileLoc &);
};
constexpr RegisteredMaterial Materials[] = {
#define PRISM_MATERIAL(name, create) {name, &create},
#include "render/material_list.inc"
#undef PRISM_MATERIAL
};
}  // namespace

std::shared_ptr<const MaterialModel> CreateMaterialModel(const std::string &type,
                                                         const MaterialParams &params,
                                                         const FileLoc &loc) {
    for (const RegisteredMaterial &r : Materials)
        if (type == r.name) return r.create(params, loc);
    return nullptr;
}

const std::vector<std::string> &MaterialNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const RegisteredMaterial &r : Materials) v.push_back(r.name);
        return v;
    }();
    return names;
}

}  // namespace prism
