#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace prism {

TriangleMesh::TriangleMesh(const Transform &renderFromObject, bool reverseOrientation,
                           const std::vector<Vec3f> &P, std::vector<uint32_t> indices,
                           const std::vector<Vec3f> &N, std::vector<Vec2f> uv)
    : indices_(std::move(indices)),
      uv_(std::move(uv)),
      flipNormals_(reverseOrientation != renderFromObject.SwapsHandedness()) {
    if (indices_.size() % 3 != 0)
        throw std::invalid_argument("number of vertex indices (" + std::to_string(indices_.size()) +
                                    ") is not a multiple of 3");
    for (uint32_t i : indices_)
        if (i >= P.size())
            throw std::invalid_argument("vertex index " + std::to_string(i) + " out of range (" +
                                        std::to_string(P.size()) + " vertices)");
    if (!N.empty() && N.size() != P.size())
        throw std::invalid_argument("\"N\" has " + std::to_string(N.size()) +
                                    " normals but there are " + std::to_string(P.size()) +
                                    " vertices");
    if (!uv_.empty() && uv_.size() != P.size())
        throw std::invalid_argument("\"uv\" has " + std::to_string(uv_.size()) +
                                    " entries but there are " + std::to_string(P.size()) +
                                    " vertices");
    positions_.resize(3 * P.size() + 1);  // Embree reads 16 bytes past the last float3
    bool identity = renderFromObject.IsIdentity();
    for (size_t i = 0; i < P.size(); ++i) {
        Vec3f w = identity ? P[i] : Vec3f(renderFromObject.Point(Vec3d(P[i])));
        positions_[3 * i] = w.x;
        positions_[3 * i + 1] = w.y;
        positions_[3 * i + 2] = w.z;
    }
    if (!N.empty()) {
        // ReverseOrientation turns the shading normals too (the geometric normal follows them):
        // pbrt-v3 emits from a reversed mesh's other side whether or not it has normals. A
        // transform that swaps handedness does not (its normals stay as transformed).
        double sign = reverseOrientation ? -1.0 : 1.0;
        normals_.resize(N.size());
        for (size_t i = 0; i < N.size(); ++i) {
            Vec3d n = identity ? Vec3d(N[i]) : renderFromObject.Normal(Vec3d(N[i]));
            double len = Length(n);
            normals_[i] = len > 0 ? Vec3f(n * (sign / len)) : Vec3f(0, 0, 0);
        }
    }
}

void TriangleMesh::SetPatches(std::vector<uint32_t> first) {
    for (size_t k = 0; k < first.size(); ++k) {
        const bool ok = k == 0 ? first[0] == 0 : first[k] > first[k - 1];
        if (!ok || first[k] >= NumTriangles())
            throw std::invalid_argument("patch " + std::to_string(k) +
                                        " does not start after the one before it within the " +
                                        std::to_string(NumTriangles()) + " triangles");
    }
    patchFirst_ = std::move(first);
}

void TriangleMesh::SetMotionSteps(const std::vector<Transform> &stepFromStart) {
    stepPositions_.clear();
    stepNormals_.clear();
    for (const Transform &m : stepFromStart) {
        std::vector<float> pos(positions_.size(), 0.f);
        for (size_t i = 0; i + 1 < positions_.size(); i += 3) {
            Vec3f w(m.Point(Vec3d(positions_[i], positions_[i + 1], positions_[i + 2])));
            pos[i] = w.x;
            pos[i + 1] = w.y;
            pos[i + 2] = w.z;
        }
        stepPositions_.push_back(std::move(pos));
        if (normals_.empty()) continue;
        std::vector<Vec3f> nrm(normals_.size());
        for (size_t i = 0; i < normals_.size(); ++i) {
            Vec3d n = m.Normal(Vec3d(normals_[i]));
            double len = Length(n);
            nrm[i] = len > 0 ? Vec3f(n / len) : Vec3f(0, 0, 0);
        }
        stepNormals_.push_back(std::move(nrm));
    }
}

