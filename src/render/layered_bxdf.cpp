#include "render/layered_bxdf.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/bsdf.h"
#include "render/layered_interfaces.h"
#include "render/medium.h"

namespace prism {

namespace {

using namespace layered;

// The walk, for a coat over `base` (the layer is two-sided: wo below the surface is mirrored).
template <class Base>
class Walk {
  public:
    Walk(const LayeredLobe &l, const Base &base)
        : l_(l), coat_{l.eta, {l.coatAlphaX, l.coatAlphaY}}, base_(base), phase_(l.g) {}

    RGB f(Vec3f wo, Vec3f wi, TransportMode mode) const {
        if (wo.z == 0 || wi.z == 0) return RGB(0);
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        const Interface<Base> top{&coat_, nullptr}, bottom{nullptr, &base_};
        const bool same = SameHemisphere(wo, wi);
        // Light leaves through the coat when wi is on wo's side, else through the base.
        const Interface<Base> exit = same ? top : bottom, nonExit = same ? bottom : top;
        const float thick = Thickness(), exitZ = same ? thick : 0.f;
        const bool scatters = !l_.albedo.IsBlack();
        const int n = std::max(l_.nSamples, 1);
        RGB sum = same ? top.f(wo, wi, mode) * float(n) : RGB(0);
        WalkRng r(HashDir(wo), HashDir(wi));
        for (int sample = 0; sample < n; ++sample) {
            // Into the layer at wo, and a virtual light's direction into it from wi.
            Scatter wos, wis;
            float uc = r();
            if (!top.Sample(wo, uc, r.Get2(), mode, Transmission, &wos) || !wos.Carries()) continue;
            uc = r();
            if (!exit.Sample(wi, uc, r.Get2(), Flip(mode), Transmission, &wis) || !wis.Carries())
                continue;
            RGB beta = wos.f * (std::abs(wos.wi.z) / wos.pdf);
            float z = thick;
            Vec3f w = wos.wi;
            // Reflection at an interface back into the layer: the walk's new direction.
            const auto reflect = [&](const Interface<Base> &at, Scatter *bs) {
                const float u0 = r();
                if (!at.Sample(-w, u0, r.Get2(), mode, Reflection, bs) || !bs->Carries())
                    return false;
                beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
                w = bs->wi;
                return true;
            };
            for (int depth = 0; depth < l_.maxDepth; ++depth) {
                if (depth > 3 && beta.MaxComponent() < 0.25f) {
                    const float q = std::max(0.f, 1 - beta.MaxComponent());
                    if (r() < q) break;
                    beta = beta / (1 - q);
                }
                if (!scatters) {
                    z = z == thick ? 0.f : thick;
                    beta *= Tr(thick, w);
                } else {
                    const float dz = -std::log(1 - r()) * std::abs(w.z);
                    const float zp = w.z > 0 ? z + dz : z - dz;
                    if (zp == z) continue;
                    if (0 < zp && zp < thick) {
                        // A scattering event in the medium: light from the virtual light...
                        float wt = 1;
                        if (!exit.Specular()) wt = PowerHeuristic(wis.pdf, phase_.p(-w, -wis.wi));
                        sum += beta * l_.albedo * wis.f *
                               (phase_.p(-w, -wis.wi) * wt * Tr(zp - exitZ, wis.wi) / wis.pdf);
                        // ... and a new direction from the phase function.
                        Vec3f wn;
                        const float p = phase_.Sample_p(-w, &wn, r.Get2());
                        if (!(p > 0) || wn.z == 0) continue;
                        beta *= l_.albedo;  // p / pdf = 1
                        w = wn;
                        z = zp;
                        if (((z < exitZ && w.z > 0) || (z > exitZ && w.z < 0)) &&
                            !exit.Specular()) {
                            const RGB fExit = exit.f(-w, wi, mode);
                            if (!fExit.IsBlack()) {
                                const float exitPdf = ExitPdf(exit, w, wi, mode);
                                sum +=
                                    beta * fExit * (Tr(zp - exitZ, w) * PowerHeuristic(p, exitPdf));
                            }
                        }
                        continue;
                    }
                    z = std::clamp(zp, 0.f, thick);
                }
                Scatter bs;
                if (z == exitZ) {
                    // Reflection back into the layer at the exit interface.
                    if (!reflect(exit, &bs)) break;
                    continue;
                }
                // At the other interface: light from the virtual light, then a new direction.
                if (!nonExit.Specular()) {
                    float wt = 1;
                    if (!exit.Specular())
                        wt = PowerHeuristic(wis.pdf, nonExit.Pdf(-w, -wis.wi, mode, All));
                    sum += beta * nonExit.f(-w, -wis.wi, mode) * wis.f *
                           (std::abs(wis.wi.z) * wt * Tr(thick, wis.wi) / wis.pdf);
                }
                if (!reflect(nonExit, &bs)) break;
                if (!exit.Specular()) {
                    const RGB fExit = exit.f(-w, wi, mode);
                    if (!fExit.IsBlack()) {
                        float wt = 1;
                        if (!nonExit.Specular())
                            wt = PowerHeuristic(bs.pdf, ExitPdf(exit, w, wi, mode));
                        sum += beta * fExit * (Tr(thick, bs.wi) * wt);
                    }
                }
            }
        }
        return sum / float(n);
    }

