// The reflection models of pbrt-v3's Whitted path: Lambertian (or Oren–Nayar) reflection and
// transmission, Trowbridge–Reitz microfacet reflection and transmission, the Ashikhmin–Shirley
// FresnelBlend lobe, and delta reflection/transmission. Mirrors pbrt-v3's BxDFs
// (reflection.cpp, microfacet.cpp) closely so images match the reference renderer.
#pragma once

#include <new>

#include "core/color.h"
#include "core/vecmath.h"
#include "render/disney_bxdf.h"
#include "render/fourier_bsdf.h"
#include "render/hair_bxdf.h"
#include "render/layered_bxdf.h"

namespace prism {

float FrDielectric(float cosThetaI, float etaI, float etaT);
RGB FrConductor(float cosThetaI, const RGB &etaI, const RGB &etaT, const RGB &k);
// pbrt-v3 TrowbridgeReitzDistribution::RoughnessToAlpha.
float RoughnessToAlpha(float roughness);

// Schlick: F = f0 + (f90 - f0)(1 - cos)^5 per channel (glTF's metallic-roughness model).
// ThinDielectric: a slab of index etaT with parallel faces (pbrt-v4's thindielectric): the
// reflectance R' = R + T² R / (1 - R²) of every bounce inside it (R the single face's Fresnel
// term, T = 1 - R); it transmits 1 - R' straight through.
enum class FresnelKind { None, Dielectric, Conductor, Schlick, ThinDielectric };

// Schlick's approximation with a colour at normal incidence f0 and at grazing incidence f90.
RGB FrSchlick(float cosTheta, const RGB &f0, const RGB &f90);

struct Fresnel {
    FresnelKind kind = FresnelKind::None;
    float etaI = 1, etaT = 1.5f;  // dielectric
    RGB eta, k;                   // conductor (etaI = 1)
    RGB f0, f90{1, 1, 1};         // Schlick
    RGB Evaluate(float cosThetaI) const;
};

// The lobes of one material, in the shading frame. A black scale switches a lobe off, so a
// default-constructed value scatters nothing.
struct BxDFLobes {
    // Non-delta lobes, evaluated for light samples.
    RGB kd;  // Lambertian albedo (f = kd / pi)
    float orenNayarA = 1, orenNayarB = 0;
    bool orenNayar = false;
    RGB kdTransmit;                // Lambertian transmission (translucent)
    RGB ks;                        // microfacet reflection scale
    float alphaX = 0, alphaY = 0;  // Trowbridge–Reitz roughness of all glossy lobes
    Fresnel glossyFresnel;
    RGB ksTransmit;          // microfacet transmission scale (translucent)
    float glossyEta = 1.5f;  // its relative index (outside 1, inside glossyEta)
    RGB blendRd, blendRs;    // FresnelBlend (substrate): diffuse and specular reflectance
    bool fresnelBlend = false;
    // glTF metallic-roughness (render/gltf_bsdf.h): kd is then scaled by 1 - max(F_d(v·h)),
    // F_d = FrSchlick(dielectricF0, dielectricF90); thinTransmit is the thin-walled GGX
    // transmission lobe (alphaX/Y, scaled by the same 1 - max(F_d)); coat is the clearcoat
    // weight above this part: every lobe of the part is scaled by 1 - coat·F_c(v·h), F_c =
    // Schlick with f0 0.04 (v·h = cos θo for the delta lobes).
    bool gltfDiffuse = false;
    RGB dielectricF0, dielectricF90;
    RGB thinTransmit;
    float coat = 0;

    // Delta lobes, followed by recursion.
    RGB kr;                   // specular reflection scale
    Fresnel specularFresnel;  // None: mirror; Dielectric: glass; Conductor: polished metal
    RGB kt;                   // specular transmission scale
    float eta = 1.5f;         // relative index for transmission (1: straight through)
    // Rough glass: the Trowbridge–Reitz alphas of kr/kt (0: smooth). WhittedIntegrator follows
    // kr/kt as delta lobes whatever these say (pbrt-v3's "whitted" traces no glossy rays);
    // BSDF::MakeRoughSpecularGlossy turns them into glossy lobes for DistributionIntegrator.
    float roughAlphaX = 0, roughAlphaY = 0;

    // pbrt-v4's layered BSDF (coateddiffuse, coatedconductor), alone in its part: its own delta
    // reflection (a smooth coat) and its stochastic non-delta part. It counts as a diffuse lobe
    // (light samples estimate it; Whitted and distribution trace no rays from it); BSDF::
    // Sample_f samples it by its walk.
    LayeredLobe layered;
    bool HasLayered() const { return layered.Active() && !layered.IsSpecular(); }