namespace {

// Embree's motion interpolation: the segment of `time` among steps - 1 equal ones, and the
// fraction along it.
inline void MotionSegment(float time, int steps, int *seg, float *f) {
    float ft = time * float(steps - 1);
    int s = std::clamp(int(std::floor(ft)), 0, steps - 2);
    *seg = s;
    *f = ft - float(s);
}

}  // namespace

Vec3f TriangleMesh::PositionAt(uint32_t i, float time) const {
    int seg;
    float f;
    MotionSegment(time, NumTimeSteps(), &seg, &f);
    const float *a = PositionData(seg) + 3 * size_t(i), *b = PositionData(seg + 1) + 3 * size_t(i);
    return {(1 - f) * a[0] + f * b[0], (1 - f) * a[1] + f * b[1], (1 - f) * a[2] + f * b[2]};
}

Vec3f TriangleMesh::NormalAt(uint32_t i, float time) const {
    int seg;
    float f;
    MotionSegment(time, NumTimeSteps(), &seg, &f);
    const Vec3f &a = seg == 0 ? normals_[i] : stepNormals_[size_t(seg - 1)][i];
    const Vec3f &b = stepNormals_[size_t(seg)][i];
    return a * (1 - f) + b * f;
}

Bounds3f TriangleMesh::RenderBounds() const {
    Bounds3f b;
    for (size_t i = 0; i + 1 < positions_.size(); i += 3)
        b.Expand(Vec3f(positions_[i], positions_[i + 1], positions_[i + 2]));
    return b;
}

namespace {

// The unit normal (p1-p0) x (p2-p0), flipped if asked; zero for degenerate triangles.
inline Vec3f UnitNormal(const Vec3f &p0, const Vec3f &p1, const Vec3f &p2, bool flip) {
    Vec3f e1 = p1 - p0, e2 = p2 - p0;
    // In float, each component of e1 x e2 is off by at most ~2 ulp of |e1| |e2|, so the unit
    // normal is off by ~2 ulp / sin(angle between the edges). Where that angle is large
    // (sin >= 1/16: at most 32 ulp, the double result rounded to float is within a few ulp
    // of it) float is enough; slivers take the exact-in-double cross product, whose only
    // rounding is the final one.
    Vec3f nf = Cross(e1, e2);
    float len2 = LengthSquared(nf);
    // (Tiny or huge triangles, where the squares leave float's normal range, take double too.)
    if (len2 >= std::numeric_limits<float>::min() && std::isfinite(len2) &&
        len2 * 256 >= LengthSquared(e1) * LengthSquared(e2)) {
        nf = nf / std::sqrt(len2);
        return flip ? -nf : nf;
    }
    Vec3d n = Cross(Vec3d(e1), Vec3d(e2));
    double len = Length(n);
    if (!(len > 0)) return {0, 0, 0};
    n = n / len;
    return Vec3f(flip ? -n : n);
}

}  // namespace

Vec3f TriangleMesh::GeometricNormal(size_t prim) const {
    const uint32_t *v = Triangle(prim);
    return UnitNormal(Position(v[0]), Position(v[1]), Position(v[2]), flipNormals_);
}

