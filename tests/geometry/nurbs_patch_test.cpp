// NURBS patches and heightfields: the B-spline basis against the Cox-de Boor definition
// evaluated recursively in long double (clamped, unclamped and repeated-knot vectors), closed
// forms (a bilinear patch; rational quarter cylinder and sphere octant, exact conics), the
// tessellation's chordal error bound, watertightness, creases and normal orientation, and
// each validation error.
#include "geometry/nurbs_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <tuple>

#include "geometry/heightfield.h"

namespace prism {
namespace {

using LD = long double;

// N_{i,p}(t) straight from the definition (half-open spans; at the domain's right end the
// last non-empty span is closed), written independently of the library's in-place scheme.
LD RefBasis(const std::vector<double> &k, int i, int p, LD t, int lastSpan) {
    if (p == 0) {
        if (t == k[size_t(lastSpan) + 1]) return i == lastSpan ? 1 : 0;  // the domain's end
        return (k[size_t(i)] <= t && t < k[size_t(i) + 1]) ? 1 : 0;
    }
    LD a = 0, b = 0;
    LD d1 = LD(k[size_t(i + p)]) - k[size_t(i)], d2 = LD(k[size_t(i + p + 1)]) - k[size_t(i + 1)];
    if (d1 > 0) a = (t - k[size_t(i)]) / d1 * RefBasis(k, i, p - 1, t, lastSpan);
    if (d2 > 0) b = (k[size_t(i + p + 1)] - t) / d2 * RefBasis(k, i + 1, p - 1, t, lastSpan);
    return a + b;
}

LD RefBasisDerivative(const std::vector<double> &k, int i, int p, LD t, int lastSpan) {
    LD d1 = LD(k[size_t(i + p)]) - k[size_t(i)], d2 = LD(k[size_t(i + p + 1)]) - k[size_t(i + 1)];
    LD a = d1 > 0 ? RefBasis(k, i, p - 1, t, lastSpan) / d1 : 0;
    LD b = d2 > 0 ? RefBasis(k, i + 1, p - 1, t, lastSpan) / d2 : 0;
    return p * (a - b);
}

// The last non-empty span of the domain [k[order-1], k[count]].
int LastSpan(const std::vector<double> &k, int count) {
    int i = count - 1;
    while (!(k[size_t(i)] < k[size_t(i) + 1])) --i;
    return i;
}

struct KnotCase {
    const char *name;
    int count, order;
    std::vector<double> knots;
};

const std::vector<KnotCase> &KnotCases() {
    static const std::vector<KnotCase> cases = {
        {"clamped cubic", 6, 4, {0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1}},
        {"unclamped uniform quadratic", 5, 3, {0, 1, 2, 3, 4, 5, 6, 7}},
        {"unclamped non-uniform cubic", 6, 4, {-1, 0, 0.5, 2, 2.5, 4, 4.2, 5, 7, 8}},
        {"repeated interior (C0) quadratic", 5, 3, {0, 0, 0, 1, 1, 2, 2, 2}},
        {"repeated interior (C1) cubic", 7, 4, {0, 0, 0, 0, 1, 1, 2, 3, 3, 3, 3}},
        {"full multiplicity (break) quadratic", 6, 3, {0, 0, 0, 1, 1, 1, 2, 2, 2}},
        {"Bezier quintic", 6, 6, {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1}},
        {"linear", 4, 2, {0, 0, 0.25, 0.75, 1, 1}},
    };
    return cases;
}

TEST(NurbsBasis, MatchesRecursiveDefinitionInLongDouble) {
    std::mt19937 rng(7);
    for (const KnotCase &c : KnotCases()) {
        const std::vector<double> &k = c.knots;
        int p = c.order - 1, last = LastSpan(k, c.count);
        double lo = k[size_t(p)], hi = k[size_t(c.count)];
        std::vector<double> ts = {lo, hi};
        for (double t : k)  // every knot in the domain, and just beside it
            if (t >= lo && t <= hi) ts.insert(ts.end(), {t, std::nextafter(t, lo), t + 1e-9});
        std::uniform_real_distribution<double> uni(lo, hi);
        for (int i = 0; i < 200; ++i) ts.push_back(uni(rng));
        for (double t : ts) {
            if (t < lo || t > hi) continue;
            int span = FindKnotSpan(k, c.count, c.order, t, false);
            ASSERT_GE(span, p) << c.name;
            ASSERT_LE(span, c.count - 1) << c.name;
            EXPECT_LT(k[size_t(span)], k[size_t(span) + 1]) << c.name << " t " << t;
            EXPECT_TRUE(k[size_t(span)] <= t && (t < k[size_t(span) + 1] || span == last))
                << c.name << " t " << t << " span " << span;
            double N[MaxNurbsOrder], dN[MaxNurbsOrder];
            BSplineBasis(k, c.order, span, t, N, dN);
            double sum = 0, dsum = 0;
            for (int j = 0; j <= p; ++j) {
                int idx = span - p + j;
                LD want = RefBasis(k, idx, p, t, last);
                EXPECT_NEAR(N[j], double(want), 1e-13) << c.name << " t " << t << " i " << idx;
                // The derivative is one-sided at a knot; compare inside spans only.
                bool atKnot = false;
                for (double kk : k) atKnot |= std::abs(kk - t) < 1e-6;
                if (!atKnot) {
                    LD dwant = RefBasisDerivative(k, idx, p, t, last);
                    EXPECT_NEAR(dN[j], double(dwant), 1e-10 * (1 + std::abs(double(dwant))))
                        << c.name << " t " << t << " i " << idx;
                    // And the derivative formula itself against central differences.
                    LD h = 1e-7L;
                    LD fd = (RefBasis(k, idx, p, t + h, last) - RefBasis(k, idx, p, t - h, last)) /
                            (2 * h);
                    EXPECT_NEAR(dN[j], double(fd), 1e-5 * (1 + std::abs(double(fd))))
                        << c.name << " t " << t;
                }
                sum += N[j];
                dsum += dN[j];
            }
            // Partition of unity on the domain, and so derivatives summing to zero.
            EXPECT_NEAR(sum, 1.0, 1e-14) << c.name << " t " << t;
            EXPECT_NEAR(dsum, 0.0, 1e-9) << c.name << " t " << t;
            // The other basis functions vanish there.
            for (int idx = 0; idx < c.count; ++idx)
                if (idx < span - p || idx > span)
                    EXPECT_EQ(RefBasis(k, idx, p, t, last), 0) << c.name << " t " << t;
        }
    }
}

TEST(NurbsBasis, OneSidedSpansAtKnots) {
    const std::vector<double> k = {0, 0, 0, 1, 1, 2, 2, 2};  // order 3, knot 1 doubled
    EXPECT_EQ(FindKnotSpan(k, 5, 3, 1.0, false), 4);         // [1, 2)
    EXPECT_EQ(FindKnotSpan(k, 5, 3, 1.0, true), 2);          // (0, 1]
    EXPECT_EQ(FindKnotSpan(k, 5, 3, 0.0, true), 2);          // the domain's start
    EXPECT_EQ(FindKnotSpan(k, 5, 3, 2.0, false), 4);         // the domain's end
    EXPECT_EQ(FindKnotSpan(k, 5, 3, -5.0, false), 2);        // outside: the end spans
    EXPECT_EQ(FindKnotSpan(k, 5, 3, 9.0, true), 4);
}

// A non-rational patch from points (w = 1), u fastest.
NurbsPatch Patch(int nu, int nv, int uo, int vo, std::vector<double> uk, std::vector<double> vk,
                 const std::vector<Vec3d> &P) {
    NurbsPatch p;
    p.nu = nu;
    p.nv = nv;
    p.uorder = uo;
    p.vorder = vo;
    p.uknots = std::move(uk);
    p.vknots = std::move(vk);
    p.u0 = p.uknots[size_t(uo - 1)];
    p.u1 = p.uknots[size_t(nu)];
    p.v0 = p.vknots[size_t(vo - 1)];
    p.v1 = p.vknots[size_t(nv)];
    for (const Vec3d &q : P) p.Pw.insert(p.Pw.end(), {q.x, q.y, q.z, 1.0});
    return p;
}

TEST(NurbsSurface, BilinearPatchIsTheClosedForm) {
    Vec3d p00(0, 0, 0), p10(2, 0, 1), p01(0, 3, -1), p11(2.5, 3.5, 2);
    NurbsPatch p = Patch(2, 2, 2, 2, {0, 0, 1, 1}, {0, 0, 1, 1}, {p00, p10, p01, p11});
    ValidateNurbs(p);
    for (double u : {0.0, 0.25, 0.6, 1.0})
        for (double v : {0.0, 0.1, 0.5, 1.0}) {
            NurbsPoint s = EvaluateNurbs(p, u, v);
            Vec3d want =
                (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11;
            Vec3d du = (1 - v) * (p10 - p00) + v * (p11 - p01);
            Vec3d dv = (1 - u) * (p01 - p00) + u * (p11 - p10);
            EXPECT_NEAR(Length(s.P - want), 0, 1e-14);
            EXPECT_NEAR(Length(s.dPdu - du), 0, 1e-13);
            EXPECT_NEAR(Length(s.dPdv - dv), 0, 1e-13);
        }
}

// A rational quadratic arc of the unit circle from (1, 0) to (0, 1) in u, extruded along z
// from 0 to 2 in v: an exact quarter cylinder.
NurbsPatch QuarterCylinder() {
    const double w = std::sqrt(0.5);
    NurbsPatch p;
    p.nu = 3;
    p.nv = 2;
    p.uorder = 3;
    p.vorder = 2;
    p.uknots = {0, 0, 0, 1, 1, 1};
    p.vknots = {0, 0, 1, 1};
    p.u0 = 0, p.u1 = 1, p.v0 = 0, p.v1 = 1;
    for (double z : {0.0, 2.0}) {
        p.Pw.insert(p.Pw.end(), {1, 0, z, 1});
        p.Pw.insert(p.Pw.end(), {w, w, w * z, w});
        p.Pw.insert(p.Pw.end(), {0, 1, z, 1});
    }
    return p;
}

// A rational biquadratic sphere octant: the quarter circle from the equator to the pole in v
// swept by a quarter turn in u (tensor-product weights), the row at v = 1 collapsed to the
// pole (0, 0, 1).
NurbsPatch SphereOctant(double radius) {
    const double w = std::sqrt(0.5);
    const double arc[3][3] = {{1, 0, 1}, {1, 1, w}, {0, 1, 1}};   // (x, y, weight) in u
    const double prof[3][3] = {{1, 0, 1}, {1, 1, w}, {0, 1, 1}};  // (r, z, weight) in v
    NurbsPatch p;
    p.nu = p.nv = 3;
    p.uorder = p.vorder = 3;
    p.uknots = p.vknots = {0, 0, 0, 1, 1, 1};
    p.u0 = 0, p.u1 = 1, p.v0 = 0, p.v1 = 1;
    for (const auto &pr : prof)
        for (const auto &a : arc) {
            double ww = pr[2] * a[2];
            Vec3d q(radius * pr[0] * a[0], radius * pr[0] * a[1], radius * pr[1]);
            p.Pw.insert(p.Pw.end(), {q.x * ww, q.y * ww, q.z * ww, ww});
        }
    return p;
}

TEST(NurbsSurface, RationalQuarterCylinderIsExact) {
    NurbsPatch p = QuarterCylinder();
    ValidateNurbs(p);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(0, 1);
    for (int i = 0; i < 500; ++i) {
        double u = i == 0 ? 0 : i == 1 ? 1 : uni(rng), v = uni(rng);
        NurbsPoint s = EvaluateNurbs(p, u, v);
        EXPECT_NEAR(std::hypot(s.P.x, s.P.y), 1.0, 1e-14) << u;
        EXPECT_NEAR(s.P.z, 2 * v, 1e-14);
        EXPECT_GE(s.P.x, -1e-15);
        EXPECT_GE(s.P.y, -1e-15);
        // dP/du is tangent to the circle, dP/dv the axis; their cross product is radial,
        // pointing outward (u turns counter-clockwise about +z, v runs up +z).
        EXPECT_NEAR(Dot(s.dPdu, s.P - Vec3d(0, 0, s.P.z)), 0, 1e-12);
        EXPECT_NEAR(Length(s.dPdv - Vec3d(0, 0, 2)), 0, 1e-13);
        Vec3d n = Normalize(Cross(s.dPdu, s.dPdv));
        EXPECT_NEAR(Dot(n, Vec3d(s.P.x, s.P.y, 0)), 1.0, 1e-12);
    }
    // The derivative against central differences of the surface.
    double u = 0.37, v = 0.61, h = 1e-6;
    Vec3d fd = (EvaluateNurbs(p, u + h, v).P - EvaluateNurbs(p, u - h, v).P) / (2 * h);
    EXPECT_NEAR(Length(EvaluateNurbs(p, u, v).dPdu - fd), 0, 1e-8);
}

TEST(NurbsSurface, RationalSphereOctantIsExact) {
    NurbsPatch p = SphereOctant(3.0);
    ValidateNurbs(p);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uni(0, 1);
    for (int i = 0; i < 500; ++i) {
        double u = uni(rng), v = uni(rng);
        NurbsPoint s = EvaluateNurbs(p, u, v);
        EXPECT_NEAR(Length(s.P), 3.0, 3e-14);
        Vec3d n = Normalize(Cross(s.dPdu, s.dPdv));
        EXPECT_NEAR(Dot(n, s.P / 3.0), 1.0, 1e-9) << u << " " << v;  // outward
        Vec3d fd = (EvaluateNurbs(p, u, v + 1e-6).P - EvaluateNurbs(p, u, v - 1e-6).P) / 2e-6;
        if (v > 1e-5 && v < 1 - 1e-5) EXPECT_NEAR(Length(s.dPdv - fd), 0, 1e-7);
    }
    // The tessellated vertices, in float, lie on the sphere to float precision, and the pole's
    // normal (from the faces around it, dP/du vanishing there) points up.
    NurbsTessellation t = TessellateNurbs(p);
    double worst = 0;
    for (size_t i = 0; i < t.mesh.P.size(); ++i) {
        worst = std::max(worst, std::abs(Length(Vec3d(t.mesh.P[i])) / 3.0 - 1.0));
        Vec3d n(t.mesh.N[i]), dir = Normalize(Vec3d(t.mesh.P[i]));
        EXPECT_GT(Dot(n, dir), 0.999) << i;
    }
    EXPECT_LT(worst, 1e-6);
}

// The triangle of the tessellation whose (u, v) holds (u, v), and the position it gives there.
bool MeshAt(const PatchMesh &m, double u, double v, Vec3d *p) {
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        Vec2f a = m.uv[size_t(m.indices[i])], b = m.uv[size_t(m.indices[i + 1])],
              c = m.uv[size_t(m.indices[i + 2])];
        double det = double(b.x - a.x) * (c.y - a.y) - double(c.x - a.x) * (b.y - a.y);
        if (det == 0) continue;
        double l1 = ((u - a.x) * (c.y - a.y) - (c.x - a.x) * (v - a.y)) / det;
        double l2 = (double(b.x - a.x) * (v - a.y) - (u - a.x) * double(b.y - a.y)) / det;
        double l0 = 1 - l1 - l2;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        *p = l0 * Vec3d(m.P[size_t(m.indices[i])]) + l1 * Vec3d(m.P[size_t(m.indices[i + 1])]) +
             l2 * Vec3d(m.P[size_t(m.indices[i + 2])]);
        return true;
    }
    return false;
}

// Every edge, by vertex positions, is used once in each direction (interior) or once in one
// direction (boundary); returns the boundary edges' count.
size_t ExpectWatertight(const PatchMesh &m, const char *what) {
    auto key = [&](int i) {
        Vec3f p = m.P[size_t(i)];
        return std::tuple<float, float, float>(p.x, p.y, p.z);
    };
    std::map<std::pair<std::tuple<float, float, float>, std::tuple<float, float, float>>, int>
        directed;
    for (size_t i = 0; i < m.indices.size(); i += 3)
        for (int e = 0; e < 3; ++e)
            directed[{key(m.indices[i + size_t(e)]), key(m.indices[i + size_t(e + 1) % 3])}]++;
    size_t boundary = 0;
    for (const auto &[e, n] : directed) {
        EXPECT_EQ(n, 1) << what << ": edge used twice in one direction";
        auto twin = directed.find({e.second, e.first});
        if (twin == directed.end())
            ++boundary;
        else
            EXPECT_EQ(twin->second, 1) << what;
    }
    return boundary;
}

// Each vertex normal lies on the side of the faces around it (and the faces are wound with
// it): one consistent orientation over the patch.
void ExpectConsistentNormals(const PatchMesh &m, const char *what, double minCos = 0.5) {
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        Vec3d a(m.P[size_t(m.indices[i])]), b(m.P[size_t(m.indices[i + 1])]),
            c(m.P[size_t(m.indices[i + 2])]);
        Vec3d fn = Normalize(Cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            Vec3d n(m.N[size_t(m.indices[i + size_t(k)])]);
            EXPECT_NEAR(Length(n), 1.0, 1e-6);
            EXPECT_GT(Dot(fn, n), minCos) << what << " triangle " << i / 3;
        }
    }
}

TEST(NurbsTessellate, ChordalErrorIsBoundedAndDensityAtLeastPbrts) {
    std::vector<std::pair<const char *, NurbsPatch>> patches = {
        {"quarter cylinder", QuarterCylinder()}, {"sphere octant", SphereOctant(1.0)}};
    // A wavy bicubic with non-uniform knots.
    std::vector<Vec3d> P;
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 7; ++i) P.push_back(Vec3d(i, j, ((i * 7 + j * 3) % 5) * 0.8 - 1.6));
    patches.push_back({"wavy bicubic", Patch(7, 6, 4, 4, {0, 0, 0, 0, 0.1, 0.5, 0.6, 1, 1, 1, 1},
                                             {0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1}, P)});
    for (auto &[name, p] : patches) {
        NurbsTessellation t = TessellateNurbs(p);
        EXPECT_FALSE(t.capped) << name;
        EXPECT_GE(t.segmentsU, 29) << name;
        EXPECT_GE(t.segmentsV, 29) << name;
        EXPECT_LE(t.chordalError, t.tolerance) << name;
        // Between the measured points too: the mesh against the surface at random (u, v).
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> uni(0, 1);
        double worst = 0;
        for (int i = 0; i < 300; ++i) {
            double u = Lerp(uni(rng), p.u0, p.u1), v = Lerp(uni(rng), p.v0, p.v1);
            Vec3d m;
            // The octant's last row of cells ends in the pole: its collapsed triangles are
            // left out, so part of that row's (u, v) has no triangle.
            bool pole = std::string(name) == "sphere octant" && v > 1 - 1.0 / t.segmentsV;
            if (!MeshAt(t.mesh, u, v, &m)) {
                EXPECT_TRUE(pole) << name << " " << u << " " << v;
                continue;
            }
            worst = std::max(worst, Length(m - EvaluateNurbs(p, u, v).P));
        }
        EXPECT_LE(worst, 1.5 * t.tolerance) << name;
        ExpectWatertight(t.mesh, name);
        ExpectConsistentNormals(t.mesh, name);
    }
    // A quarter cylinder's vertices lie on the circle (float precision), and its chords
    // (sagitta of the finest segment) stay within the tolerance: 2e-4 of the diagonal.
    NurbsTessellation t = TessellateNurbs(QuarterCylinder());
    for (const Vec3f &q : t.mesh.P) EXPECT_NEAR(std::hypot(q.x, q.y), 1.0, 1e-6);
    double sagitta = 1 - std::cos(Pi / 4 / t.segmentsU);
    EXPECT_LE(sagitta, t.tolerance);
    EXPECT_NEAR(t.tolerance, 2e-4 * std::sqrt(1 + 1 + 4), 1e-9);
}