    // pbrt's hair fibre model (Material "hair"), alone in its part. Like the layered lobe it
    // counts as a diffuse lobe (light samples estimate it; Whitted and distribution trace no
    // rays from it, as pbrt-v3's Whitted traces none); it reflects and transmits whatever side
    // the geometric normal puts the directions on.
    HairLobe hair;
    // pbrt-v3's tabulated BSDF (Material "fourier"), alone in its part, counted as the hair
    // lobe is: it reflects and transmits by its table, whatever the geometric normal says.
    FourierLobe fourier;
    // pbrt-v3's Disney BSDF (Material "disney"), alone in its part, counted as the hair lobe
    // is; it picks reflection or transmission components by the geometric normal.
    DisneyLobe disney;
    // Where subsurface light leaves (render/subsurface.h), alone in its part: the BSSRDF's
    // directional factor, f = η² Sw(wi) with η this index (0: no lobe), on wo's side of the
    // geometric normal, counted and sampled as a Lambertian lobe.
    float subsurfaceEta = 0;

    bool HasNonSpecular() const {
        return !kd.IsBlack() || !ks.IsBlack() || !kdTransmit.IsBlack() || !ksTransmit.IsBlack() ||
               fresnelBlend || !thinTransmit.IsBlack() || HasLayered() || hair.Active() ||
               fourier.Active() || disney.Active() || subsurfaceEta > 0;
    }
    // Lobes that are sampled by light samples only (Lambertian, Oren–Nayar, diffuse
    // transmission, FresnelBlend's diffuse base) and lobes that glossy rays sample
    // (microfacet reflection and transmission, FresnelBlend's glossy coat).
    bool HasDiffuse() const {
        return !kd.IsBlack() || !kdTransmit.IsBlack() || fresnelBlend || HasLayered() ||
               hair.Active() || fourier.Active() || disney.Active() || subsurfaceEta > 0;
    }
    bool HasGlossy() const {
        return !ks.IsBlack() || !ksTransmit.IsBlack() || fresnelBlend || !thinTransmit.IsBlack();
    }
    // f split into those two sets (f = fDiffuse + fGlossy up to rounding).
    RGB fDiffuse(const Vec3f &wo, const Vec3f &wi, bool reflect) const;
    RGB fGlossy(const Vec3f &wo, const Vec3f &wi, bool reflect) const;
    // f for local directions; `reflect` says whether the geometric normal puts wo and wi on
    // the same side (pbrt BSDF::f picks reflection or transmission lobes with it). The layered
    // lobe ignores it, as pbrt-v4 does (its two-sided coat decides by the shading frame).
    RGB f(const Vec3f &wo, const Vec3f &wi, bool reflect) const;
    // f without the layered lobe.
    RGB fUnlayered(const Vec3f &wo, const Vec3f &wi, bool reflect) const;
};

// One direction sampled from a whole BSDF (BSDF::Sample_f: path and directlighting).
struct BSDFSample {
    Vec3f wi;       // world direction, away from the surface
    RGB f;          // f(wo, wi) (non-delta: every non-delta lobe; delta: the lobe's f)
    float pdf = 0;  // its density (delta lobes: the probability of choosing the lobe)
    RGB weight;     // f |cos θi| / pdf
    bool specular = false;
    bool transmission = false;
    float eta = 1;  // delta transmission: the relative index crossed (pbrt's etaScale)
};

// A surface's scattering at one hit: a shading frame and up to MaxParts weighted sets of lobes.
// Most materials fill one part; mix materials (and uber's opacity) add more. f and the delta
// lobes are linear in the parts, which is how pbrt-v3's MixMaterial scales its BxDFs.
struct BSDF {
    static constexpr int MaxParts = 8;

    // Shading frame (ns = z) and the geometric normal that decides reflection vs transmission.
    Vec3f ss, ts, ns, ng;

    BSDF() {}  // parts are constructed on demand by AddPart (a BSDF is built at every hit)
    BSDF(const BSDF &o) : ss(o.ss), ts(o.ts), ns(o.ns), ng(o.ng), n_(o.n_) {
        for (int i = 0; i < n_; ++i) {
            new (&weight_[i]) RGB(o.weight_[i]);
            new (&parts_[i]) BxDFLobes(o.parts_[i]);
        }
    }
    BSDF &operator=(const BSDF &o) = delete;