void TriangleMesh::NormalDerivatives(size_t prim, const SurfaceInteraction &si, const Vec3f &n,
                                     const Vec3f *dp, Vec3f *dn, int count) const {
    for (int i = 0; i < count; ++i) dn[i] = Vec3f();
    if (normals_.empty()) return;
    const uint32_t *vi = Triangle(prim);
    const bool moving = !stepPositions_.empty();
    Vec3d p0(moving ? PositionAt(vi[0], si.time) : Position(vi[0])),
        p1(moving ? PositionAt(vi[1], si.time) : Position(vi[1])),
        p2(moving ? PositionAt(vi[2], si.time) : Position(vi[2]));
    Vec3d n0(moving ? NormalAt(vi[0], si.time) : normals_[vi[0]]),
        n1(moving ? NormalAt(vi[1], si.time) : normals_[vi[1]]),
        n2(moving ? NormalAt(vi[2], si.time) : normals_[vi[2]]);
    // Barycentrics (b1, b2) of a point q in the plane: the least-squares solution of
    // e1 b1 + e2 b2 = q - p0 (Gram matrix of the edges); the same solve maps a tangent dp to
    // (db1, db2). The shading normal is N / |N| with N = n0 + b1 (n1 - n0) + b2 (n2 - n0).
    const Vec3d e1 = p1 - p0, e2 = p2 - p0;
    const double d11 = Dot(e1, e1), d12 = Dot(e1, e2), d22 = Dot(e2, e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(std::abs(det) > 0)) return;
    auto solve = [&](const Vec3d &w, double *b1, double *b2) {
        const double w1 = Dot(w, e1), w2 = Dot(w, e2);
        *b1 = (d22 * w1 - d12 * w2) / det;
        *b2 = (d11 * w2 - d12 * w1) / det;
    };
    double b1, b2;
    solve(Vec3d(si.p) - p0, &b1, &b2);
    const Vec3d dn1 = n1 - n0, dn2 = n2 - n0;
    const Vec3d N = n0 + dn1 * b1 + dn2 * b2;
    const double len = Length(N);
    if (!(len > 0) || !std::isfinite(len)) return;
    const Vec3d m = N / len;
    // d(N / |N|) = (I - m m^T) dN / |N|, turned to n's side.
    const double scale = (Dot(m, Vec3d(n)) < 0 ? -1 : 1) / len;
    for (int i = 0; i < count; ++i) {
        double db1, db2;
        solve(Vec3d(dp[i]), &db1, &db2);
        const Vec3d dN = dn1 * db1 + dn2 * db2;
        dn[i] = Vec3f((dN - m * Dot(m, dN)) * scale);
    }
}