TEST(NurbsTessellate, RuledDirectionIsNotRefinedForTheOthersCurvature) {
    // A full unit cylinder of height 1 as one 9-point rational patch (4 arcs, doubled knots):
    // u refines until the chords are within tolerance, v (straight lines) stays at 29.
    const double w = std::sqrt(0.5);
    const double c[9][3] = {{1, 0, 1},   {1, 1, w},  {0, 1, 1},  {-1, 1, w}, {-1, 0, 1},
                            {-1, -1, w}, {0, -1, 1}, {1, -1, w}, {1, 0, 1}};
    NurbsPatch p;
    p.nu = 9;
    p.nv = 2;
    p.uorder = 3;
    p.vorder = 2;
    p.uknots = {0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1};
    p.vknots = {0, 0, 1, 1};
    p.u0 = 0, p.u1 = 1, p.v0 = 0, p.v1 = 1;
    for (double z : {0.0, 1.0})
        for (const auto &q : c) p.Pw.insert(p.Pw.end(), {q[0] * q[2], q[1] * q[2], z * q[2], q[2]});
    ValidateNurbs(p);
    NurbsTessellation t = TessellateNurbs(p);
    EXPECT_EQ(t.segmentsV, 29);
    EXPECT_GT(t.segmentsU, 64);
    EXPECT_LE(t.chordalError, t.tolerance);
    for (const Vec3f &q : t.mesh.P) EXPECT_NEAR(std::hypot(q.x, q.y), 1.0, 1e-6);
    ExpectWatertight(t.mesh, "cylinder");
    ExpectConsistentNormals(t.mesh, "cylinder", 0.99);
}

