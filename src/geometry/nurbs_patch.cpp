#include "geometry/nurbs_patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

namespace prism {

namespace {

std::string Num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

void ValidateDirection(const char *countName, const char *orderName, const char *knotsName,
                       const char *t0Name, const char *t1Name, int count, int order,
                       const std::vector<double> &knots, double t0, double t1) {
    if (count < 1)
        throw PatchParamError(countName, std::string("nurbs \"") + countName + "\" " +
                                             std::to_string(count) + " must be at least 1");
    if (order < 2 || order > count || order > MaxNurbsOrder)
        throw PatchParamError(
            orderName, std::string("nurbs \"") + orderName + "\" " + std::to_string(order) +
                           " out of range (2 to " + std::to_string(std::min(count, MaxNurbsOrder)) +
                           ", at most \"" + countName + "\" = " + std::to_string(count) + ")");
    size_t want = size_t(count) + size_t(order);
    if (knots.size() != want)
        throw PatchParamError(knotsName, std::string("nurbs \"") + knotsName + "\" has " +
                                             std::to_string(knots.size()) + " values; \"" +
                                             countName + "\" + \"" + orderName +
                                             "\" = " + std::to_string(want));
    for (size_t i = 0; i < knots.size(); ++i) {
        if (!std::isfinite(knots[i]))
            throw PatchParamError(knotsName, std::string("nurbs \"") + knotsName + "\" value " +
                                                 std::to_string(i) + " is not finite");
        if (i > 0 && knots[i] < knots[i - 1])
            throw PatchParamError(knotsName, std::string("nurbs \"") + knotsName +
                                                 "\" decreases at value " + std::to_string(i) +
                                                 " (" + Num(knots[i - 1]) + " then " +
                                                 Num(knots[i]) + ")");
    }
    // A knot of multiplicity above the order makes a basis function identically zero.
    for (size_t i = 0, j; i < knots.size(); i = j) {
        for (j = i; j < knots.size() && knots[j] == knots[i]; ++j) {
        }
        if (j - i > size_t(order))
            throw PatchParamError(
                knotsName, std::string("nurbs \"") + knotsName + "\": knot " + Num(knots[i]) +
                               " repeats " + std::to_string(j - i) +
                               " times, more than the order " + std::to_string(order));
    }
    double lo = knots[size_t(order - 1)], hi = knots[size_t(count)];
    if (!(lo < hi))
        throw PatchParamError(knotsName, std::string("nurbs \"") + knotsName +
                                             "\" has an empty domain: value " +
                                             std::to_string(order - 1) + " equals value " +
                                             std::to_string(count) + " (" + Num(lo) + ")");
    if (!std::isfinite(t0) || !std::isfinite(t1) || !(t0 < t1))
        throw PatchParamError(t0Name, std::string("nurbs parameter range \"") + t0Name + "\" " +
                                          Num(t0) + " to \"" + t1Name + "\" " + Num(t1) +
                                          " is empty");
    if (t0 < lo || t1 > hi)
        throw PatchParamError(t0 < lo ? t0Name : t1Name, std::string("nurbs parameter range [") +
                                                             Num(t0) + ", " + Num(t1) + "] (\"" +
                                                             t0Name + "\", \"" + t1Name +
                                                             "\") leaves the knots' domain [" +
                                                             Num(lo) + ", " + Num(hi) + "]");
}

// The distinct parameter values where the grid must have a line: t0, the knots strictly
// inside (t0, t1), t1; and each one's knot multiplicity (0 for t0/t1 when not knots).
struct Breaks {
    std::vector<double> t;
    std::vector<int> multiplicity;
};

Breaks BreakPoints(const std::vector<double> &knots, double t0, double t1) {
    Breaks b;
    b.t.push_back(t0);
    b.multiplicity.push_back(0);
    for (size_t i = 0; i < knots.size();) {
        size_t j = i;
        while (j < knots.size() && knots[j] == knots[i]) ++j;
        if (knots[i] > t0 && knots[i] < t1) {
            b.t.push_back(knots[i]);
            b.multiplicity.push_back(int(j - i));
        }
        i = j;
    }
    b.t.push_back(t1);
    b.multiplicity.push_back(0);
    return b;
}

// The samples of one direction: grid lines with the side their derivatives come from, and
// the segments between them (a doubled line at a crease has no segment between its copies).
struct Axis {
    std::vector<double> t;
    std::vector<char> fromLeft;
    std::vector<char> sharesPrevious;  // same position as the line before (a crease copy)
    std::vector<std::array<int, 2>> segments;
    std::vector<int> segmentSpan;  // which break interval each segment lies in
};

Axis MakeAxis(const Breaks &b, const std::vector<int> &perSpan, int order) {
    Axis a;
    auto add = [&](double t, bool left, bool shares) {
        a.t.push_back(t);
        a.fromLeft.push_back(left);
        a.sharesPrevious.push_back(shares);
    };
    add(b.t[0], false, false);
    size_t spans = b.t.size() - 1;
    for (size_t s = 0; s < spans; ++s) {
        double ta = b.t[s], tb = b.t[s + 1];
        int k = perSpan[s];
        for (int i = 1; i <= k; ++i) {
            int prev = int(a.t.size()) - 1;
            bool end = i == k;
            double t = end ? tb : ta + (tb - ta) * double(i) / double(k);
            // At the span's end: the limit from below (this span's derivatives).
            add(t, end, false);
            a.segments.push_back({prev, prev + 1});
            a.segmentSpan.push_back(int(s));
        }
        if (s + 1 < spans) {
            int m = b.multiplicity[s + 1];
            if (m >= order - 1) {
                // A crease: the next span starts on a copy of the line with its own
                // derivatives, at the same position unless the surface breaks (m = order).
                add(tb, false, m < order);
            } else {
                a.fromLeft.back() = false;
            }
        }
    }
    return a;
}

// The initial segments of each break interval: its share of minSegments, at least one.
std::vector<int> BaseSegments(const Breaks &b, int minSegments) {
    double total = b.t.back() - b.t.front();
    std::vector<int> k(b.t.size() - 1);
    for (size_t s = 0; s < k.size(); ++s) {
        double share = double(minSegments) * (b.t[s + 1] - b.t[s]) / total;
        k[s] = std::max(1, int(std::ceil(share - 1e-9)));
    }
    return k;
}

uint64_t SegmentCount(const std::vector<int> &k) {
    uint64_t n = 0;
    for (int x : k) n += uint64_t(x);
    return n;
}

// Every grid point of the axes' product, v-major (index iv * nU + iu).
struct Grid {
    std::vector<Vec3d> P, N;
    std::vector<char> degenerateN;
};

// The diagonal of the control points' bounding box (the surface lies in their hull).
double ControlExtent(const NurbsPatch &patch) {
    Vec3d lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
    for (size_t i = 0; i + 3 < patch.Pw.size(); i += 4) {
        Vec3d p = Vec3d(patch.Pw[i], patch.Pw[i + 1], patch.Pw[i + 2]) / patch.Pw[i + 3];
        lo = Min(lo, p);
        hi = Max(hi, p);
    }
    return Length(hi - lo);
}

Grid EvaluateGrid(const NurbsPatch &patch, const Axis &au, const Axis &av) {
    size_t nU = au.t.size(), nV = av.t.size();
    // A normal is taken from the faces around the vertex where dP/du x dP/dv, over the whole
    // parameter range, is below 1e-12 of the squared extent (a pole, a collapsed edge).
    double extent = ControlExtent(patch);
    double tinyArea = 1e-12 * extent * extent / ((patch.u1 - patch.u0) * (patch.v1 - patch.v0));
    Grid g;
    g.P.resize(nU * nV);
    g.N.resize(nU * nV);
    g.degenerateN.assign(nU * nV, 0);
    for (size_t iv = 0; iv < nV; ++iv)
        for (size_t iu = 0; iu < nU; ++iu) {
            NurbsPoint s = EvaluateNurbs(patch, au.t[iu], av.t[iv], au.fromLeft[iu] != 0,
                                         av.fromLeft[iv] != 0);
            size_t idx = iv * nU + iu;
            if (au.sharesPrevious[iu])
                s.P = g.P[idx - 1];
            else if (av.sharesPrevious[iv])
                s.P = g.P[idx - nU];
            g.P[idx] = s.P;
            Vec3d n = Cross(s.dPdu, s.dPdv);
            double len = Length(n);
            if (!(len > tinyArea) || !std::isfinite(len)) {
                g.degenerateN[idx] = 1;  // a pole or a collapsed edge: from the faces below
                g.N[idx] = Vec3d(0, 0, 0);
            } else {
                g.N[idx] = n / len;
            }
        }
    // Points that coincide but for rounding (a pole: a row of the net collapsed to one point)
    // are made one, so the triangles between them collapse exactly and the mesh stays closed.
    double snap = 1e-10 * extent;
    for (size_t iv = 0; iv < nV; ++iv)
        for (size_t iu = 0; iu < nU; ++iu) {
            size_t idx = iv * nU + iu;
            if (iu > 0 && Length(g.P[idx] - g.P[idx - 1]) <= snap) g.P[idx] = g.P[idx - 1];
            if (iv > 0 && Length(g.P[idx] - g.P[idx - nU]) <= snap) g.P[idx] = g.P[idx - nU];
        }
    return g;
}

double DistanceToMid(const Vec3d &s, const Vec3d &a, const Vec3d &b) {
    return Length(s - 0.5 * (a + b));
}

// The chordal error per break interval of each axis: the surface at the middle of every grid
// edge against the edge's midpoint, and at the centre of every cell against the midpoint of
// the diagonal the triangles share. A cell's centre error counts for the direction whose edges
// explain it (at least half as large; a ruled surface's straight direction is not refined for
// the other's curvature), or for both when neither does (a twist).
void MeasureErrors(const NurbsPatch &patch, const Axis &au, const Axis &av, const Grid &g,
                   std::vector<double> &errU, std::vector<double> &errV) {
    size_t nU = au.t.size(), nV = av.t.size();
    auto P = [&](int iu, int iv) { return g.P[size_t(iv) * nU + size_t(iu)]; };
    auto mid = [](const Axis &a, size_t seg) {
        return 0.5 * (a.t[size_t(a.segments[seg][0])] + a.t[size_t(a.segments[seg][1])]);
    };
    std::vector<double> eu(au.segments.size() * nV), ev(av.segments.size() * nU);
    for (size_t su = 0; su < au.segments.size(); ++su) {
        auto [a, b] = au.segments[su];
        double &worst = errU[size_t(au.segmentSpan[su])];
        for (size_t iv = 0; iv < nV; ++iv) {
            Vec3d s = EvaluateNurbs(patch, mid(au, su), av.t[iv], false, av.fromLeft[iv] != 0).P;
            double e = DistanceToMid(s, P(a, int(iv)), P(b, int(iv)));
            eu[su * nV + iv] = e;
            worst = std::max(worst, e);
        }
    }
    for (size_t sv = 0; sv < av.segments.size(); ++sv) {
        auto [c, d] = av.segments[sv];
        double &worst = errV[size_t(av.segmentSpan[sv])];
        for (size_t iu = 0; iu < nU; ++iu) {
            Vec3d s = EvaluateNurbs(patch, au.t[iu], mid(av, sv), au.fromLeft[iu] != 0, false).P;
            double e = DistanceToMid(s, P(int(iu), c), P(int(iu), d));
            ev[sv * nU + iu] = e;
            worst = std::max(worst, e);
        }
    }
    for (size_t su = 0; su < au.segments.size(); ++su)
        for (size_t sv = 0; sv < av.segments.size(); ++sv) {
            auto [a, b] = au.segments[su];
            auto [c, d] = av.segments[sv];
            Vec3d s = EvaluateNurbs(patch, mid(au, su), mid(av, sv)).P;
            double e = DistanceToMid(s, P(a, c), P(b, d));
            double edgeU = std::max(eu[su * nV + size_t(c)], eu[su * nV + size_t(d)]);
            double edgeV = std::max(ev[sv * nU + size_t(a)], ev[sv * nU + size_t(b)]);
            bool toU = edgeU >= 0.5 * e, toV = edgeV >= 0.5 * e;
            if (!toU && !toV) toU = toV = true;
            if (toU)
                errU[size_t(au.segmentSpan[su])] = std::max(errU[size_t(au.segmentSpan[su])], e);
            if (toV)
                errV[size_t(av.segmentSpan[sv])] = std::max(errV[size_t(av.segmentSpan[sv])], e);
        }
}

// More segments for each interval over the tolerance: the error of a segment falls with the
// square of its length.
bool Refine(std::vector<int> &k, const std::vector<double> &err, double tol) {
    bool any = false;
    for (size_t s = 0; s < k.size(); ++s)
        if (err[s] > tol) {
            double f = std::ceil(std::sqrt(err[s] / tol) * 1.05);
            k[s] = int(std::min<double>(double(k[s]) * std::clamp(f, 2.0, 16.0), 1 << 24));
            any = true;
        }
    return any;
}

PatchMesh BuildMesh(const Axis &au, const Axis &av, const Grid &g) {
    size_t nU = au.t.size(), nV = av.t.size();
    PatchMesh m;
    m.P.resize(nU * nV);
    m.uv.resize(nU * nV);
    std::vector<Vec3d> faceSum(nU * nV, Vec3d(0, 0, 0));
    for (size_t iv = 0; iv < nV; ++iv)
        for (size_t iu = 0; iu < nU; ++iu) {
            size_t i = iv * nU + iu;
            m.P[i] = Vec3f(g.P[i]);
            m.uv[i] = Vec2f(float(au.t[iu]), float(av.t[iv]));
        }
    auto tri = [&](size_t a, size_t b, size_t c) {
        if (m.P[a] == m.P[b] || m.P[b] == m.P[c] || m.P[a] == m.P[c]) return;  // collapsed
        m.indices.insert(m.indices.end(), {int(a), int(b), int(c)});
        Vec3d n = Cross(g.P[b] - g.P[a], g.P[c] - g.P[a]);
        for (size_t v : {a, b, c}) faceSum[v] += n;
    };
    for (const auto &[c, d] : av.segments)
        for (const auto &[a, b] : au.segments) {
            size_t v00 = size_t(c) * nU + size_t(a), v10 = size_t(c) * nU + size_t(b);
            size_t v01 = size_t(d) * nU + size_t(a), v11 = size_t(d) * nU + size_t(b);
            tri(v00, v10, v11);
            tri(v00, v11, v01);
        }
    // Where dP/du x dP/dv vanishes, the normal of the faces around the point, summed over every
    // vertex at that position (all of a pole's copies).
    std::map<std::tuple<double, double, double>, Vec3d> around;
    for (size_t i = 0; i < m.P.size(); ++i)
        if (g.degenerateN[i]) around[{g.P[i].x, g.P[i].y, g.P[i].z}] += faceSum[i];
    m.N.resize(nU * nV);
    for (size_t i = 0; i < m.N.size(); ++i) {
        Vec3d n = g.N[i];
        if (g.degenerateN[i]) {
            Vec3d sum = around[{g.P[i].x, g.P[i].y, g.P[i].z}];
            double len = Length(sum);
            n = len > 0 ? sum / len : Vec3d(0, 0, 1);
        }
        m.N[i] = Vec3f(n);
    }
    return m;
}

}  // namespace

void ValidateNurbs(const NurbsPatch &p) {
    ValidateDirection("nu", "uorder", "uknots", "u0", "u1", p.nu, p.uorder, p.uknots, p.u0, p.u1);
    ValidateDirection("nv", "vorder", "vknots", "v0", "v1", p.nv, p.vorder, p.vknots, p.v0, p.v1);
    uint64_t points = uint64_t(p.nu) * uint64_t(p.nv);
    if (p.Pw.size() != 4 * points)
        throw PatchParamError("Pw", "nurbs needs \"nu\" * \"nv\" = " + std::to_string(points) +
                                        " control points, got " + std::to_string(p.Pw.size() / 4));
    for (size_t i = 0; i < points; ++i) {
        const double *q = &p.Pw[4 * i];
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(q[c]))
                throw PatchParamError(
                    "Pw", "nurbs control point " + std::to_string(i) + " is not finite");
        if (!(q[3] > 0))
            throw PatchParamError("Pw", "nurbs control point " + std::to_string(i) +
                                            " has weight " + Num(q[3]) +
                                            "; weights must be positive");
    }
}

