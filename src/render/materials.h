// pbrt-v3's material models (materials/*.cpp), one class each, with the pbrt-v4 types that map
// onto them: matte (diffuse), plastic, mirror, glass (dielectric), metal (conductor), uber,
// substrate, translucent (diffusetransmission), mix and
// "" / none / interface (an invisible interface). Their Creates (materials.cpp, beside each
// class) read pbrt's parameters; the constructors take the textures directly (tests).
#pragma once

#include <memory>

#include "render/material.h"

namespace prism {

// Roughness parameters as pbrt gives them, and whether they are remapped to a microfacet alpha
// (pbrt-v3's RoughnessToAlpha).
struct Roughness {
    TexturePtr u, v;
    bool remap = true;
};

// Parameter readers the material Creates share (materials.cpp). "<prefix>roughness" (default
// def), with "<prefix>uroughness"/"<prefix>vroughness" (default 0) overriding it, and
// "remaproughness".
Roughness ReadUVRoughness(const MaterialParams &p, float def, const std::string &prefix = "");
// pbrt-v4's conductor given its normal-incidence reflectance r: eta 1 and this k,
// 2 sqrt(r / (1 - r)) (r clamped below 1), reproduce r at normal incidence.
RGB ConductorKFromReflectance(RGB r);
// False only when the texture is absent or a constant black (after clamping below 0): the lobe
// it scales can never appear.
bool MaybeNonBlack(const TexturePtr &t);
// False only when the (float) texture is absent or the constant 0.
bool MaybeNonZero(const TexturePtr &t);
// The dielectric Fresnel term between indices etaI (outside) and etaT (inside).
Fresnel Dielectric(float etaI, float etaT);
// pbrt-v4's roughness remapping (alpha = sqrt(roughness)) applied to constant roughness, which
// then needs no remapping at hits (pbrt-v4's "conductor", "dielectric" and "subsurface").
void RemapRoughnessAsV4(Roughness &r);
// An index of refraction that must be a value (default 1.5; 0 means 1, no interface, as in
// pbrt-v4): SceneError at the parameter for a texture or a non-positive value.
float ReadConstantIndex(const MaterialParams &p, const char *name);

class MatteMaterial final : public MaterialModel {
  public:
    // sigma: Oren–Nayar's standard deviation in degrees (null or 0: Lambertian).
    explicit MatteMaterial(TexturePtr Kd, TexturePtr sigma = nullptr)
        : Kd_(std::move(Kd)), sigma_(std::move(sigma)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool IsLambertian() const override;
    RGB LambertianKd(const TextureContext &tc) const override {
        return Kd_->Evaluate(tc).Clamped(0.f);
    }
    std::vector<const Texture *> Textures() const override { return {Kd_.get(), sigma_.get()}; }
    const TexturePtr &Kd() const { return Kd_; }

  private:
    TexturePtr Kd_, sigma_;
};

class PlasticMaterial final : public MaterialModel {
  public:
    PlasticMaterial(TexturePtr Kd, TexturePtr Ks, TexturePtr roughness, bool remap)
        : Kd_(std::move(Kd)), Ks_(std::move(Ks)), roughness_(std::move(roughness)), remap_(remap) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectGlossily() const override;
    std::vector<const Texture *> Textures() const override {
        return {Kd_.get(), Ks_.get(), roughness_.get()};
    }

  private:
    TexturePtr Kd_, Ks_, roughness_;
    bool remap_;
};

class MirrorMaterial final : public MaterialModel {
  public:
    explicit MirrorMaterial(TexturePtr Kr) : Kr_(std::move(Kr)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override { return true; }
    std::vector<const Texture *> Textures() const override { return {Kr_.get()}; }

  private:
    TexturePtr Kr_;
};

class GlassMaterial final : public MaterialModel {
  public:
    // Smooth unless a roughness is non-zero (rough glass: microfacet, or Whitted's delta lobes).
    GlassMaterial(TexturePtr Kr, TexturePtr Kt, TexturePtr index, Roughness r)
        : Kr_(std::move(Kr)), Kt_(std::move(Kt)), index_(std::move(index)), r_(std::move(r)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override { return true; }
    bool MayTransmit() const override { return true; }
    bool MayReflectGlossily() const override;
    bool MayTransmitGlossily() const override;
    bool IsRoughGlass() const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override {
        return {Kr_.get(), Kt_.get(), r_.u.get(), r_.v.get(), index_.get()};
    }

  private:
    TexturePtr Kr_, Kt_, index_;
    Roughness r_;
};

// pbrt-v4's "thindielectric": a thin slab of index eta, a delta reflection of the slab's
// reflectance and a delta transmission straight through (no bending) of the rest.
class ThinDielectricMaterial final : public MaterialModel {
  public:
    explicit ThinDielectricMaterial(float eta) : eta_(eta) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override { return eta_ != 1; }
    bool MayTransmit() const override { return true; }

