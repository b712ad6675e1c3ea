// pbrt-v4's layered BSDF (Material "coateddiffuse" and "coatedconductor"): a dielectric coat
// over a diffuse or conductor base, with an optional homogeneous scattering layer between the
// two, evaluated, sampled and given a density by a random walk between the two interfaces
// (Guo, Hašan and Zhao 2018, "Position-free Monte Carlo simulation for arbitrary layered
// BSDFs", as the pbrt-v4 book's section 14.3 describes it). Every value is an unbiased
// estimate; the walk's random numbers come from a hash of its arguments, so a value is a pure
// function of the directions (deterministic for any thread count) and the density that light
// sampling asks for at a direction is the one BSDF sampling reported for it.
//
// Directions are local to the shading frame (z up) and point away from the surface; the layer
// is two-sided: a direction below the surface sees the same coat from its side.
#pragma once

#include <cstdint>

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

// pbrt's TransportMode: radiance (paths from the camera) or importance (paths from lights);
// they differ in the radiance scaling of refraction through the coat.
enum class TransportMode : uint8_t { Radiance, Importance };

struct LayeredLobe {
    // Trowbridge–Reitz alphas below this are a smooth (delta) surface (pbrt-v4's
    // EffectivelySmooth).
    static constexpr float SmoothAlpha = 1e-3f;
    enum class Base : uint8_t { None, Diffuse, Conductor };
    Base base = Base::None;  // None: no layered lobe in this part
    // The coat: a dielectric interface of index eta (1: index-matched, no Fresnel reflection)
    // with Trowbridge–Reitz alphas (below 1e-3: smooth, a delta reflection).
    float eta = 1.5f;
    float coatAlphaX = 0, coatAlphaY = 0;
    // The base: Lambertian reflectance, or a conductor's eta and k relative to the coat (pbrt-v4
    // divides both by the coat's index) with its own alphas.
    RGB reflectance;
    RGB conductorEta, conductorK;
    float baseAlphaX = 0, baseAlphaY = 0;
    // The layer between: thickness (in mean free paths of a medium of extinction 1), the
    // medium's single-scattering albedo (black: it absorbs, exp(-thickness/|cos|) per crossing,
    // and never scatters) and Henyey–Greenstein g.
    float thickness = 0.01f;
    RGB albedo;
    float g = 0;
    int maxDepth = 10;  // interface and medium events per walk
    int nSamples = 1;   // walks averaged per evaluation
    // f's MIS weights as pbrt-v4 computes them (its images' parity; biased bright by a few
    // percent, see ExitPdf in layered_bxdf.cpp) or consistent with SampleF (false).
    bool pbrtV4Weights = true;

    bool Active() const { return base != Base::None; }
    // A smooth coat over a polished conductor: every path through the layer is specular, so the
    // lobe has no non-delta part (f and Pdf are 0; Sample gives delta directions).
    bool IsSpecular() const;
    // The coat alone is specular: its reflection is a delta lobe that Sample gives.
    bool CoatIsSmooth() const;

    // f(wo, wi): an unbiased estimate of the non-delta part.
    RGB f(const Vec3f &wo, const Vec3f &wi, TransportMode mode = TransportMode::Radiance) const;

    struct Sample {
        Vec3f wi;
        RGB weight;     // f·|cos θi| / pdf of the sampled path (an unbiased ratio)
        float pdf = 0;  // the path's density, proportional to the direction's; use Pdf for MIS
        bool specular = false;      // every event on the path was a delta one
        bool transmission = false;  // wi is on the other side of the surface from wo
    };
    // Samples wi by a walk through the layers driven by (uc, u) and the hash of wo; false when
    // the walk ends inside (Russian roulette, maxDepth, absorption) — the ratio of the walks
    // that leave stays unbiased.
    bool SampleF(const Vec3f &wo, float uc, Vec2f u, TransportMode mode, Sample *s) const;

    // An estimate of the density of SampleF's non-delta directions, mixed 9:1 with the uniform
    // density 1/(4π) as pbrt-v4 does (so it is positive wherever f may be).
    float Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode = TransportMode::Radiance) const;

    // The delta part's reflectance at wo (mirror direction; 0 when the coat is rough): the
    // coat's Fresnel reflection, and over a polished conductor in a non-scattering layer every
    // path that bounces between the two interfaces, summed in closed form (what the integrators
    // that follow delta lobes apart from the rest, Whitted and directlighting, trace).
    RGB SpecularReflectance(const Vec3f &wo) const;

    // A cheap estimate of the share of light at wo the lobe reflects, for choosing it among a
    // BSDF's other lobes.
    float AlbedoEstimate(const Vec3f &wo) const;
};

}  // namespace prism