int FindKnotSpan(const std::vector<double> &knots, int count, int order, double t, bool fromLeft) {
    int lo = order - 1, hi = count - 1;
    const double *k = knots.data();
    int span;
    if (!fromLeft)  // the largest i in [lo, hi] with k[i] <= t
        span = int(std::upper_bound(k + lo, k + hi + 1, t) - k) - 1;
    else  // the smallest i in [lo, hi] with t <= k[i+1]
        span = int(std::lower_bound(k + lo + 1, k + hi + 2, t) - k) - 1;
    span = std::clamp(span, lo, hi);
    // An empty span (a repeated knot) at the ends of the domain: step inwards.
    while (span > lo && !(k[span] < k[span + 1]) && t >= k[span]) --span;
    while (span < hi && !(k[span] < k[span + 1])) ++span;
    while (span > lo && !(k[span] < k[span + 1])) --span;
    return span;
}

void BSplineBasis(const std::vector<double> &knots, int order, int span, double t, double *N,
                  double *dN) {
    // N[j] is N_{span-d+j, d}, j = 0..d, built up degree by degree in place (from the right,
    // so each new value reads the two of the degree below before they are overwritten):
    //   N_{i,d}(t) = (t - k_i)/(k_{i+d} - k_i) N_{i,d-1} + (k_{i+d+1} - t)/(k_{i+d+1} - k_{i+1})
    //   N_{i+1,d-1}, and  N'_{i,p} = p (N_{i,p-1}/(k_{i+p} - k_i) - N_{i+1,p-1}/(k_{i+p+1} -
    //   k_{i+1})), with 0/0 = 0 (de Boor, A Practical Guide to Splines, ch. IX-X).
    const double *k = knots.data();
    int p = order - 1;
    auto ratio = [](double num, double den) { return den > 0 ? num / den : 0.0; };
    N[0] = 1;
    for (int d = 1; d <= p; ++d) {
        if (d == p && dN) {
            for (int j = 0; j <= p; ++j) {
                int i = span - p + j;
                double a = j >= 1 ? ratio(N[j - 1], k[i + p] - k[i]) : 0.0;
                double b = j <= p - 1 ? ratio(N[j], k[i + p + 1] - k[i + 1]) : 0.0;
                dN[j] = double(p) * (a - b);
            }
        }
        for (int j = d; j >= 0; --j) {
            int i = span - d + j;
            double a = j >= 1 ? N[j - 1] * ratio(t - k[i], k[i + d] - k[i]) : 0.0;
            double b = j <= d - 1 ? N[j] * ratio(k[i + d + 1] - t, k[i + d + 1] - k[i + 1]) : 0.0;
            N[j] = a + b;
        }
    }
}

