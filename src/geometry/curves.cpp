#include "geometry/curves.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace prism {

size_t CurveSegmentCount(size_t points, int degree, bool bspline) {
    if (degree != 2 && degree != 3) return 0;
    const size_t d = size_t(degree);
    if (bspline) return points > d ? points - d : 0;
    if (points < d + 1 || (points - 1) % d != 0) return 0;
    return (points - 1) / d;
}

namespace {

// The cubic form of the quadratic Bézier (q0, q1, q2): degree elevation, exact.
void ElevateQuadratic(const Vec3d &q0, const Vec3d &q1, const Vec3d &q2, Vec3d out[4]) {
    out[0] = q0;
    out[1] = q0 + (q1 - q0) * (2.0 / 3.0);
    out[2] = q2 + (q1 - q2) * (2.0 / 3.0);
    out[3] = q2;
}

}  // namespace

std::vector<Vec3f> CubicBezierSegments(const std::vector<Vec3f> &P, int degree, bool bspline) {
    const size_t n = CurveSegmentCount(P.size(), degree, bspline);
    if (degree != 2 && degree != 3)
        throw std::invalid_argument("degree must be 2 or 3, not " + std::to_string(degree));
    if (n == 0) {
        const std::string need =
            bspline ? "n + " + std::to_string(degree) : std::to_string(degree) + "n + 1";
        throw std::invalid_argument(std::to_string(P.size()) + " control points make no whole " +
                                    "number of segments (a " + (bspline ? "B-spline" : "Bézier") +
                                    " curve of degree " + std::to_string(degree) +
                                    " and n >= 1 segments has " + need + ")");
    }
    std::vector<Vec3f> out;
    out.reserve(4 * n);
    for (size_t s = 0; s < n; ++s) {
        Vec3d b[4];
        if (!bspline && degree == 3) {
            for (int k = 0; k < 4; ++k) b[k] = Vec3d(P[3 * s + size_t(k)]);
        } else if (!bspline) {
            ElevateQuadratic(Vec3d(P[2 * s]), Vec3d(P[2 * s + 1]), Vec3d(P[2 * s + 2]), b);
        } else if (degree == 3) {
            // A uniform cubic B-spline segment over p0..p3 in Bézier form.
            const Vec3d p0(P[s]), p1(P[s + 1]), p2(P[s + 2]), p3(P[s + 3]);
            b[0] = (p0 + p1 * 4.0 + p2) / 6.0;
            b[1] = (p1 * 2.0 + p2) / 3.0;
            b[2] = (p1 + p2 * 2.0) / 3.0;
            b[3] = (p1 + p2 * 4.0 + p3) / 6.0;
        } else {
            // A uniform quadratic B-spline segment over p0..p2: the quadratic Bézier from the
            // midpoint of p0 p1 through p1 to the midpoint of p1 p2, then elevated.
            const Vec3d p0(P[s]), p1(P[s + 1]), p2(P[s + 2]);
            ElevateQuadratic((p0 + p1) * 0.5, p1, (p1 + p2) * 0.5, b);
        }
        for (const Vec3d &v : b) out.push_back(Vec3f(v));
    }
    return out;
}

namespace {

// The cubic Bézier approximating the great-circle arc from unit n0 to unit n1 (parameterized
// nearly uniformly in angle: the spherical interpolation pbrt-v3 uses between ribbon normals).
void NormalArc(const Vec3d &n0, const Vec3d &n1, Vec3d out[4]) {
    const double c = std::clamp(Dot(n0, n1), -1.0, 1.0);
    const double theta = std::acos(c);
    out[0] = n0;
    out[3] = n1;
    if (theta < 1e-6 || theta > Pi - 1e-3) {
        // Equal normals, or opposite ones (no unique arc): linear interpolation.
        out[1] = n0 + (n1 - n0) * (1.0 / 3.0);
        out[2] = n0 + (n1 - n0) * (2.0 / 3.0);
        return;
    }
    const double s = std::sin(theta);
    const Vec3d t0 = (n1 - n0 * c) / s;  // unit tangent at n0, toward n1
    const Vec3d t1 = (n1 * c - n0) / s;  // unit tangent at n1, onward
    const double h = 4.0 / 3.0 * std::tan(theta / 4);
    out[1] = n0 + t0 * h;
    out[2] = n1 - t1 * h;
}

Vec3d AnyPerpendicular(const Vec3d &t) {
    Vec3d a, b;
    CoordinateSystem(t, &a, &b);
    return a;
}

}  // namespace

