#include "geometry/bilinear_patch.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace prism {

namespace {

struct Corners {
    Vec3d p00, p10, p01, p11;
};

Corners PatchCorners(const BilinearMesh &m, size_t patch) {
    const int *v = &m.indices[4 * patch];
    return {Vec3d(m.P[size_t(v[0])]), Vec3d(m.P[size_t(v[1])]), Vec3d(m.P[size_t(v[2])]),
            Vec3d(m.P[size_t(v[3])])};
}

template <class T>
T Bilerp(double u, double v, const T &a00, const T &a10, const T &a01, const T &a11) {
    return (a00 * (1 - v) + a01 * v) * (1 - u) + (a10 * (1 - v) + a11 * v) * u;
}

}  // namespace

void ValidateBilinearMesh(const BilinearMesh &m) {
    if (m.P.empty()) throw PatchParamError("P", "bilinearmesh needs vertex positions \"P\"");
    if (m.indices.empty())
        throw PatchParamError("indices",
                              "bilinearmesh needs \"indices\" (4 per patch) unless \"P\" has "
                              "exactly 4 points, one patch");
    if (m.indices.size() % 4 != 0)
        throw PatchParamError("indices", "bilinearmesh has " + std::to_string(m.indices.size()) +
                                             " vertex indices, not a multiple of 4");
    for (int i : m.indices)
        if (i < 0 || size_t(i) >= m.P.size())
            throw PatchParamError("indices", "bilinearmesh vertex index " + std::to_string(i) +
                                                 " out of range (" + std::to_string(m.P.size()) +
                                                 " vertices)");
    if (!m.N.empty() && m.N.size() != m.P.size())
        throw PatchParamError("N", "bilinearmesh has " + std::to_string(m.N.size()) +
                                       " normals \"N\" for " + std::to_string(m.P.size()) +
                                       " vertices");
    if (!m.uv.empty() && m.uv.size() != m.P.size())
        throw PatchParamError("uv", "bilinearmesh has " + std::to_string(m.uv.size()) +
                                        " \"uv\" for " + std::to_string(m.P.size()) + " vertices");
    for (const Vec3f &p : m.P)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw PatchParamError("P", "bilinearmesh vertex position is not finite");
}

std::vector<int> BilinearSegments(const BilinearMesh &m, double relativeTolerance,
                                  uint64_t maxTriangles) {
    const size_t patches = m.indices.size() / 4;
    std::vector<int> n(patches, 1);
    for (size_t k = 0; k < patches; ++k) {
        const Corners c = PatchCorners(m, k);
        const double twist = Length(c.p00 - c.p10 - c.p01 + c.p11);
        const Vec3d lo = Min(Min(c.p00, c.p10), Min(c.p01, c.p11));
        const Vec3d hi = Max(Max(c.p00, c.p10), Max(c.p01, c.p11));
        const double tol = relativeTolerance * Length(hi - lo);
        if (!(twist > tol * 4)) continue;  // flat, or within the tolerance as two triangles
        const double s = std::ceil(std::sqrt(twist / (4 * tol)));
        n[k] = int(std::min<double>(s, MaxBilinearSegments));
    }
    // Too many triangles: scale every grid down by the same factor (a flat patch stays 1).
    const uint64_t total = BilinearTriangles(n);
    if (total > maxTriangles) {
        const double f = std::sqrt(double(maxTriangles) / double(total));
        for (int &s : n) s = std::max(1, int(std::floor(s * f)));
    }
    return n;
}

uint64_t BilinearTriangles(const std::vector<int> &segments) {
    uint64_t t = 0;
    for (int s : segments) t += 2 * uint64_t(s) * uint64_t(s);
    return t;
}

uint64_t BilinearVertices(const std::vector<int> &segments) {
    uint64_t v = 0;
    for (int s : segments) v += uint64_t(s + 1) * uint64_t(s + 1);
    return v;
}

std::vector<uint32_t> BilinearPatchFirstTriangles(const std::vector<int> &segments) {
    std::vector<uint32_t> first(segments.size());
    uint32_t next = 0;
    for (size_t k = 0; k < segments.size(); ++k) {
        first[k] = next;
        next += uint32_t(2 * segments[k] * segments[k]);
    }
    return first;
}

PatchMesh TessellateBilinearMesh(const BilinearMesh &m, const std::vector<int> &segments) {
    PatchMesh out;
    const size_t patches = m.indices.size() / 4;
    const bool curved = std::any_of(segments.begin(), segments.end(), [](int s) { return s > 1; });
    const bool normals = !m.N.empty() || curved;
    const uint64_t vertices = BilinearVertices(segments);
    out.P.reserve(vertices);
    out.uv.reserve(vertices);
    if (normals) out.N.reserve(vertices);
    out.indices.reserve(3 * BilinearTriangles(segments));
    for (size_t k = 0; k < patches; ++k) {
        const Corners c = PatchCorners(m, k);
        const int *v = &m.indices[4 * k];
        const int n = segments[k];
        const int base = int(out.P.size());
        for (int j = 0; j <= n; ++j) {
            const double pv = double(j) / n;
            for (int i = 0; i <= n; ++i) {
                const double pu = double(i) / n;
                out.P.push_back(Vec3f(Bilerp(pu, pv, c.p00, c.p10, c.p01, c.p11)));
                if (m.uv.empty()) {
                    out.uv.push_back(Vec2f(float(pu), float(pv)));
                } else {
                    const Vec2f &a = m.uv[size_t(v[0])], &b = m.uv[size_t(v[1])],
                                &d = m.uv[size_t(v[2])], &e = m.uv[size_t(v[3])];
                    out.uv.push_back(Vec2f(
                        float(Bilerp(pu, pv, double(a.x), double(b.x), double(d.x), double(e.x))),
                        float(Bilerp(pu, pv, double(a.y), double(b.y), double(d.y), double(e.y)))));
                }
                if (!normals) continue;
                Vec3d nrm;
                if (!m.N.empty()) {
                    nrm = Bilerp(pu, pv, Vec3d(m.N[size_t(v[0])]), Vec3d(m.N[size_t(v[1])]),
                                 Vec3d(m.N[size_t(v[2])]), Vec3d(m.N[size_t(v[3])]));
                } else {
                    const Vec3d dpdu = (c.p10 - c.p00) * (1 - pv) + (c.p11 - c.p01) * pv;
                    const Vec3d dpdv = (c.p01 - c.p00) * (1 - pu) + (c.p11 - c.p10) * pu;
                    nrm = Cross(dpdu, dpdv);
                }
                const double len = Length(nrm);
                out.N.push_back(len > 0 ? Vec3f(nrm / len) : Vec3f(0, 0, 0));
            }
        }
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int a = base + j * (n + 1) + i, b = a + 1, d = a + (n + 1), e = d + 1;
                out.indices.insert(out.indices.end(), {a, b, e, a, e, d});
            }
    }
    return out;
}

}  // namespace prism