NurbsPoint EvaluateNurbs(const NurbsPatch &patch, double u, double v, bool uFromLeft,
                         bool vFromLeft) {
    int su = FindKnotSpan(patch.uknots, patch.nu, patch.uorder, u, uFromLeft);
    int sv = FindKnotSpan(patch.vknots, patch.nv, patch.vorder, v, vFromLeft);
    std::array<double, MaxNurbsOrder> Nu, dNu, Nv, dNv;
    BSplineBasis(patch.uknots, patch.uorder, su, u, Nu.data(), dNu.data());
    BSplineBasis(patch.vknots, patch.vorder, sv, v, Nv.data(), dNv.data());
    // The homogeneous surface A = sum N_i(u) N_j(v) Pw_ij and its derivatives.
    double A[4] = {0, 0, 0, 0}, Au[4] = {0, 0, 0, 0}, Av[4] = {0, 0, 0, 0};
    int iu0 = su - patch.uorder + 1, iv0 = sv - patch.vorder + 1;
    for (int jv = 0; jv < patch.vorder; ++jv) {
        double rowA[4] = {0, 0, 0, 0}, rowAu[4] = {0, 0, 0, 0};
        const double *row = &patch.Pw[4 * (size_t(iv0 + jv) * size_t(patch.nu) + size_t(iu0))];
        for (int ju = 0; ju < patch.uorder; ++ju)
            for (int c = 0; c < 4; ++c) {
                rowA[c] += Nu[size_t(ju)] * row[4 * ju + c];
                rowAu[c] += dNu[size_t(ju)] * row[4 * ju + c];
            }
        for (int c = 0; c < 4; ++c) {
            A[c] += Nv[size_t(jv)] * rowA[c];
            Au[c] += Nv[size_t(jv)] * rowAu[c];
            Av[c] += dNv[size_t(jv)] * rowA[c];
        }
    }
    // S = A.xyz / A.w; dS = (dA.xyz - dA.w S) / A.w.
    NurbsPoint r;
    double invW = 1.0 / A[3];
    r.P = Vec3d(A[0], A[1], A[2]) * invW;
    r.dPdu = (Vec3d(Au[0], Au[1], Au[2]) - Au[3] * r.P) * invW;
    r.dPdv = (Vec3d(Av[0], Av[1], Av[2]) - Av[3] * r.P) * invW;
    return r;
}

