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

RayDifferential ReflectDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, const Vec3f &ns, const Vec3f &wi) {
    const Vec3f &wo = si.wo;
    RayDifferential r;
    r.rxOrigin = si.p + tc.dpdx;
    r.ryOrigin = si.p + tc.dpdy;
    // pbrt-v3 with dn/dx = 0: wi' = wi - dwo + 2 (dwo · ns) ns.
    const Vec3f dwodx = -rd.rxDirection - wo, dwody = -rd.ryDirection - wo;
    r.rxDirection = wi - dwodx + ns * (2 * Dot(dwodx, ns));
    r.ryDirection = wi - dwody + ns * (2 * Dot(dwody, ns));
    return r;
}

RayDifferential RefractDifferential(const SurfaceInteraction &si, const TextureContext &tc,
                                    const RayDifferential &rd, Vec3f ns, const Vec3f &wi,
                                    float eta) {
    const Vec3f &wo = si.wo;
    RayDifferential r;
    r.rxOrigin = si.p + tc.dpdx;
    r.ryOrigin = si.p + tc.dpdy;
    // pbrt-v3: the relative index from wo's side to wi's, with ns turned to wo's side.
    float e = 1 / eta;
    if (Dot(wo, ns) < 0) {
        e = eta;
        ns = -ns;
    }
    const Vec3f dwodx = -rd.rxDirection - wo, dwody = -rd.ryDirection - wo;
    const float dDNdx = Dot(dwodx, ns), dDNdy = Dot(dwody, ns);
    const float cosI = Dot(wo, ns), cosT = AbsDot(wi, ns);
    const float k = cosT > 0 ? e - (e * e * cosI) / cosT : 0.f;
    r.rxDirection = wi - dwodx * e + ns * (k * dDNdx);
    r.ryDirection = wi - dwody * e + ns * (k * dDNdy);
    return r;
}

}  // namespace prism
