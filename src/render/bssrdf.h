// pbrt-v3's subsurface scattering (Material "subsurface" and "kdsubsurface"): a separable
// BSSRDF S(po, wo, pi, wi) = (1 - Fr(cos θo)) Sp(|po - pi|) Sw(wi). Sp, the radial profile, is
// tabulated by photon beam diffusion (Habel et al. 2013: single scattering plus the
// multiple-scattering dipole integrated over the depth of the beam) for 100 single-scattering
// albedos ρ and 64 optical radii r·σt, and interpolated by Catmull–Rom splines in both; Sw is
// the normalized Fresnel transmittance of the exit. Light entering at po leaves at a point pi
// found by probe rays (render/subsurface.h).
#pragma once

#include <memory>
#include <vector>

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

// The first and second moments of the dielectric Fresnel reflectance, ∫ Fr(η, cos) cos^i
// d(cos) × (i + 1) (d'Eon and Irving's polynomial fits, as pbrt-v3 uses them).
float FresnelMoment1(float eta);
float FresnelMoment2(float eta);

// Photon beam diffusion for a medium of unit extinction: the radiant exitance at radius r of
// its multiple scattering (the dipole integrated over the beam's depth) and of its single
// scattering (below the critical angle), per unit incident flux.
float BeamDiffusionMS(float sigmaS, float sigmaA, float g, float eta, float r);
float BeamDiffusionSS(float sigmaS, float sigmaA, float g, float eta, float r);

// The profile table: profile[i * radii + j] = 2π r_j (SS + MS)(ρ_i, r_j) in optical units
// (σt = 1), rhoEff[i] its integral over r (the albedo light entering sees), profileCdf the
// running integrals of each row.
struct BssrdfTable {
    std::vector<float> rho, radius, profile, rhoEff, profileCdf;
    int NumRho() const { return int(rho.size()); }
    int NumRadius() const { return int(radius.size()); }
    float Profile(int i, int j) const { return profile[size_t(i * NumRadius() + j)]; }
};

// The table for phase asymmetry g and relative index eta, computed once per pair and shared.
std::shared_ptr<const BssrdfTable> BeamDiffusionTable(float g, float eta);

// σa and σs (per unit length) of the medium whose effective albedo is rhoEff and mean free
// path mfp (pbrt-v3 SubsurfaceFromDiffuse: ρ inverted from the table's rhoEff).
void SubsurfaceFromDiffuse(const BssrdfTable &t, const RGB &rhoEff, const RGB &mfp, RGB *sigmaA,
                           RGB *sigmaS);

// Sw: the exit's directional factor for a direction at cosine cosTheta to the exit's shading
// normal, (1 - Fr(cosθ)) / (c π), c = 1 - 2 FresnelMoment1(1/η), which integrates to 1 against
// cosθ over the hemisphere.
float SubsurfaceSw(float cosTheta, float eta);

// The BSSRDF where light enters, at po with shading frame (ss, ts, ns): its radial profile is
// the beam-diffusion table's for the coefficients σa, σs, or (Disney) Burley's normalised
// diffusion R (e^(-r/d) + e^(-r/3d)) / (8π d r) of albedo R and scattering distance d.
class SeparableBssrdf {
  public:
    SeparableBssrdf(const BssrdfTable &table, const Vec3f &po, const Vec3f &ns, const Vec3f &ss,
                    float eta, const RGB &sigmaA, const RGB &sigmaS);
    SeparableBssrdf() = default;  // scatters nothing
    static SeparableBssrdf Disney(const Vec3f &po, const Vec3f &ns, const Vec3f &ss, float eta,
                                  const RGB &R, const RGB &d);

    float Eta() const { return eta_; }
    // The radial profile at distance r (world units), per channel.
    RGB Sr(float r) const;
    RGB Sp(const Vec3f &pi) const { return Sr(Length(po_ - pi)); }
    // A radius drawn from channel ch's profile (over its own integral: rhoEff, R); -1 when the
    // channel does not scatter.
    float SampleSr(int ch, float u) const;
    // The density of SampleSr(ch) at r, per unit area of the plane (2π r already removed).
    float PdfSr(int ch, float r) const;
    // The density per unit area with which Probe's strategies together find the point pi
    // with geometric normal ni (before the choice among the probe's hits).
    float PdfSp(const Vec3f &pi, const Vec3f &ni) const;

    // The probe segment of one sample: an axis (ns with probability 1/2, ss and ts 1/4 each)
    // and a channel from u1, a radius and angle from u2, and the chord along the axis through
    // the sphere that bounds the profile there. False when the sample gives none. *uRest is
    // what remains of u1, uniform in [0, 1), for choosing among the hits.
    bool Probe(float u1, Vec2f u2, Vec3f *from, Vec3f *to, float *uRest) const;

  private:
    SeparableBssrdf(const Vec3f &po, const Vec3f &ns, const Vec3f &ss, float eta);
    // The tabulated profile of channel ch at radius r in world units (*sr, not clamped) and
    // the interpolated effective albedo (*rhoEff, when not null); false outside the table.
    bool TabulatedSr(int ch, float r, double *sr, double *rhoEff) const;
    const BssrdfTable *table_ = nullptr;  // null: the Disney profile
    Vec3f po_, ns_, ss_, ts_;
    float eta_ = 1;
    RGB sigmaT_, rho_;  // tabulated
    RGB R_, d_;         // Disney
};

}  // namespace prism