uint64_t MinNurbsTriangles(const NurbsPatch &patch, int minSegments) {
    uint64_t su =
        SegmentCount(BaseSegments(BreakPoints(patch.uknots, patch.u0, patch.u1), minSegments));
    uint64_t sv =
        SegmentCount(BaseSegments(BreakPoints(patch.vknots, patch.v0, patch.v1), minSegments));
    return 2 * su * sv;
}

NurbsTessellation TessellateNurbs(const NurbsPatch &patch,
                                  const NurbsTessellationOptions &options) {
    Breaks bu = BreakPoints(patch.uknots, patch.u0, patch.u1);
    Breaks bv = BreakPoints(patch.vknots, patch.v0, patch.v1);
    std::vector<int> ku = BaseSegments(bu, options.minSegments);
    std::vector<int> kv = BaseSegments(bv, options.minSegments);
    if (2 * SegmentCount(ku) * SegmentCount(kv) > options.maxTriangles)
        throw PatchParamError(
            "nu", "nurbs patch needs at least " +
                      std::to_string(2 * SegmentCount(ku) * SegmentCount(kv)) +
                      " triangles (its knot spans times " + std::to_string(options.minSegments) +
                      " segments), more than the limit of " + std::to_string(options.maxTriangles));
    NurbsTessellation r;
    for (int iteration = 0;; ++iteration) {
        Axis au = MakeAxis(bu, ku, patch.uorder), av = MakeAxis(bv, kv, patch.vorder);
        Grid g = EvaluateGrid(patch, au, av);
        if (iteration == 0) {
            Vec3d lo = g.P[0], hi = g.P[0];
            for (const Vec3d &p : g.P) {
                lo = Min(lo, p);
                hi = Max(hi, p);
            }
            r.tolerance = options.relativeTolerance * Length(hi - lo);
        }
        std::vector<double> errU(ku.size(), 0.0), errV(kv.size(), 0.0);
        MeasureErrors(patch, au, av, g, errU, errV);
        r.chordalError = std::max(*std::max_element(errU.begin(), errU.end()),
                                  *std::max_element(errV.begin(), errV.end()));
        std::vector<int> nku = ku, nkv = kv;
        bool more = Refine(nku, errU, r.tolerance) | Refine(nkv, errV, r.tolerance);
        bool fits = 2 * SegmentCount(nku) * SegmentCount(nkv) <= options.maxTriangles;
        if (!more || !fits || iteration >= 16) {
            r.capped = more;
            r.segmentsU = int(au.segments.size());
            r.segmentsV = int(av.segments.size());
            r.mesh = BuildMesh(au, av, g);
            return r;
        }
        ku = std::move(nku);
        kv = std::move(nkv);
    }
}

}  // namespace prism
