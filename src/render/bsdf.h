// The reflection models of pbrt-v3's Whitted path, as one flat value type per hit:
// a Lambertian (or Oren–Nayar) lobe, a Trowbridge–Reitz microfacet lobe with dielectric or
// conductor Fresnel, and delta reflection/transmission lobes. Mirrors pbrt-v3's BxDFs
// (reflection.cpp, microfacet.cpp) closely so images match the reference renderer.
#pragma once

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

float FrDielectric(float cosThetaI, float etaI, float etaT);
RGB FrConductor(float cosThetaI, const RGB &etaI, const RGB &etaT, const RGB &k);
// pbrt-v3 TrowbridgeReitzDistribution::RoughnessToAlpha.
float RoughnessToAlpha(float roughness);

enum class FresnelKind { None, Dielectric, Conductor };

struct Fresnel {
    FresnelKind kind = FresnelKind::None;
    float etaI = 1, etaT = 1.5f;  // dielectric
    RGB eta, k;                   // conductor (etaI = 1)
    RGB Evaluate(float cosThetaI) const;
};

struct BSDF {
    // Shading frame (ns = z) and the geometric normal that decides reflection vs transmission.
    Vec3f ss, ts, ns, ng;

    // Non-delta lobes, evaluated for light samples.
    RGB kd;                    // Lambertian albedo (f = kd / pi)
    float orenNayarA = 1, orenNayarB = 0;
    bool orenNayar = false;
    RGB kdTransmit;            // diffuse transmission (translucent)
    RGB ks;                    // microfacet reflection scale
    float alphaX = 0, alphaY = 0;
    Fresnel glossyFresnel;

    // Delta lobes, followed by recursion.
    RGB kr;                    // specular reflection scale
    Fresnel specularFresnel;   // None: mirror; Dielectric: glass; Conductor: polished metal
    RGB kt;                    // specular transmission scale
    float eta = 1.5f;          // relative index for transmission

    bool HasNonSpecular() const {
        return !kd.IsBlack() || !ks.IsBlack() || !kdTransmit.IsBlack();
    }
    bool HasSpecularReflection() const { return !kr.IsBlack(); }
    bool HasSpecularTransmission() const { return !kt.IsBlack(); }

    Vec3f ToLocal(const Vec3f &v) const { return {Dot(v, ss), Dot(v, ts), Dot(v, ns)}; }
    Vec3f FromLocal(const Vec3f &v) const { return ss * v.x + ts * v.y + ns * v.z; }
    void SetFrame(const Vec3f &shadingNormal, const Vec3f &dpdu, const Vec3f &geometricNormal);

    // f(wo, wi) for the non-delta lobes (world directions, both pointing away from the surface).
    RGB f(const Vec3f &woWorld, const Vec3f &wiWorld) const;

    // Delta lobes: the direction and weight f·|cos|/pdf of the specular reflection and
    // transmission. Return false when the lobe is absent or carries nothing (e.g. TIR).
    bool SampleSpecularReflection(const Vec3f &woWorld, Vec3f *wi, RGB *weight) const;
    bool SampleSpecularTransmission(const Vec3f &woWorld, Vec3f *wi, RGB *weight) const;
};

}  // namespace prism
