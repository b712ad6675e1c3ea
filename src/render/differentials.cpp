#include "render/differentials.h"

#include <cmath>

namespace prism {

namespace {

bool Solve2x2(const float A[2][2], const float B[2], float *x0, float *x1) {
    const float det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    if (std::abs(det) < 1e-10f) return false;
    *x0 = (A[1][1] * B[0] - A[0][1] * B[1]) / det;
    *x1 = (A[0][0] * B[1] - A[1][0] * B[0]) / det;
    return std::isfinite(*x0) && std::isfinite(*x1);
}

}  // namespace

void ComputeDifferentials(const SurfaceInteraction &si, const RayDifferential &rd,
                          TextureContext *tc) {
    const Vec3f &n = si.n, &p = si.p;
    // The offset rays meet the tangent plane Dot(n, x - p) = 0 (relative to p, which keeps
    // the precision of the render's camera-centred coordinates).
    const float tx = -Dot(n, rd.rxOrigin - p) / Dot(n, rd.rxDirection);
    const float ty = -Dot(n, rd.ryOrigin - p) / Dot(n, rd.ryDirection);
    if (!std::isfinite(tx) || !std::isfinite(ty)) {
        tc->dpdx = tc->dpdy = Vec3f();
        tc->dudx = tc->dvdx = tc->dudy = tc->dvdy = 0;
        return;
    }
    tc->dpdx = (rd.rxOrigin - p) + rd.rxDirection * tx;
    tc->dpdy = (rd.ryOrigin - p) + rd.ryDirection * ty;
    // (u, v) from the two coordinates the normal projects least onto.
    int d0, d1;
    if (std::abs(n.x) > std::abs(n.y) && std::abs(n.x) > std::abs(n.z)) {
        d0 = 1;
        d1 = 2;
    } else if (std::abs(n.y) > std::abs(n.z)) {
        d0 = 0;
        d1 = 2;
    } else {
        d0 = 0;
        d1 = 1;
    }
    const float A[2][2] = {{si.dpdu[d0], si.dpdv[d0]}, {si.dpdu[d1], si.dpdv[d1]}};
    const float Bx[2] = {tc->dpdx[d0], tc->dpdx[d1]}, By[2] = {tc->dpdy[d0], tc->dpdy[d1]};
    if (!Solve2x2(A, Bx, &tc->dudx, &tc->dvdx)) tc->dudx = tc->dvdx = 0;
    if (!Solve2x2(A, By, &tc->dudy, &tc->dvdy)) tc->dudy = tc->dvdy = 0;
}

NormalDifferentials FootprintNormalDifferentials(const Accel &accel, const SurfaceInteraction &si,
                                                 const TextureContext &tc, const Vec3f &ns) {
    const Vec3f dp[2] = {tc.dpdx, tc.dpdy};
    Vec3f dn[2];
    accel.NormalDerivatives(si, ns, dp, dn, 2);
    return {dn[0], dn[1]};
}

RayDifferential ReflectDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, const Vec3f &ns,
                                    const NormalDifferentials &dn, const Vec3f &wi) {
    const Vec3f &wo = si.wo;
    RayDifferential r;
    r.rxOrigin = si.p + tc.dpdx;
    r.ryOrigin = si.p + tc.dpdy;
    // wi = -wo + 2 (wo . n) n, differentiated across the footprint:
    // dwi = -dwo + 2 [(wo . n) dn + (dwo . n + wo . dn) n], with dwo = -(d + dd) - wo the
    // change of wo toward the offset ray.
    const Vec3f dwodx = -rd.rxDirection - wo, dwody = -rd.ryDirection - wo;
    const float cosO = Dot(wo, ns);
    const float dDNdx = Dot(dwodx, ns) + Dot(wo, dn.dndx);
    const float dDNdy = Dot(dwody, ns) + Dot(wo, dn.dndy);
    r.rxDirection = wi - dwodx + (dn.dndx * cosO + ns * dDNdx) * 2;
    r.ryDirection = wi - dwody + (dn.dndy * cosO + ns * dDNdy) * 2;
    return r;
}

RayDifferential RefractDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, Vec3f ns, NormalDifferentials dn,
                                    const Vec3f &wi, float eta) {
    const Vec3f &wo = si.wo;
    RayDifferential r;
    r.rxOrigin = si.p + tc.dpdx;
    r.ryOrigin = si.p + tc.dpdy;
    // The relative index e from wo's side to wi's, with ns (and its derivatives) turned to
    // wo's side.
    float e = 1 / eta;
    if (Dot(wo, ns) < 0) {
        e = eta;
        ns = -ns;
        dn.dndx = -dn.dndx;
        dn.dndy = -dn.dndy;
    }
    // wi = -e wo + mu n with mu = e cosI - cosT, cosI = wo . n, cosT = sqrt(1 - e^2 (1 -
    // cosI^2)); so dwi = -e dwo + mu dn + dmu n, dmu = (e - e^2 cosI / cosT) dcosI and
    // dcosI = dwo . n + wo . dn.
    const Vec3f dwodx = -rd.rxDirection - wo, dwody = -rd.ryDirection - wo;
    const float dDNdx = Dot(dwodx, ns) + Dot(wo, dn.dndx);
    const float dDNdy = Dot(dwody, ns) + Dot(wo, dn.dndy);
    const float cosI = Dot(wo, ns), cosT = AbsDot(wi, ns);
    const float mu = e * cosI - cosT;
    const float k = cosT > 0 ? e - (e * e * cosI) / cosT : 0.f;
    r.rxDirection = wi - dwodx * e + dn.dndx * mu + ns * (k * dDNdx);
    r.ryDirection = wi - dwody * e + dn.dndy * mu + ns * (k * dDNdy);
    return r;
}

}  // namespace prism