    int NumParts() const { return n_; }
    // A new part with no lobes; the caller must not add more than MaxParts (materials check
    // their part count when the scene is built).
    BxDFLobes &AddPart(const RGB &weight = RGB(1));
    // A part copied from `lobes` (a material's prebuilt parts), without first building a
    // default one to assign over: about 200 bytes written once instead of twice per hit.
    void AddPart(const RGB &weight, const BxDFLobes &lobes);
    const BxDFLobes &Part(int i) const { return parts_[i]; }
    BxDFLobes &Part(int i) { return parts_[i]; }
    const RGB &Weight(int i) const { return weight_[i]; }

    bool HasNonSpecular() const {
        for (int i = 0; i < n_; ++i)
            if (parts_[i].HasNonSpecular()) return true;
        return false;
    }

    bool HasDiffuse() const {
        for (int i = 0; i < n_; ++i)
            if (!weight_[i].IsBlack() && parts_[i].HasDiffuse()) return true;
        return false;
    }
    bool HasGlossy() const {
        for (int i = 0; i < n_; ++i)
            if (!weight_[i].IsBlack() && parts_[i].HasGlossy()) return true;
        return false;
    }

    Vec3f ToLocal(const Vec3f &v) const { return {Dot(v, ss), Dot(v, ts), Dot(v, ns)}; }
    Vec3f FromLocal(const Vec3f &v) const { return ss * v.x + ts * v.y + ns * v.z; }
    void SetFrame(const Vec3f &shadingNormal, const Vec3f &dpdu, const Vec3f &geometricNormal);

    // f(wo, wi) for the non-delta lobes (world directions, both pointing away from the surface).
    RGB f(const Vec3f &woWorld, const Vec3f &wiWorld) const;

    // f of the diffuse lobes only (BxDFLobes::HasDiffuse): what light samples estimate when
    // glossy rays sample the glossy lobes (DistributionIntegrator).
    RGB fDiffuse(const Vec3f &woWorld, const Vec3f &wiWorld) const;

    // DistributionIntegrator: rough glass (roughAlpha > 0) becomes microfacet reflection and
    // transmission lobes in place of its delta lobes (pbrt-v3 GlassMaterial). Returns
    // HasGlossy() afterwards.
    bool MakeRoughSpecularGlossy();

    // pbrt-v4's BSDF::Regularize (its path and volpath "regularize"): every Trowbridge–Reitz
    // alpha below 0.3 of a dielectric or conductor lobe, delta ones included (alpha 0), and of
    // a layered lobe's coat and conductor base becomes 2·alpha clamped to [0.1, 0.3]; delta
    // lobes thereby become rough (MakeRoughSpecularGlossy turns them into glossy lobes).
    // Thin dielectrics, mirrors and diffuse lobes are unchanged, as in pbrt-v4.
    void Regularize();

    // Samples the glossy lobes of one part (Cook's distribution ray tracing): a microfacet
    // normal from the Trowbridge–Reitz distribution of normals visible from wo (Heitz 2018),
    // driven by the stratified u; uc chooses reflection or transmission (in proportion to the
    // dielectric Fresnel term) when the part has both. Gives wi and weight = part weight ×
    // f_glossy·|cos θi| / pdf; false when the sample carries nothing.
    bool SampleGlossy(int part, const Vec3f &woWorld, Vec2f u, float uc, Vec3f *wi,
                      RGB *weight) const;

    // Delta lobes of one part: the direction and weight (part weight × f·|cos|/pdf) of the
    // specular reflection and transmission. Return false when the lobe is absent or carries
    // nothing (e.g. TIR).
    bool SampleSpecularReflection(int part, const Vec3f &woWorld, Vec3f *wi, RGB *weight) const;
    bool SampleSpecularTransmission(int part, const Vec3f &woWorld, Vec3f *wi, RGB *weight) const;

    // Importance sampling of every lobe of every part (render/bsdf_sampling.cpp): a lobe is
    // chosen with uc in proportion to its albedo estimate, then sampled with u (cosine-weighted
    // for the diffuse lobes, visible normals for the glossy ones as SampleGlossy, the delta
    // direction for delta lobes). For a non-delta choice, f and pdf cover every non-delta lobe
    // (pbrt-v3 BSDF::Sample_f). withSpecular false: delta lobes are never chosen.
    bool Sample_f(const Vec3f &woWorld, Vec2f u, float uc, bool withSpecular, BSDFSample *s) const;
    // The density with which Sample_f(withSpecular) gives the non-delta direction wi (multiple
    // importance sampling; with delta lobes it includes the probability of not choosing them).
    float Pdf(const Vec3f &woWorld, const Vec3f &wiWorld, bool withSpecular = false) const;

  private:
    int n_ = 0;
    union {
        RGB weight_[MaxParts];
    };
    union {
        BxDFLobes parts_[MaxParts];
    };
};

}  // namespace prism
