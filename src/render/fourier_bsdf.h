// pbrt-v3's Material "fourier": a BSDF tabulated in a ".bsdf" file (Jakob et al. 2014, "A
// Comprehensive Framework for Rendering Layered Materials", in the layout pbrt-v3 reads). For
// each pair of zenith cosines (μi, μo) on a grid the file holds the Fourier coefficients in the
// azimuth difference φ of f·|μi|: f(μi, μo, φ)·|μi| = Σ_k a_k(μi, μo) cos(kφ), in one channel
// (luminance) or three (luminance, red, blue; green is derived). Between grid points the
// coefficients are interpolated by Catmull–Rom splines in both cosines. μi is the cosine of the
// incident direction pointing into the surface (−wi), so reflection has μi·μo < 0.
//
// Sampling draws μi from the spline of the coefficient a_0 (the average over φ) for the given
// μo, by inverting its integral, and φ from the luminance series, by inverting its integral;
// the density is exact for the interpolated table.
#pragma once

#include <string>
#include <vector>

#include "core/color.h"
#include "core/vecmath.h"
#include "render/spline.h"

namespace prism {

class FourierTable {
  public:
    // Parses a .bsdf file's bytes; throws std::runtime_error saying what is wrong (header,
    // version, flags, counts, offsets past the coefficients, unsorted cosines, non-finite
    // values). `name` is for messages.
    static FourierTable Parse(const std::string &bytes, const std::string &name);

    int NumMu() const { return int(mu_.size()); }
    int MaxOrder() const { return mMax_; }
    int NumChannels() const { return nChannels_; }
    float Eta() const { return eta_; }
    const std::vector<float> &Mu() const { return mu_; }

    // The coefficients at (μi, μo) interpolated, per channel (channel c at ak[c * MaxOrder()]);
    // returns the order used, 0 when a cosine is outside the table.
    int Coefficients(float muI, float muO, std::vector<float> *ak) const;
    // ∫ a_0 dμi over the table for μo (spline-interpolated), the sampling density's norm.
    float Total(float muO) const;
    // Samples μi for μo with u; its density per unit μi in *pdf.
    float SampleMu(float muO, float u, float *pdf) const;

  private:
    int mMax_ = 0, nChannels_ = 1;
    float eta_ = 1;
    std::vector<float> mu_;
    std::vector<float> avg_;  // a_0 of each entry: [o * nMu + i]
    std::vector<float> cdf_;  // ∫ from mu[0] to mu[i] of the a_0 spline, per o: [o * nMu + i]
    std::vector<int> offset_, order_;  // per entry: where its coefficients start, how many
    std::vector<float> coeffs_;
};

// Σ_k a_k cos(kφ) for k < m.
float FourierSeries(const float *a, int m, double cosPhi);

struct FourierLobe {
    const FourierTable *table = nullptr;  // the material's; null: no lobe

    bool Active() const { return table != nullptr; }
    RGB f(const Vec3f &wo, const Vec3f &wi) const;
    // Samples wi (u.y the zenith, u.x the azimuth); false when nothing can be sampled.
    bool Sample(const Vec3f &wo, Vec2f u, Vec3f *wi, float *pdf) const;
    float Pdf(const Vec3f &wo, const Vec3f &wi) const;
    // The share of light at wo the table scatters (its a_0 integrated), for lobe choice.
    float AlbedoEstimate(const Vec3f &wo) const;
    // The directional albedo ∫ f |cos θi| dωi at wo, per channel: 2π times each channel's a_0
    // integrated over μi (its spline through the grid), transmission scaled as f scales it;
    // not clamped to 1 (a table need not conserve energy). The "albedo" AOV.
    RGB Albedo(const Vec3f &wo) const;
};

}  // namespace prism