CurveSet::CurveSet(const Transform &renderFromObject, bool reverseOrientation, CurveType type,
                   const std::vector<Vec3f> &bezier, float width0, float width1,
                   const std::vector<Vec3f> &N, int tessellationRate)
    : type_(type),
      flipNormals_(reverseOrientation != renderFromObject.SwapsHandedness()),
      tessellationRate_(std::clamp(tessellationRate, 1, MaxCurveTessellation)) {
    if (bezier.empty() || bezier.size() % 4 != 0)
        throw std::invalid_argument("curve control points must be 4 per segment, not " +
                                    std::to_string(bezier.size()));
    const size_t n = bezier.size() / 4;
    if (type == CurveType::Ribbon && N.size() != n + 1)
        throw std::invalid_argument("a ribbon curve of " + std::to_string(n) + " segments needs " +
                                    std::to_string(n + 1) + " normals, not " +
                                    std::to_string(N.size()));
    const double scale = std::cbrt(std::abs(renderFromObject.Matrix().Determinant3x3()));
    vertices_.resize(16 * n + 4, 0.f);
    indices_.resize(n);
    for (size_t s = 0; s < n; ++s) {
        indices_[s] = uint32_t(4 * s);
        for (int k = 0; k < 4; ++k) {
            const Vec3d p = renderFromObject.Point(Vec3d(bezier[4 * s + size_t(k)]));
            const double u = (double(s) + k / 3.0) / double(n);
            const double w = (1 - u) * double(width0) + u * double(width1);
            float *v = &vertices_[16 * s + 4 * size_t(k)];
            v[0] = float(p.x);
            v[1] = float(p.y);
            v[2] = float(p.z);
            v[3] = float(0.5 * w * scale);
        }
    }
    if (type == CurveType::Ribbon) {
        std::vector<Vec3d> ends(N.size());
        for (size_t i = 0; i < N.size(); ++i) {
            const Vec3d m = renderFromObject.Normal(Vec3d(N[i]));
            const double len = Length(m);
            if (!(len > 0) || !std::isfinite(len))
                throw std::invalid_argument("ribbon normal " + std::to_string(i) +
                                            " is zero or not finite");
            ends[i] = m / len;
        }
        normals_.resize(12 * n + 1, 0.f);
        for (size_t s = 0; s < n; ++s) {
            Vec3d arc[4];
            NormalArc(ends[s], ends[s + 1], arc);
            for (int k = 0; k < 4; ++k) {
                float *v = &normals_[12 * s + 3 * size_t(k)];
                v[0] = float(arc[k].x);
                v[1] = float(arc[k].y);
                v[2] = float(arc[k].z);
            }
        }
    }
}

Bounds3f CurveSet::RenderBounds() const {
    Bounds3f b;
    for (int step = 0; step < NumTimeSteps(); ++step)
        for (size_t i = 0; i < NumVertices(); ++i) {
            const float *v = VertexData(step) + 4 * i;
            const float r = std::abs(v[3]);
            b.Expand(Vec3f(v[0] - r, v[1] - r, v[2] - r));
            b.Expand(Vec3f(v[0] + r, v[1] + r, v[2] + r));
        }
    return b;
}

void CurveSet::SetMotionSteps(const std::vector<Transform> &stepFromStart) {
    stepVertices_.clear();
    stepNormals_.clear();
    for (const Transform &m : stepFromStart) {
        const double scale = std::cbrt(std::abs(m.Matrix().Determinant3x3()));
        std::vector<float> v(vertices_.size(), 0.f);
        for (size_t i = 0; i < 4 * NumVertices(); i += 4) {
            const Vec3f w(m.Point(Vec3d(vertices_[i], vertices_[i + 1], vertices_[i + 2])));
            v[i] = w.x;
            v[i + 1] = w.y;
            v[i + 2] = w.z;
            v[i + 3] = float(double(vertices_[i + 3]) * scale);
        }
        stepVertices_.push_back(std::move(v));
        if (normals_.empty()) continue;
        std::vector<float> nv(normals_.size(), 0.f);
        for (size_t i = 0; i < 3 * NumVertices(); i += 3) {
            const Vec3f w(m.Normal(Vec3d(normals_[i], normals_[i + 1], normals_[i + 2])));
            nv[i] = w.x;
            nv[i + 1] = w.y;
            nv[i + 2] = w.z;
        }
        stepNormals_.push_back(std::move(nv));
    }
}

double CurveSet::Segment::Radius(double u) const { return std::max(0.0, BezierPoint(r, u)); }

CurveSet::Segment CurveSet::SegmentAt(size_t prim, float time) const {
    // Embree's time step and the fraction between it and the next (as for meshes).
    const int steps = NumTimeSteps();
    int step = 0;
    double f = 0;
    if (steps > 1) {
        const float ft = std::clamp(time, 0.f, 1.f) * float(steps - 1);
        step = std::min(int(std::floor(ft)), steps - 2);
        f = double(ft - float(step));
    }
    Segment seg;
    const float *a = VertexData(step) + 16 * prim;
    const float *b = steps > 1 ? VertexData(step + 1) + 16 * prim : a;
    const float *na = normals_.empty() ? nullptr : NormalData(step) + 12 * prim;
    const float *nb = normals_.empty() ? nullptr
                      : steps > 1      ? NormalData(step + 1) + 12 * prim
                                       : na;
    for (int k = 0; k < 4; ++k) {
        const float *va = a + 4 * k, *vb = b + 4 * k;
        seg.p[k] = Vec3d(va[0], va[1], va[2]) * (1 - f) + Vec3d(vb[0], vb[1], vb[2]) * f;
        seg.r[k] = (1 - f) * double(va[3]) + f * double(vb[3]);
        if (na)
            seg.n[k] = Vec3d(na[3 * k], na[3 * k + 1], na[3 * k + 2]) * (1 - f) +
                       Vec3d(nb[3 * k], nb[3 * k + 1], nb[3 * k + 2]) * f;
    }
    return seg;
}