TEST(NurbsTessellate, BilinearPatchIsAPbrtGrid) {
    NurbsPatch p =
        Patch(2, 2, 2, 2, {0, 0, 1, 1}, {0, 0, 2, 2}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    NurbsTessellation t = TessellateNurbs(p);
    EXPECT_EQ(t.segmentsU, 29);
    EXPECT_EQ(t.segmentsV, 29);
    EXPECT_EQ(t.mesh.indices.size(), size_t(2 * 29 * 29 * 3));
    EXPECT_EQ(ExpectWatertight(t.mesh, "bilinear"), size_t(4 * 29));
    // uv is the parametric (u, v): v runs over [0, 2].
    float vmax = 0;
    for (const Vec2f &uv : t.mesh.uv) vmax = std::max(vmax, uv.y);
    EXPECT_EQ(vmax, 2.f);
    for (const Vec3f &n : t.mesh.N) EXPECT_EQ(n, Vec3f(0, 0, 1));  // du x dv = +z
    ExpectConsistentNormals(t.mesh, "bilinear", 0.999);
}

TEST(NurbsTessellate, CreaseKeepsBothNormalsAndStaysWatertight) {
    // Piecewise linear in u (order 2): a roof ridge at u = 1, knots with the ridge a knot.
    std::vector<Vec3d> P = {{0, 0, 0}, {1, 0, 1}, {2, 0, 0}, {0, 1, 0}, {1, 1, 1}, {2, 1, 0}};
    NurbsPatch p = Patch(3, 2, 2, 2, {0, 0, 1, 2, 2}, {0, 0, 1, 1}, P);
    NurbsTessellation t = TessellateNurbs(p);
    EXPECT_EQ(ExpectWatertight(t.mesh, "ridge"), size_t(2 * 29 + 2 * 30));
    ExpectConsistentNormals(t.mesh, "ridge", 0.999);
    // On the ridge (x = 1) both slopes' normals appear, each at the same positions.
    int left = 0, right = 0;
    for (size_t i = 0; i < t.mesh.P.size(); ++i)
        if (t.mesh.P[i].x == 1.f) {
            Vec3f n = t.mesh.N[i];
            left += std::abs(n.x + std::sqrt(0.5f)) < 1e-6f;
            right += std::abs(n.x - std::sqrt(0.5f)) < 1e-6f;
        }
    EXPECT_EQ(left, 30);
    EXPECT_EQ(right, 30);

    // A cubic with a triple interior knot (C0) is creased the same way, and exact on the
    // grid line (the knot is one).
    std::vector<Vec3d> Q;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 7; ++i) Q.push_back(Vec3d(i, j, i == 3 ? 2.0 : 0.3 * (i % 2)));
    NurbsPatch c =
        Patch(7, 4, 4, 4, {0, 0, 0, 0, 0.4, 0.4, 0.4, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, Q);
    NurbsTessellation tc = TessellateNurbs(c);
    ExpectWatertight(tc.mesh, "cubic crease");
    ExpectConsistentNormals(tc.mesh, "cubic crease");
    bool onRidge = false;
    for (const Vec3f &q : tc.mesh.P) onRidge |= q.x == 3.f && q.z == 2.f;
    EXPECT_TRUE(onRidge);

    // Full multiplicity: the surface breaks at the knot, and so does the mesh (the two
    // pieces end at their own control points).
    std::vector<Vec3d> B = {{0, 0, 0}, {1, 0, 1}, {2, 0, 0}, {3, 0, 5}, {4, 0, 1}, {5, 0, 0},
                            {0, 1, 0}, {1, 1, 1}, {2, 1, 0}, {3, 1, 5}, {4, 1, 1}, {5, 1, 0}};
    NurbsPatch b = Patch(6, 2, 3, 2, {0, 0, 0, 1, 1, 1, 2, 2, 2}, {0, 0, 1, 1}, B);
    ValidateNurbs(b);
    NurbsTessellation tb = TessellateNurbs(b);
    bool a2 = false, a3 = false;
    for (const Vec3f &q : tb.mesh.P) {
        a2 |= q == Vec3f(2, 0, 0);
        a3 |= q == Vec3f(3, 0, 5);
    }
    EXPECT_TRUE(a2 && a3);
}

TEST(NurbsTessellate, UnclampedKnotsAndSubrange) {
    // A uniform unclamped biquadratic over a 5 x 4 net, tessellated over a sub-range.
    std::vector<Vec3d> P;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 5; ++i) P.push_back(Vec3d(i, j, std::sin(i + 2.0 * j)));
    NurbsPatch p = Patch(5, 4, 3, 3, {0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6}, P);
    p.u0 = 2.5;
    p.u1 = 4.5;
    p.v0 = 2;
    p.v1 = 3.25;
    ValidateNurbs(p);
    NurbsTessellation t = TessellateNurbs(p);
    Vec2f lo(1e9f, 1e9f), hi(-1e9f, -1e9f);
    for (const Vec2f &uv : t.mesh.uv) {
        lo = Vec2f(std::min(lo.x, uv.x), std::min(lo.y, uv.y));
        hi = Vec2f(std::max(hi.x, uv.x), std::max(hi.y, uv.y));
    }
    EXPECT_EQ(lo, Vec2f(2.5f, 2.f));
    EXPECT_EQ(hi, Vec2f(4.5f, 3.25f));
    // The corner vertex is the surface there.
    for (size_t i = 0; i < t.mesh.P.size(); ++i)
        if (t.mesh.uv[i] == Vec2f(4.5f, 3.25f))
            EXPECT_NEAR(Length(Vec3d(t.mesh.P[i]) - EvaluateNurbs(p, 4.5, 3.25).P), 0, 1e-6);
    ExpectWatertight(t.mesh, "unclamped");
    ExpectConsistentNormals(t.mesh, "unclamped");
}

