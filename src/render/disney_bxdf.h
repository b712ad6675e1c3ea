// pbrt-v3's Disney BSDF (Material "disney"; Burley 2012 and 2015 as pbrt-v3 builds it): a
// Fresnel-modified diffuse lobe (or, thin, a blend with the Hanrahan–Krueger-like "fake
// subsurface" lobe by flatness), retro-reflection and sheen, a Trowbridge–Reitz specular lobe
// with a Schlick/dielectric Fresnel blended by metallic and the separable masking-shadowing
// term, a GTR1 clearcoat, microfacet transmission by specTrans, and (thin) diffuse
// transmission. One lobe of a BSDF part, counted as a diffuse lobe (light samples estimate it;
// Whitted and distribution trace no rays from it, as pbrt-v3's Whitted traces none). Its
// components are sampled by their estimated albedo at wo, each by its own distribution, with
// the mixture's exact density.
#pragma once

#include "core/color.h"
#include "core/vecmath.h"

namespace prism {

struct DisneyLobe {
    bool active = false;
    // Reflection lobes sampled by the cosine: DisneyDiffuse, fake subsurface, retro-reflection
    // (all three with the material's roughness) and sheen.
    RGB diffuse, fakeSS, retro, sheen;
    float roughness = 0;
    // The specular lobe (unscaled, as the reference pbrt-v3 builds it; later pbrt-v3 sources
    // scale it by the colour as well): the Fresnel blend's normal-incidence colour, metallic
    // and index, and the Trowbridge–Reitz alphas.
    RGB cspec0;
    float metallic = 0, eta = 1.5f, ax = 0.001f, ay = 0.001f;
    float clearcoat = 0, clearcoatGloss = 1;
    // Microfacet transmission (scale, alphas; thin: pbrt's height-correlated masking, else the
    // separable one) and Lambertian transmission (thin).
    RGB transmit;
    float tax = 0.001f, tay = 0.001f;
    bool thin = false;
    RGB diffuseTransmit;

    bool Active() const { return active; }
    // f for local directions; `reflect` as BxDFLobes::f (reflection or transmission lobes).
    RGB f(const Vec3f &wo, const Vec3f &wi, bool reflect) const;
    // Samples wi: uc chooses the component, u drives it. False when nothing is sampled.
    bool Sample(const Vec3f &wo, float uc, Vec2f u, Vec3f *wi) const;
    float Pdf(const Vec3f &wo, const Vec3f &wi) const;
    // The estimated share of light at wo it scatters (for choosing among a BSDF's lobes).
    float AlbedoEstimate(const Vec3f &wo) const;
    // Its diffuse colour (the albedo AOV).
    RGB DiffuseColour() const { return diffuse + fakeSS; }
};

}  // namespace prism