SurfaceInteraction TriangleMesh::Interaction(size_t prim, float u, float v, float t,
                                             const Vec3f &rayDir, unsigned needs, float time,
                                             int shape) const {
    const uint32_t *vi = Triangle(prim);
    const bool moving = !stepPositions_.empty();
    Vec3f p0 = moving ? PositionAt(vi[0], time) : Position(vi[0]),
          p1 = moving ? PositionAt(vi[1], time) : Position(vi[1]),
          p2 = moving ? PositionAt(vi[2], time) : Position(vi[2]);
    float b0 = 1 - u - v, b1 = u, b2 = v;
    // Every field is computed into a local and the result is built once, in the caller's
    // object, at the end (a SurfaceInteraction declared up front is zero-filled first: 144
    // bytes per hit, and was then copied out).
    const Vec3f p = p0 * b0 + p1 * b1 + p2 * b2;
    // pbrt-v3 triangle.cpp: gamma7 * sum |b_i p_i|.
    // (A moving mesh's vertices are interpolated here and by Embree, each rounding: more.)
    Vec3f pError = (Abs(p0 * b0) + Abs(p1 * b1) + Abs(p2 * b2)) *
                   (moving ? Gamma<float>(12) : Gamma<float>(7));
    // pbrt-v3 also rejects its own triangle test's hits below that test's error bound in t;
    // Embree has no such test, so a spawned ray must start beyond the error of Embree's. Its
    // test (Moeller-Trumbore in float; Pluecker when ROBUST) takes the origin's side of the
    // plane from dot(Ng, v0 - o) with a float normal Ng = e1 x e2: off by about
    // eps |v0 - o| (4 + 4 |e1| |e2| / |Ng|) as a distance. The bound above is per component and
    // small across a tilted plane whose vertices are far from p, so large triangles got acne
    // (docs/SHAPES.md, "Offset modes"); this isotropic term, added to every component, makes
    // the offset along n at least that error. It grows with the triangle's size, not with |p|.
    {
        Vec3f e1 = p1 - p0, e2 = p2 - p0;
        float ng = Length(Cross(e1, e2));
        // One sqrt: sqrt is monotonic and correctly rounded, so this is the max of the lengths.
        float reach = std::sqrt(
            std::max({LengthSquared(p0 - p), LengthSquared(p1 - p), LengthSquared(p2 - p)}));
        float aspect = ng > 0 ? Length(e1) * Length(e2) / ng : 1;
        pError += Vec3f(1, 1, 1) * (Gamma<float>(8) * reach * (1 + aspect));
    }

    Vec2f uv0(0, 0), uv1(1, 0), uv2(1, 1);
    if (needs != NeedNone && !uv_.empty()) {
        uv0 = uv_[vi[0]];
        uv1 = uv_[vi[1]];
        uv2 = uv_[vi[2]];
    }
    Vec2f uv, uvSecond;
    if (needs & NeedUV) {
        uv = uv0 * b0 + uv1 * b1 + uv2 * b2;
        uvSecond = uv1_.empty() ? uv : uv1_[vi[0]] * b0 + uv1_[vi[1]] * b1 + uv1_[vi[2]] * b2;
    }

    Vec3f n = UnitNormal(p0, p1, p2, flipNormals_);
    if (n == Vec3f(0, 0, 0)) n = Normalize(-rayDir);  // degenerate: never NaN
    Vec3f dpdu, dpdv;
    if (needs & NeedDpdu) {
        // Partial derivatives from the uv parameterization (pbrt-v3 Triangle::Intersect).
        Vec2f duv02 = uv0 - uv2, duv12 = uv1 - uv2;
        Vec3f dp02 = p0 - p2, dp12 = p1 - p2;
        double det = double(duv02.x) * duv12.y - double(duv02.y) * duv12.x;
        if (std::abs(det) < 1e-12) {
            CoordinateSystem(n, &dpdu, &dpdv);
        } else {
            float invdet = float(1 / det);
            dpdu = (dp02 * duv12.y - dp12 * duv02.y) * invdet;
            dpdv = (dp12 * duv02.x - dp02 * duv12.x) * invdet;
        }
    }
    Vec3f ns = n;
    if (!normals_.empty()) {
        Vec3f nsi = moving ? NormalAt(vi[0], time) * b0 + NormalAt(vi[1], time) * b1 +
                                 NormalAt(vi[2], time) * b2
                           : normals_[vi[0]] * b0 + normals_[vi[1]] * b1 + normals_[vi[2]] * b2;
        float len = Length(nsi);
        if (len > 0) {
            ns = nsi / len;
            // pbrt: with shading normals, the geometric normal is turned to agree with them.
            n = FaceForward(n, ns);
        }
    }
    if ((needs & NeedDpdu) && !tangents_.empty()) {
        Vec3f tg = tangents_[vi[0]] * b0 + tangents_[vi[1]] * b1 + tangents_[vi[2]] * b2;
        if (LengthSquared(tg) > 0) {
            dpdu = tg;
            dpdv = bitangents_[vi[0]] * b0 + bitangents_[vi[1]] * b1 + bitangents_[vi[2]] * b2;
        }
    }
    return SurfaceInteraction{.p = p,
                              .pError = pError,
                              .n = n,
                              .ns = ns,
                              .dpdu = dpdu,
                              .dpdv = dpdv,
                              .uv = uv,
                              .uv1 = uvSecond,
                              .wo = Normalize(-rayDir),
                              .t = t,
                              .shape = shape,
                              .prim = int(prim),
                              .time = time};
}

void TriangleMesh::SetTangents(const Transform &renderFromObject, const std::vector<float> &xyzw) {
    const size_t nv = NumVertices();
    if (xyzw.size() != 4 * nv)
        throw std::invalid_argument("\"tangent\" has " + std::to_string(xyzw.size()) +
                                    " values but there are " + std::to_string(nv) +
                                    " vertices (4 each)");
    tangents_.resize(nv);
    std::vector<float> signs(nv);
    for (size_t i = 0; i < nv; ++i) {
        Vec3d t = renderFromObject.Vector(
            Vec3d(double(xyzw[4 * i]), double(xyzw[4 * i + 1]), double(xyzw[4 * i + 2])));
        double len = Length(t);
        tangents_[i] = len > 0 && std::isfinite(len) ? Vec3f(t / len) : Vec3f(0, 0, 0);
        // A transform that swaps handedness mirrors the bitangent too.
        float w = xyzw[4 * i + 3] < 0 ? -1.f : 1.f;
        signs[i] = renderFromObject.SwapsHandedness() ? -w : w;
    }
    FinishTangents(signs);
}

