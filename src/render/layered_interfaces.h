// The pieces of pbrt-v4's layered BSDF (render/layered_bxdf.cpp) that its random walk
// combines: the two interfaces — the dielectric coat (smooth or Trowbridge–Reitz rough) and the
// Lambertian or conductor base — each with pbrt-v4's f, sampling and density in local
// coordinates, the walk's hashed random numbers, and small helpers. Internal to the walk.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/rng.h"
#include "render/bsdf.h"
#include "render/layered_bxdf.h"
#include "render/microfacet.h"

namespace prism::layered {

inline constexpr float OneMinusEpsilon = 0x1.fffffep-1f;
inline constexpr float SmoothAlpha = LayeredLobe::SmoothAlpha;

inline bool SameHemisphere(const Vec3f &a, const Vec3f &b) { return a.z * b.z > 0; }
inline Vec3f FaceUp(const Vec3f &v) { return v.z < 0 ? -v : v; }
inline float Sqr(float v) { return v * v; }
inline Vec3f Reflect(const Vec3f &wo, const Vec3f &n) { return -wo + n * (2 * Dot(wo, n)); }
inline TransportMode Flip(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

inline float PowerHeuristic(float f, float g) {
    const float f2 = f * f, g2 = g * g;
    if (std::isinf(f2)) return 1;
    return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.f;
}

// Transmittance of the layer's medium (extinction 1) over a height dz along w.
inline float Tr(float dz, const Vec3f &w) {
    if (std::abs(dz) <= std::numeric_limits<float>::min()) return 1;
    return std::exp(-std::abs(dz / w.z));
}

// Snell's law about n (either side): false for total internal reflection. etap: the relative
// index crossed (transmitted side over incident side).
inline bool Refract(const Vec3f &wi, Vec3f n, float eta, float *etap, Vec3f *wt) {
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

inline uint64_t Hash3(float a, float b, float c) {
    const uint64_t h =
        MixBits64((uint64_t(std::bit_cast<uint32_t>(a)) << 32) | std::bit_cast<uint32_t>(b));
    return MixBits64(h ^ (uint64_t(std::bit_cast<uint32_t>(c)) * 0x9e3779b97f4a7c15ull));
}
inline uint64_t HashDir(const Vec3f &w) { return Hash3(w.x, w.y, w.z); }

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

}  // namespace prism::layered