SurfaceInteraction CurveSet::Interaction(size_t prim, float uHit, float /*vHit*/, float t,
                                         const Vec3f &rayO, const Vec3f &rayD, float time,
                                         int shape) const {
    const double u = std::clamp(double(uHit), 0.0, 1.0);
    const Segment seg = SegmentAt(prim, time);
    const Vec3d c = seg.Center(u);
    const Vec3d dpdu = seg.Tangent(u, NumSegments());
    const double r = seg.Radius(u);
    const double len = Length(dpdu);
    const Vec3d T = len > 0 ? dpdu / len : Normalize(seg.p[3] - seg.p[0]);
    const Vec3d D(rayD);
    const Vec3d wo = -Normalize(D);
    const Vec3d pHit = Vec3d(rayO) + D * double(t);
    // The side of the curve that faces the ray (the "flat" ribbon's normal).
    Vec3d facing = wo - T * Dot(wo, T);
    facing = LengthSquared(facing) > 1e-20 ? Normalize(facing) : AnyPerpendicular(T);
    Vec3d n;
    Vec3d p = pHit;
    double offSurface = 0;  // how far Embree's hit lies from the surface modelled here
    switch (type_) {
        case CurveType::Cylinder: {
            // Embree meets the swept tube; the hit is placed on the centre plane and the normal
            // is pbrt's (below), once v is known.
            const Vec3d radial = pHit - c;
            offSurface = std::abs(Length(radial) - r);
            n = facing;
            break;
        }
        case CurveType::Flat:
            n = facing;
            offSurface = std::abs(Dot(pHit - c, n));
            break;
        case CurveType::Ribbon: {
            Vec3d along = BezierPoint(seg.n, u);
            along = along - T * Dot(along, T);
            n = LengthSquared(along) > 1e-20 ? Normalize(along) : facing;
            offSurface = std::abs(Dot(pHit - c, n));
            break;
        }
    }
    // Across the curve as the ray sees it: v = 0.5 on the centre line, 0 and 1 at its edges.
    const Vec3d across = Normalize(Cross(type_ == CurveType::Ribbon ? n : facing, T));
    const double offset = Dot(pHit - c, across);
    const double v = r > 0 ? std::clamp(0.5 + 0.5 * offset / r, 0.0, 1.0) : 0.5;
    if (type_ == CurveType::Cylinder) {
        // pbrt's cylinder: the band facing the ray, its normal turned about the curve from the
        // ray's side (v = 0.5) to straight across (v = 0 and 1) by an angle linear in v, and
        // the other way from a tube's outward normal (pbrt rotates dpdv by -θ). Shaded so, the
        // curves probe is 1.16% from pbrt-v3 against its own 0.80% (as a tube: 1.92%).
        const double theta = (0.5 - v) * Pi;
        n = facing * std::cos(theta) + across * std::sin(theta);
    }
    const Vec3d dpdv = Normalize(Cross(n, T)) * (2 * r);

    SurfaceInteraction si;
    // Embree's curve intersectors work in float and refine iteratively; the bound covers the
    // distance between their hit and the surface above, a hundredth of the radius for their
    // tolerance (a thousandth lets 1 in 6,000 rays leaving a thin tube hit it again:
    // tests/geometry/curves_test.cpp), and the float rounding of p.
    double slack = offSurface + 1e-2 * r;
    if (type_ == CurveType::Cylinder) {
        // On the centre plane, inside the tube, where pbrt places every curve hit. Rays leave
        // along ±n, which is not radial: at offset x·r across, moving k along n ends
        // (x·r - k·sin(xπ/2), k·cos(xπ/2)) from the axis, outside the tube for every x once
        // k >= 2r. So the bound is a little over twice the radius, and no ray leaving the hit
        // meets the same tube (hair's fibres scatter through it whole).
        p = c + across * offset;
        slack = 2.05 * r + offSurface;
    }
    const Vec3d err = Abs(p) * (8 * double(MachineEpsilon<float>())) + Vec3d(slack, slack, slack);
    RoundHitPoint(p, err, &si.p, &si.pError);
    if (flipNormals_) n = -n;
    si.n = si.ns = Vec3f(n);
    si.dpdu = Vec3f(dpdu);
    si.dpdv = Vec3f(dpdv);
    si.uv = Vec2f(float((double(prim) + u) / double(NumSegments())), float(v));
    si.uv1 = si.uv;
    si.wo = Vec3f(wo);
    si.t = t;
    si.shape = shape;
    si.prim = int(prim);
    si.time = time;
    return si;
}

}  // namespace prism
