// The hair fibre scattering model of pbrt-v3's and pbrt-v4's Material "hair" (Chiang, Bitterli,
// Tappan and Burley 2016, "A Practical and Controllable Hair and Fur Model for Production Path
// Tracing"; the pbrt-v3 book's online hair chapter derives it): a dielectric cylinder of index
// eta whose interior absorbs with sigma_a (per unit fibre radius), with cuticle scales tilted by
// alpha. Light leaves after p internal paths (R: p = 0, TT: 1, TRT: 2, and every longer path
// together as p = 3); each path's share is a longitudinal lobe Mp (a von Mises–Fisher-like
// distribution of variance v_p around the tilted mirror angle) times an attenuation Ap (Fresnel
// and absorption along the path) times an azimuthal lobe Np (a trimmed logistic of scale s
// around the exit azimuth Φ the path's refractions give).
//
// Directions are local to the fibre's frame: x along the fibre (the curve's dpdu), y and z
// across it, z the shading normal. The azimuth φ is measured from y towards z, i.e. positively
// about x; h in [-1, 1] is where the ray meets the fibre's width (pbrt's -1 + 2v), positive on
// the side that positive rotation about x turns the viewer's direction away from. The lobe is
// not confined to a hemisphere: f covers reflection and transmission through the fibre, and it
// is divided by |cos θ| to the shading normal, which the integrators multiply back (the model
// is defined per unit projected solid angle of the fibre, not of a surface).
#pragma once

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

struct HairLobe {
    static constexpr int PMax = 3;  // paths beyond TRT are summed into one isotropic-azimuth term

    float h = 0;        // offset across the fibre, -1 to 1
    float eta = 1.55f;  // the fibre's index of refraction
    RGB sigmaA;         // absorption coefficient inside the fibre (per unit radius)
    float v0 = 0;       // longitudinal variance of R (TT: v0/4, TRT and beyond: 4 v0); 0: no lobe
    float s = 0;        // azimuthal logistic scale
    float sinAlpha = 0, cosAlpha = 1;  // the cuticle scales' tilt

    bool Active() const { return v0 > 0; }

    // The lobe for offset h with longitudinal roughness betaM, azimuthal roughness betaN (both
    // 0 to 1) and scale tilt alpha in degrees, as pbrt parameterises it.
    static HairLobe Make(float h, float eta, const RGB &sigmaA, float betaM, float betaN,
                         float alphaDegrees);
    // sigma_a of a fibre with these eumelanin and pheomelanin concentrations.
    static RGB SigmaAFromConcentration(float eumelanin, float pheomelanin);
    // sigma_a that gives roughly colour c after multiple scattering in a head of hair of
    // azimuthal roughness betaN (Chiang et al.'s fit).
    static RGB SigmaAFromReflectance(const RGB &c, float betaN);

    RGB f(const Vec3f &wo, const Vec3f &wi) const;
    // Samples wi: uc chooses the path p in proportion to its attenuation's luminance and then,
    // rescaled, the azimuth; u the longitudinal angle and its cone azimuth. False when nothing
    // can be sampled (wo along the fibre's axis).
    bool Sample(const Vec3f &wo, float uc, Vec2f u, Vec3f *wi, float *pdf) const;
    float Pdf(const Vec3f &wo, const Vec3f &wi) const;
    // The share of light at wo leaving the fibre (the attenuations summed over p), for choosing
    // the lobe among a BSDF's others.
    float AlbedoEstimate(const Vec3f &wo) const;
    // The directional albedo ∫ f |cos θi| dωi at wo, per channel: the attenuations summed (each
    // path's lobes integrate to 1). The "albedo" AOV.
    RGB Albedo(const Vec3f &wo) const;
};

}  // namespace prism