void TriangleMesh::FinishTangents(const std::vector<float> &signs) {
    const size_t nv = NumVertices();
    std::vector<Vec3f> N = normals_;
    if (N.empty()) {
        N.assign(nv, Vec3f(0, 0, 0));
        for (size_t f = 0; f < NumTriangles(); ++f) {
            const uint32_t *v = Triangle(f);
            Vec3f fn = Cross(Position(v[1]) - Position(v[0]), Position(v[2]) - Position(v[0]));
            for (int k = 0; k < 3; ++k) N[v[k]] += fn;
        }
    }
    bitangents_.assign(nv, Vec3f(0, 0, 0));
    for (size_t i = 0; i < nv; ++i) {
        if (!(LengthSquared(N[i]) > 0)) continue;
        bitangents_[i] = Cross(Normalize(N[i]), tangents_[i]) * signs[i];
    }
}

void TriangleMesh::SetUV1(std::vector<Vec2f> uv1) {
    if (!uv1.empty() && uv1.size() != NumVertices())
        throw std::invalid_argument("\"uv1\" has " + std::to_string(uv1.size()) +
                                    " entries but there are " + std::to_string(NumVertices()) +
                                    " vertices");
    uv1_ = std::move(uv1);
}

void TriangleMesh::GenerateTangents(int uvSet) {
    const std::vector<Vec2f> &uvs = uvSet == 1 && !uv1_.empty() ? uv1_ : uv_;
    const size_t nv = NumVertices();
    std::vector<Vec3f> T(nv, Vec3f(0, 0, 0)), B(nv, Vec3f(0, 0, 0)), N(nv, Vec3f(0, 0, 0));
    for (size_t f = 0; f < NumTriangles(); ++f) {
        const uint32_t *v = Triangle(f);
        Vec3f p[3] = {Position(v[0]), Position(v[1]), Position(v[2])};
        Vec2f uv[3] = {Vec2f(0, 0), Vec2f(1, 0), Vec2f(1, 1)};
        if (!uvs.empty())
            for (int k = 0; k < 3; ++k) uv[k] = uvs[v[k]];
        Vec3f e1 = p[1] - p[0], e2 = p[2] - p[0];
        Vec3f fn = Cross(e1, e2);
        if (!(LengthSquared(fn) > 0)) continue;
        Vec2f d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
        float det = d1.x * d2.y - d1.y * d2.x;
        if (det == 0 || !std::isfinite(det)) continue;
        Vec3f dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
        float lu = Length(dpdu), lv = Length(dpdv);
        if (!(lu > 0) || !(lv > 0) || !std::isfinite(lu) || !std::isfinite(lv)) continue;
        dpdu = dpdu / lu;
        dpdv = dpdv / lv;
        fn = Normalize(fn);
        for (int k = 0; k < 3; ++k) {
            Vec3f a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            float la = Length(a), lb = Length(b);
            if (!(la > 0) || !(lb > 0)) continue;
            float angle = std::acos(std::clamp(Dot(a, b) / (la * lb), -1.f, 1.f));
            T[v[k]] += dpdu * angle;
            B[v[k]] += dpdv * angle;
            N[v[k]] += fn * angle;
        }
    }
    tangents_.assign(nv, Vec3f(0, 0, 0));
    std::vector<float> signs(nv, 1.f);
    for (size_t i = 0; i < nv; ++i) {
        Vec3f n = !normals_.empty() ? normals_[i] : N[i];
        if (!(LengthSquared(n) > 0)) continue;
        n = Normalize(n);
        Vec3f t = T[i] - n * Dot(n, T[i]);
        float len = Length(t);
        if (!(len > 0) || !std::isfinite(len)) continue;
        tangents_[i] = t / len;
        signs[i] = Dot(Cross(n, tangents_[i]), B[i]) < 0 ? -1.f : 1.f;
    }
    FinishTangents(signs);
}

}  // namespace prism
