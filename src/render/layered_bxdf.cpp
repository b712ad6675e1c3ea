#include "render/layered_bxdf.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/rng.h"
#include "render/bsdf.h"
#include "render/medium.h"
#include "render/microfacet.h"

namespace prism {

namespace {

constexpr float OneMinusEpsilon = 0x1.fffffep-1f;
constexpr float SmoothAlpha = LayeredLobe::SmoothAlpha;

inline bool SameHemisphere(const Vec3f &a, const Vec3f &b) { return a.z * b.z > 0; }
inline Vec3f FaceUp(const Vec3f &v) { return v.z < 0 ? -v : v; }
inline float Sqr(float v) { return v * v; }
inline Vec3f Reflect(const Vec3f &wo, const Vec3f &n) { return -wo + n * (2 * Dot(wo, n)); }
inline TransportMode Flip(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

float PowerHeuristic(float f, float g) {
    const float f2 = f * f, g2 = g * g;
    if (std::isinf(f2)) return 1;
    return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.f;
}

// Transmittance of the layer's medium (extinction 1) over a height dz along w.
float Tr(float dz, const Vec3f &w) {
    if (std::abs(dz) <= std::numeric_limits<float>::min()) return 1;
    return std::exp(-std::abs(dz / w.z));
}

// Snell's law about n (either side): false for total internal reflection. etap: the relative
// index crossed (transmitted side over incident side).
bool Refract(const Vec3f &wi, Vec3f n, float eta, float *etap, Vec3f *wt) {
    float cosI = Dot(n, wi);
    if (cosI < 0) {
        eta = 1 / eta;
        cosI = -cosI;
        n = -n;
    }
    const float sin2T = std::max(0.f, 1 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1) return false;
    const float cosT = std::sqrt(1 - sin2T);
    *wt = -wi / eta + n * (cosI / eta - cosT);
    *etap = eta;
    return true;
}

uint64_t Hash3(float a, float b, float c) {
    const uint64_t h =
        MixBits64((uint64_t(std::bit_cast<uint32_t>(a)) << 32) | std::bit_cast<uint32_t>(b));
    return MixBits64(h ^ (uint64_t(std::bit_cast<uint32_t>(c)) * 0x9e3779b97f4a7c15ull));
}
uint64_t HashDir(const Vec3f &w) { return Hash3(w.x, w.y, w.z); }

// The walk's random numbers, a pure function of the seeds.
class WalkRng {
  public:
    WalkRng(uint64_t a, uint64_t b) : rng_(a, b) {}
    float operator()() { return std::min(rng_.Uniform(), OneMinusEpsilon); }
    Vec2f Get2() {
        const float x = (*this)();
        return {x, (*this)()};
    }

  private:
    PCG32 rng_;
};

// Trowbridge–Reitz normal distribution, as pbrt-v4 uses it for both interfaces.
struct Microfacets {
    float ax, ay;
    bool Smooth() const { return std::max(ax, ay) < SmoothAlpha; }
    float D(const Vec3f &wm) const { return TrowbridgeReitzD(wm, ax, ay); }
    float Lambda(const Vec3f &w) const { return TrowbridgeReitzLambda(w, ax, ay); }
    float G(const Vec3f &wo, const Vec3f &wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }
    // The density of microfacet normals visible from w (either side).
    float VisiblePdf(const Vec3f &w, const Vec3f &wm) const {
        return D(wm) * AbsDot(w, wm) / ((1 + Lambda(w)) * std::abs(w.z));
    }
    Vec3f SampleVisible(const Vec3f &w, Vec2f u) const {
        return TrowbridgeReitzSampleVisible(FaceUp(w), ax, ay, u);
    }
};

// What one interface's sampling gives (pbrt-v4's BSDFSample, f without the cosine).
struct Scatter {
    Vec3f wi;
    RGB f;
    float pdf = 0;
    bool specular = false;
    bool transmission = false;
    bool Carries() const { return !f.IsBlack() && pdf > 0 && wi.z != 0; }
};

enum : unsigned { Reflection = 1, Transmission = 2, All = 3 };

// The coat: pbrt-v4's dielectric BxDF (smooth or rough).
struct Coat {
    float eta;
    Microfacets mf;
    bool Specular() const { return eta == 1 || mf.Smooth(); }

    // The half vector of a reflection or refraction pair on the upper side, or false when the
    // pair is not one (backfacing microfacets are discarded).
    bool HalfVector(const Vec3f &wo, const Vec3f &wi, Vec3f *wm, float *etap) const {
        const float cosO = wo.z, cosI = wi.z;
        *etap = cosI * cosO > 0 ? 1.f : (cosO > 0 ? eta : 1 / eta);
        const Vec3f h = wi * *etap + wo;
        if (cosI == 0 || cosO == 0 || LengthSquared(h) == 0) return false;
        *wm = FaceUp(Normalize(h));
        return !(Dot(*wm, wi) * cosI < 0 || Dot(*wm, wo) * cosO < 0);
    }

    RGB f(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
        if (Specular()) return RGB(0);
        Vec3f wm;
        float etap;
        if (!HalfVector(wo, wi, &wm, &etap)) return RGB(0);
        const float F = FrDielectric(Dot(wo, wm), 1.f, eta);
        if (wo.z * wi.z > 0) return RGB(mf.D(wm) * mf.G(wo, wi) * F / std::abs(4 * wi.z * wo.z));
        const float denom = Sqr(Dot(wi, wm) + Dot(wo, wm) / etap) * wi.z * wo.z;
        float ft = mf.D(wm) * (1 - F) * mf.G(wo, wi) * std::abs(Dot(wi, wm) * Dot(wo, wm) / denom);
        if (mode == TransportMode::Radiance) ft /= Sqr(etap);
        return RGB(ft);
    }

    bool Sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode, unsigned flags,
                Scatter *s) const {
        if (wo.z == 0) return false;
        if (Specular()) {
            const float R = FrDielectric(wo.z, 1.f, eta), T = 1 - R;
            const float pr = (flags & Reflection) ? R : 0.f, pt = (flags & Transmission) ? T : 0.f;
            if (!(pr + pt > 0)) return false;
            s->specular = true;
            if (uc < pr / (pr + pt)) {
                s->wi = Vec3f(-wo.x, -wo.y, wo.z);
                s->f = RGB(R / std::abs(wo.z));
                s->pdf = pr / (pr + pt);
                s->transmission = false;
                return true;
            }
            float etap;
            if (!Refract(wo, Vec3f(0, 0, 1), eta, &etap, &s->wi) || s->wi.z == 0) return false;
            float ft = T / std::abs(s->wi.z);
            if (mode == TransportMode::Radiance) ft /= Sqr(etap);
            s->f = RGB(ft);
            s->pdf = pt / (pr + pt);
            s->transmission = true;
            return true;
        }
        const Vec3f wm = mf.SampleVisible(wo, u);
        const float R = FrDielectric(Dot(wo, wm), 1.f, eta), T = 1 - R;
        const float pr = (flags & Reflection) ? R : 0.f, pt = (flags & Transmission) ? T : 0.f;
        if (!(pr + pt > 0)) return false;
        s->specular = false;
        if (uc < pr / (pr + pt)) {
            const Vec3f wi = Reflect(wo, wm);
            if (!SameHemisphere(wo, wi)) return false;
            s->wi = wi;
            s->pdf = mf.VisiblePdf(wo, wm) / (4 * AbsDot(wo, wm)) * pr / (pr + pt);
            s->f = RGB(mf.D(wm) * mf.G(wo, wi) * R / (4 * wi.z * wo.z));
            s->transmission = false;
            return true;
        }
        float etap;
        Vec3f wi;
        if (!Refract(wo, wm, eta, &etap, &wi) || SameHemisphere(wo, wi) || wi.z == 0) return false;
        const float denom = Sqr(Dot(wi, wm) + Dot(wo, wm) / etap);
        s->wi = wi;
        s->pdf = mf.VisiblePdf(wo, wm) * AbsDot(wi, wm) / denom * pt / (pr + pt);
        float ft = T * mf.D(wm) * mf.G(wo, wi) *
                   std::abs(Dot(wi, wm) * Dot(wo, wm) / (wi.z * wo.z * denom));
        if (mode == TransportMode::Radiance) ft /= Sqr(etap);
        s->f = RGB(ft);
        s->transmission = true;
        return true;
    }

    float Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode, unsigned flags) const {
        if (Specular()) return 0;
        Vec3f wm;
        float etap;
        if (!HalfVector(wo, wi, &wm, &etap)) return 0;
        const float R = FrDielectric(Dot(wo, wm), 1.f, eta), T = 1 - R;
        const float pr = (flags & Reflection) ? R : 0.f, pt = (flags & Transmission) ? T : 0.f;
        if (!(pr + pt > 0)) return 0;
        if (wo.z * wi.z > 0) return mf.VisiblePdf(wo, wm) / (4 * AbsDot(wo, wm)) * pr / (pr + pt);
        const float denom = Sqr(Dot(wi, wm) + Dot(wo, wm) / etap);
        return mf.VisiblePdf(wo, wm) * AbsDot(wi, wm) / denom * pt / (pr + pt);
    }
};

// Lambertian base.
struct DiffuseBase {
    RGB R;
    bool Specular() const { return false; }
    RGB f(const Vec3f &wo, const Vec3f &wi, TransportMode) const {
        return SameHemisphere(wo, wi) ? R * float(InvPi) : RGB(0);
    }
    bool Sample(const Vec3f &wo, float, Vec2f u, TransportMode, unsigned flags, Scatter *s) const {
        if (!(flags & Reflection)) return false;
        const float r = std::sqrt(u.x), phi = 2 * float(Pi) * u.y;
        Vec3f wi(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1 - u.x)));
        if (wo.z < 0) wi.z = -wi.z;
        s->wi = wi;
        s->f = R * float(InvPi);
        s->pdf = std::abs(wi.z) * float(InvPi);
        s->specular = s->transmission = false;
        return true;
    }
    float Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode, unsigned flags) const {
        if (!(flags & Reflection) || !SameHemisphere(wo, wi)) return 0;
        return std::abs(wi.z) * float(InvPi);
    }
};