TEST(NurbsTessellate, StopsAtTheTriangleLimit) {
    NurbsTessellationOptions o;
    o.relativeTolerance = 1e-9;
    o.maxTriangles = 20000;
    NurbsTessellation t = TessellateNurbs(QuarterCylinder(), o);
    EXPECT_TRUE(t.capped);
    EXPECT_LE(t.mesh.indices.size() / 3, size_t(20000));
    o.maxTriangles = 100;  // below pbrt's 29 x 29 grid
    try {
        TessellateNurbs(QuarterCylinder(), o);
        FAIL();
    } catch (const PatchParamError &e) {
        EXPECT_STREQ(e.param, "nu");
    }
}

// The parameter each bad patch is reported at.
std::string BadParam(const std::function<void(NurbsPatch &)> &edit) {
    NurbsPatch p = QuarterCylinder();
    edit(p);
    try {
        ValidateNurbs(p);
    } catch (const PatchParamError &e) {
        return std::string(e.param) + ": " + e.what();
    }
    return "accepted";
}

TEST(NurbsValidate, EachBadParameterIsNamed) {
    auto starts = [](const std::string &s, const char *prefix) { return s.rfind(prefix, 0) == 0; };
    EXPECT_EQ(BadParam([](NurbsPatch &) {}), "accepted");
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.nu = 0; }), "nu: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uorder = 1; }), "uorder: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uorder = 4; }), "uorder: "));  // > nu
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.vorder = 3; }), "vorder: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uknots.pop_back(); }), "uknots: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.vknots = {0, 1, 0.5, 1}; }), "vknots: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uknots = {0, 0, 0, 0, 1, 1}; }), "uknots: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uknots = {0, 0, 1, 1, 1, 1}; }),
                       "uknots: "));  // empty domain
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.uknots[2] = NAN; }), "uknots: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.u0 = 0.5, p.u1 = 0.5; }), "u0: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.u0 = -0.1; }), "u0: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.v1 = 1.5; }), "v1: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.Pw.resize(20); }), "Pw: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.Pw[7] = 0; }), "Pw: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.Pw[7] = -1; }), "Pw: "));
    EXPECT_TRUE(starts(BadParam([](NurbsPatch &p) { p.Pw[4] = INFINITY; }), "Pw: "));
    EXPECT_NE(BadParam([](NurbsPatch &p) { p.Pw[7] = -1; }).find("weights must be positive"),
              std::string::npos);
}