  private:
    float eta_;
};

// pbrt-v3's copper (its default metal, and pbrt-v4's "metal-Cu-eta"/"metal-Cu-k") in RGB.
inline constexpr RGB CopperEta(0.200438f, 0.924033f, 1.10221f);
inline constexpr RGB CopperK(3.91295f, 2.45285f, 2.14219f);

class MetalMaterial final : public MaterialModel {
  public:
    // eta and k: the conductor's complex index of refraction, per channel.
    MetalMaterial(RGB eta, RGB k, Roughness r) : eta_(eta), k_(k), r_(std::move(r)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override;
    bool MayReflectGlossily() const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override { return {r_.u.get(), r_.v.get()}; }
    RGB Eta() const { return eta_; }
    RGB K() const { return k_; }

  private:
    RGB eta_, k_;
    Roughness r_;
};

// pbrt-v3's uber: diffuse, glossy, specular reflection and transmission, and opacity.
// roughness: "roughness", with optional "uroughness"/"vroughness" (null: roughness).
class UberMaterial final : public MaterialModel {
  public:
    struct Params {
        TexturePtr Kd, Ks, Kr, Kt, roughness, uRoughness, vRoughness, index, opacity;
        bool remap = true;
    };
    explicit UberMaterial(Params p) : p_(std::move(p)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override;
    bool MayTransmit() const override;
    bool MayReflectGlossily() const override;
    int MaxParts() const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override {
        return {p_.Kd.get(),         p_.Ks.get(),        p_.Kr.get(),
                p_.Kt.get(),         p_.roughness.get(), p_.uRoughness.get(),
                p_.vRoughness.get(), p_.index.get(),     p_.opacity.get()};
    }

  private:
    Params p_;
};

class SubstrateMaterial final : public MaterialModel {
  public:
    SubstrateMaterial(TexturePtr Kd, TexturePtr Ks, Roughness r)
        : Kd_(std::move(Kd)), Ks_(std::move(Ks)), r_(std::move(r)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectGlossily() const override;
    unsigned LobeNeeds() const override;
    std::vector<const Texture *> Textures() const override {
        return {Kd_.get(), Ks_.get(), r_.u.get(), r_.v.get()};
    }

  private:
    TexturePtr Kd_, Ks_;
    Roughness r_;
};

class TranslucentMaterial final : public MaterialModel {
  public:
    TranslucentMaterial(TexturePtr Kd, TexturePtr Ks, TexturePtr reflect, TexturePtr transmit,
                        TexturePtr roughness, bool remap)
        : Kd_(std::move(Kd)),
          Ks_(std::move(Ks)),
          reflect_(std::move(reflect)),
          transmit_(std::move(transmit)),
          roughness_(std::move(roughness)),
          remap_(remap) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectGlossily() const override;
    bool MayTransmitGlossily() const override;
    std::vector<const Texture *> Textures() const override {
        return {Kd_.get(), Ks_.get(), roughness_.get(), reflect_.get(), transmit_.get()};
    }

  private:
    TexturePtr Kd_, Ks_, reflect_, transmit_, roughness_;
    bool remap_;
};

// pbrt-v3's mix: m1's parts weighted by amount and m2's by 1 - amount, per channel.
class MixMaterial final : public MaterialModel {
  public:
    MixMaterial(std::shared_ptr<const Material> m1, std::shared_ptr<const Material> m2,
                TexturePtr amount)
        : m1_(std::move(m1)), m2_(std::move(m2)), amount_(std::move(amount)) {}
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool MayReflectSpecularly() const override;
    bool MayTransmit() const override;
    bool MayReflectGlossily() const override;
    bool MayTransmitGlossily() const override;
    int MaxParts() const override;
    unsigned LobeNeeds() const override;
    unsigned GeometryNeeds() const override;
    bool TexturesUseDifferentials() const override;

  private:
    std::shared_ptr<const Material> m1_, m2_;
    TexturePtr amount_;
};

// "" / "none" / "interface": no BSDF; rays continue through the surface.
class InterfaceMaterial final : public MaterialModel {
  public:
    void AddParts(BSDF &b, const TextureContext &tc, const RGB &weight) const override;
    bool IsPassThrough() const override { return true; }
};

}  // namespace prism