    bool Sample(Vec3f wo, float uc, Vec2f u, TransportMode mode, LayeredLobe::Sample *out) const {
        if (wo.z == 0) return false;
        const bool flip = wo.z < 0;
        if (flip) wo = -wo;
        const Interface<Base> top{&coat_, nullptr}, bottom{nullptr, &base_};
        Scatter bs;
        if (!top.Sample(wo, uc, u, mode, All, &bs) || !bs.Carries()) return false;
        if (!bs.transmission) {
            // Reflected by the coat.
            out->wi = flip ? -bs.wi : bs.wi;
            out->weight = bs.f * (std::abs(bs.wi.z) / bs.pdf);
            out->pdf = bs.pdf;
            out->specular = bs.specular;
            out->transmission = false;
            return true;
        }
        Vec3f w = bs.wi;
        bool specularPath = bs.specular;
        WalkRng r(HashDir(wo), Hash3(uc, u.x, u.y));
        RGB f = bs.f * std::abs(bs.wi.z);
        float pdf = bs.pdf;
        const float thick = Thickness();
        float z = thick;
        const bool scatters = !l_.albedo.IsBlack();
        for (int depth = 0; depth < l_.maxDepth; ++depth) {
            const float rrBeta = f.MaxComponent() / pdf;
            if (depth > 3 && rrBeta < 0.25f) {
                const float q = std::max(0.f, 1 - rrBeta);
                if (r() < q) return false;
                pdf *= 1 - q;
            }
            if (w.z == 0) return false;
            if (scatters) {
                const float dz = -std::log(1 - r()) * std::abs(w.z);
                const float zp = w.z > 0 ? z + dz : z - dz;
                if (zp == z) return false;
                if (0 < zp && zp < thick) {
                    Vec3f wn;
                    const float p = phase_.Sample_p(-w, &wn, r.Get2());
                    if (!(p > 0) || wn.z == 0) return false;
                    f *= l_.albedo * p;
                    pdf *= p;
                    specularPath = false;
                    w = wn;
                    z = zp;
                    continue;
                }
                z = std::clamp(zp, 0.f, thick);
            } else {
                z = z == thick ? 0.f : thick;
                f *= Tr(thick, w);
            }
            const Interface<Base> &at = z == 0 ? bottom : top;
            Scatter is;
            const float ucAt = r();
            if (!at.Sample(-w, ucAt, r.Get2(), mode, All, &is) || !is.Carries()) return false;
            f *= is.f;
            pdf *= is.pdf;
            specularPath = specularPath && is.specular;
            w = is.wi;
            if (is.transmission) {
                // Out of the layer.
                out->transmission = !SameHemisphere(wo, w);
                out->specular = specularPath;
                out->wi = flip ? -w : w;
                out->weight = f * (std::abs(w.z) / pdf);
                out->pdf = pdf;
                return out->weight.IsFinite();
            }
            f *= std::abs(is.wi.z);
        }
        return false;
    }

    float Pdf(Vec3f wo, Vec3f wi, TransportMode mode) const {
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        const int n = std::max(l_.nSamples, 1);
        WalkRng r(HashDir(wi), HashDir(wo));
        float sum = 0;
        if (SameHemisphere(wo, wi)) {
            sum += float(n) * coat_.Pdf(wo, wi, mode, Reflection);
            for (int sample = 0; sample < n; ++sample) {
                // Transmission in through the coat at both ends, reflection at the base (TRT);
                // the bases transmit nothing, so wi below the surface adds nothing.
                Scatter wos, wis;
                float uc = r();
                const bool okO = coat_.Sample(wo, uc, r.Get2(), mode, Transmission, &wos);
                uc = r();
                const bool okI = coat_.Sample(wi, uc, r.Get2(), Flip(mode), Transmission, &wis);
                if (!okO || wos.f.IsBlack() || !(wos.pdf > 0) || !okI || wis.f.IsBlack() ||
                    !(wis.pdf > 0))
                    continue;
                if (coat_.Specular()) {
                    sum += base_.Pdf(-wos.wi, -wis.wi, mode, All);
                    continue;
                }
                Scatter rs;
                uc = r();
                if (!base_.Sample(-wos.wi, uc, r.Get2(), mode, All, &rs) || rs.f.IsBlack() ||
                    !(rs.pdf > 0))
                    continue;
                if (base_.Specular()) {
                    sum += coat_.Pdf(-rs.wi, wi, mode, All);
                    continue;
                }
                // Both rough: the two one-sided estimates combined by MIS.
                const float rPdf = base_.Pdf(-wos.wi, -wis.wi, mode, All);
                sum += PowerHeuristic(wis.pdf, rPdf) * rPdf;
                const float tPdf = coat_.Pdf(-rs.wi, wi, mode, All);
                sum += PowerHeuristic(rs.pdf, tPdf) * tPdf;
            }
        }
        return 0.1f / (4 * float(Pi)) + 0.9f * sum / float(n);
    }