TEST(Heightfield, GridSplitAndUV) {
    PatchMesh m = TessellateHeightfield(3, 2, {0, 1, 2, 3, 4, 5});
    ASSERT_EQ(m.P.size(), size_t(6));
    EXPECT_EQ(m.P[1], Vec3f(0.5f, 0, 1));
    EXPECT_EQ(m.P[5], Vec3f(1, 1, 5));
    EXPECT_EQ(m.uv[4], Vec2f(0.5f, 1));
    EXPECT_TRUE(m.N.empty());  // flat shading, as pbrt-v3
    // Two triangles per cell, split along (i, j)-(i+1, j+1), a flat field facing +z.
    EXPECT_EQ(m.indices, (std::vector<int>{0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4}));
    PatchMesh flat = TessellateHeightfield(4, 5, std::vector<double>(20, 0.0));
    for (size_t i = 0; i < flat.indices.size(); i += 3) {
        Vec3f a = flat.P[size_t(flat.indices[i])], b = flat.P[size_t(flat.indices[i + 1])],
              c = flat.P[size_t(flat.indices[i + 2])];
        EXPECT_GT(Cross(b - a, c - a).z, 0);
    }
    EXPECT_EQ(ExpectWatertight(flat, "heightfield"), size_t(2 * 3 + 2 * 4));
}

TEST(Heightfield, BadInputIsNamed) {
    auto param = [](int nu, int nv, std::vector<double> z) -> std::string {
        try {
            TessellateHeightfield(nu, nv, z);
        } catch (const PatchParamError &e) {
            return e.param;
        }
        return "accepted";
    };
    EXPECT_EQ(param(1, 3, {0, 0, 0}), "nu");
    EXPECT_EQ(param(2, 0, {}), "nv");
    EXPECT_EQ(param(2, 2, {0, 0, 0}), "Pz");
    EXPECT_EQ(param(2, 2, {0, 0, NAN, 0}), "Pz");
    EXPECT_EQ(param(1 << 20, 1 << 20, {0}), "nu");
    EXPECT_EQ(param(2, 2, {0, 0, 0, 0}), "accepted");
}

}  // namespace
}  // namespace prism