// Conductor base: polished (a delta reflection) or Trowbridge–Reitz rough.
struct ConductorBase {
    RGB eta, k;
    Microfacets mf;
    bool Specular() const { return mf.Smooth(); }
    RGB F(float cosTheta) const { return FrConductor(cosTheta, RGB(1), eta, k); }
    RGB f(const Vec3f &wo, const Vec3f &wi, TransportMode) const {
        if (!SameHemisphere(wo, wi) || mf.Smooth()) return RGB(0);
        const float cosO = std::abs(wo.z), cosI = std::abs(wi.z);
        Vec3f wm = wi + wo;
        if (cosI == 0 || cosO == 0 || LengthSquared(wm) == 0) return RGB(0);
        wm = Normalize(wm);
        return F(AbsDot(wo, wm)) * (mf.D(wm) * mf.G(wo, wi) / (4 * cosI * cosO));
    }
    bool Sample(const Vec3f &wo, float, Vec2f u, TransportMode, unsigned flags, Scatter *s) const {
        if (!(flags & Reflection) || wo.z == 0) return false;
        s->transmission = false;
        if (mf.Smooth()) {
            s->wi = Vec3f(-wo.x, -wo.y, wo.z);
            s->f = F(std::abs(wo.z)) / std::abs(wo.z);
            s->pdf = 1;
            s->specular = true;
            return true;
        }
        const Vec3f wm = mf.SampleVisible(wo, u);
        const Vec3f wi = Reflect(wo, wm);
        if (!SameHemisphere(wo, wi)) return false;
        const float cosO = std::abs(wo.z), cosI = std::abs(wi.z);
        if (cosI == 0 || cosO == 0) return false;
        s->wi = wi;
        s->pdf = mf.VisiblePdf(wo, wm) / (4 * AbsDot(wo, wm));
        s->f = F(AbsDot(wo, wm)) * (mf.D(wm) * mf.G(wo, wi) / (4 * cosI * cosO));
        s->specular = false;
        return true;
    }
    float Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode, unsigned flags) const {
        if (!(flags & Reflection) || !SameHemisphere(wo, wi) || mf.Smooth()) return 0;
        Vec3f wm = wo + wi;
        if (LengthSquared(wm) == 0) return 0;
        wm = FaceUp(Normalize(wm));
        return mf.VisiblePdf(wo, wm) / (4 * AbsDot(wo, wm));
    }
};

// One of the two interfaces (pbrt-v4's TopOrBottomBxDF).
template <class Base>
struct Interface {
    const Coat *coat;
    const Base *base;
    bool Specular() const { return coat ? coat->Specular() : base->Specular(); }
    RGB f(const Vec3f &wo, const Vec3f &wi, TransportMode m) const {
        return coat ? coat->f(wo, wi, m) : base->f(wo, wi, m);
    }
    bool Sample(const Vec3f &wo, float uc, Vec2f u, TransportMode m, unsigned flags,
                Scatter *s) const {
        return coat ? coat->Sample(wo, uc, u, m, flags, s) : base->Sample(wo, uc, u, m, flags, s);
    }
    float Pdf(const Vec3f &wo, const Vec3f &wi, TransportMode m, unsigned flags) const {
        return coat ? coat->Pdf(wo, wi, m, flags) : base->Pdf(wo, wi, m, flags);
    }
};

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