  private:
    // The density that the other next-event strategy (the virtual light's direction wis,
    // sampled from wi through the exit interface) gives the direction w inside the layer, for
    // the MIS weight of a sampled w that leaves towards wi. pbrt-v4 uses the density of wi
    // sampled from w instead, a density over the other direction: the weights of the two
    // strategies then do not sum to 1 and f comes out brighter than the lobe's sampling (3-8%
    // of the albedo of a rough coat; tests/render/layered_bxdf_test.cpp). Its images carry
    // that, so pbrt-v4's form is the default (LayeredLobe::pbrtV4Weights).
    float ExitPdf(const Interface<Base> &exit, const Vec3f &w, const Vec3f &wi,
                  TransportMode mode) const {
        return l_.pbrtV4Weights ? exit.Pdf(-w, wi, mode, Transmission)
                                : exit.Pdf(wi, -w, Flip(mode), Transmission);
    }
    float Thickness() const { return std::max(l_.thickness, std::numeric_limits<float>::min()); }

    const LayeredLobe &l_;
    Coat coat_;
    const Base &base_;
    HenyeyGreenstein phase_;
};

DiffuseBase MakeDiffuse(const LayeredLobe &l) { return {l.reflectance}; }
ConductorBase MakeConductor(const LayeredLobe &l) {
    return {l.conductorEta, l.conductorK, {l.baseAlphaX, l.baseAlphaY}};
}

// Calls fn(walk) with the walk for the lobe's base.
template <class Fn>
auto WithWalk(const LayeredLobe &l, Fn &&fn) {
    if (l.base == LayeredLobe::Base::Conductor) {
        const ConductorBase base = MakeConductor(l);
        return fn(Walk<ConductorBase>(l, base));
    }
    const DiffuseBase base = MakeDiffuse(l);
    return fn(Walk<DiffuseBase>(l, base));
}

}  // namespace

bool LayeredLobe::CoatIsSmooth() const {
    return eta == 1 || std::max(coatAlphaX, coatAlphaY) < SmoothAlpha;
}

bool LayeredLobe::IsSpecular() const {
    return CoatIsSmooth() && base == Base::Conductor &&
           std::max(baseAlphaX, baseAlphaY) < SmoothAlpha && albedo.IsBlack();
}

RGB LayeredLobe::f(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
    if (!Active() || IsSpecular()) return RGB(0);
    return WithWalk(*this, [&](const auto &walk) { return walk.f(wo, wi, mode); });
}

bool LayeredLobe::SampleF(const Vec3f &wo, float uc, Vec2f u, TransportMode mode, Sample *s) const {
    if (!Active()) return false;
    return WithWalk(*this, [&](const auto &walk) { return walk.Sample(wo, uc, u, mode, s); });
}

float LayeredLobe::Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
    if (!Active() || IsSpecular()) return 0;
    return WithWalk(*this, [&](const auto &walk) { return walk.Pdf(wo, wi, mode); });
}

RGB LayeredLobe::SpecularReflectance(const Vec3f &wo) const {
    if (!Active() || !CoatIsSmooth() || wo.z == 0) return RGB(0);
    const float c = std::abs(wo.z);
    const float F = eta == 1 ? 0.f : FrDielectric(c, 1.f, eta);
    if (!IsSpecular()) return RGB(F);
    // Inside: the refracted direction's cosine; each round trip crosses the layer twice
    // (transmittance T each way), reflects at the conductor (Rc) and, to stay in, at the coat
    // from below (F again, by reciprocity), so the series is F + (1 - F)² Rc T² / (1 - F Rc T²).
    const float sin2T = (1 - c * c) / (eta * eta), cT = std::sqrt(std::max(0.f, 1 - sin2T));
    const float T = Tr(std::max(thickness, std::numeric_limits<float>::min()), Vec3f(0, 0, cT));
    const RGB Rc = FrConductor(cT, RGB(1), conductorEta, conductorK) * (T * T);
    RGB r;
    for (int ch = 0; ch < 3; ++ch) r[ch] = F + (1 - F) * (1 - F) * Rc[ch] / (1 - F * Rc[ch]);
    return r;
}

float LayeredLobe::AlbedoEstimate(const Vec3f &wo) const {
    const float c = std::abs(wo.z);
    const float F = FrDielectric(c, 1.f, eta);
    const float b = base == Base::Conductor
                        ? FrConductor(c, RGB(1), conductorEta, conductorK).Average()
                        : reflectance.Average();
    return std::clamp(F + (1 - F) * b, 0.01f, 1.f);
}

}  // namespace prism
