// Loop subdivision: triangle counts, closed meshes stay closed, the limit surface stays
// inside the control hull, normals face outward, and straight boundaries stay straight.
#include "geometry/loop_subdiv.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace prism {
namespace {

const std::vector<Vec3f> TetraP = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
// Counter-clockwise seen from outside.
const std::vector<int> TetraIdx = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

const std::vector<Vec3f> CubeP = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const std::vector<int> CubeIdx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                  2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};

// Every directed edge must have exactly one opposite twin: closed and consistently wound.
void ExpectClosed(const LoopSubdivResult &r) {
    std::map<std::pair<int, int>, int> directed;
    for (size_t i = 0; i < r.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) directed[{r.indices[i + k], r.indices[i + (k + 1) % 3]}]++;
    for (const auto &[e, n] : directed) {
        EXPECT_EQ(n, 1);
        auto twin = directed.find({e.second, e.first});
        ASSERT_NE(twin, directed.end()) << "open edge " << e.first << "-" << e.second;
        EXPECT_EQ(twin->second, 1);
    }
}

TEST(LoopSubdiv, TetrahedronCountsClosedInsideHullOutwardNormals) {
    for (int levels = 0; levels <= 4; ++levels) {
        LoopSubdivResult r = LoopSubdivide(TetraP, TetraIdx, levels);
        EXPECT_EQ(r.indices.size() / 3, size_t(4) << (2 * levels));
        ExpectClosed(r);
        ASSERT_EQ(r.P.size(), r.N.size());
        for (size_t v = 0; v < r.P.size(); ++v) {
            const Vec3f &p = r.P[v];
            // Inside the tetrahedron: each face plane n·p <= d.
            for (size_t f = 0; f < TetraIdx.size(); f += 3) {
                Vec3f a = TetraP[size_t(TetraIdx[f])], b = TetraP[size_t(TetraIdx[f + 1])],
                      c = TetraP[size_t(TetraIdx[f + 2])];
                Vec3f n = Cross(b - a, c - a);
                EXPECT_LE(Dot(n, p - a), 1e-5f);
            }
            // The tetrahedron is symmetric about the origin: normals point away from it.
            EXPECT_GT(Dot(r.N[v], p), 0.f);
            EXPECT_NEAR(Length(r.N[v]), 1.f, 1e-5f);
        }
    }
}

TEST(LoopSubdiv, CubeCountsClosedShrinksInsideCube) {
    for (int levels = 0; levels <= 3; ++levels) {
        LoopSubdivResult r = LoopSubdivide(CubeP, CubeIdx, levels);
        EXPECT_EQ(r.indices.size() / 3, size_t(12) << (2 * levels));
        ExpectClosed(r);
        for (size_t v = 0; v < r.P.size(); ++v) {
            for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(r.P[v][c]), 1.f);
            EXPECT_GT(Dot(r.N[v], r.P[v]), 0.f);
        }
    }
}

TEST(LoopSubdiv, SymmetricTetrahedronLimitIsSymmetric) {
    // The regular tetrahedron's limit surface has its vertices' images on the diagonals.
    LoopSubdivResult r = LoopSubdivide(TetraP, TetraIdx, 2);
    for (int v = 0; v < 4; ++v) {
        Vec3f p = r.P[size_t(v)];
        Vec3f dir = Normalize(TetraP[size_t(v)]);
        EXPECT_NEAR(Length(Cross(p, dir)), 0.f, 1e-5f);
        EXPECT_NEAR(Dot(r.N[size_t(v)], dir), 1.f, 1e-4f);
    }
}

TEST(LoopSubdiv, FlatOpenPatchStaysFlatAndStraightBoundaryStaysStraight) {
    // A 3x2 grid of quads in z = 0 (12 triangles): open, with straight boundary sides.
    std::vector<Vec3f> P;
    for (int y = 0; y <= 2; ++y)
        for (int x = 0; x <= 3; ++x) P.push_back({float(x), float(y), 0});
    std::vector<int> idx;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            int a = y * 4 + x, b = a + 1, c = a + 5, d = a + 4;
            idx.insert(idx.end(), {a, b, c, a, c, d});
        }
    LoopSubdivResult r = LoopSubdivide(P, idx, 3);
    EXPECT_EQ(r.indices.size() / 3, size_t(12) * 64);
    for (size_t v = 0; v < r.P.size(); ++v) {
        EXPECT_EQ(r.P[v].z, 0.f);
        EXPECT_NEAR(r.N[v].z, 1.f, 1e-6f);  // counter-clockwise seen from +z
        EXPECT_GE(r.P[v].x, -1e-6f);
        EXPECT_LE(r.P[v].x, 3 + 1e-6f);
        EXPECT_GE(r.P[v].y, -1e-6f);
        EXPECT_LE(r.P[v].y, 2 + 1e-6f);
    }
    // Interior edges are shared by two triangles; boundary edges by one.
    std::map<std::pair<int, int>, int> uses;
    for (size_t i = 0; i < r.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            int a = r.indices[i + k], b = r.indices[i + (k + 1) % 3];
            uses[{std::min(a, b), std::max(a, b)}]++;
        }
    std::vector<bool> onBoundary(r.P.size(), false);
    int boundaryEdges = 0;
    for (const auto &[e, n] : uses) {
        EXPECT_LE(n, 2);
        if (n == 1) {
            ++boundaryEdges;
            onBoundary[size_t(e.first)] = onBoundary[size_t(e.second)] = true;
        }
    }
    EXPECT_EQ(boundaryEdges, (3 + 2) * 2 * 8);
    // The boundary is the cubic B-spline of the boundary polygon: between x = 1 and 2 its
    // control points (0,0) (1,0) (2,0) (3,0) are collinear, so the curve is the line y = 0,
    // with the 9 level-3 vertices evenly spaced on it.
    std::vector<float> xs;
    for (size_t v = 0; v < r.P.size(); ++v)
        if (onBoundary[v] && r.P[v].y < 0.5f && r.P[v].x >= 1 - 1e-6f && r.P[v].x <= 2 + 1e-6f) {
            EXPECT_NEAR(r.P[v].y, 0.f, 1e-6f);
            xs.push_back(r.P[v].x);
        }
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(xs.size(), size_t(9));
    for (size_t i = 0; i < xs.size(); ++i) EXPECT_NEAR(xs[i], 1 + 0.125f * float(i), 1e-5f);
    // Corners are rounded off: no limit vertex sits at (0, 0).
    for (size_t v = 0; v < r.P.size(); ++v) EXPECT_GT(r.P[v].x + r.P[v].y, 0.05f);
}

TEST(LoopSubdiv, BoundaryCornerFollowsTheBoundaryRule) {
    // One triangle: its boundary is the closed cubic B-spline of the triangle, so corner 0
    // lands on (p2 + 4 p0 + p1) / 6 at every level. Level 1 by hand: the corner becomes
    // 3/4·0 + 1/8·((8,0)+(0,8)) = (1,1) with boundary neighbours (4,0) and (0,4); the limit
    // mask (1/6, 4/6, 1/6) gives 4/6·(1,1) + 1/6·(4,4) = (4/3, 4/3).
    std::vector<Vec3f> P = {{0, 0, 0}, {8, 0, 0}, {0, 8, 0}};
    for (int levels : {0, 1, 4}) {
        LoopSubdivResult r = LoopSubdivide(P, {0, 1, 2}, levels);
        ASSERT_EQ(r.indices.size(), size_t(3) << (2 * levels));
        EXPECT_NEAR(r.P[0].x, 4.f / 3, 1e-5f);
        EXPECT_NEAR(r.P[0].y, 4.f / 3, 1e-5f);
    }
}

// Limit positions and normals are properties of the surface, not of the level: a control
// vertex of level L is still a vertex of level L + 2 and must land on the same limit point
// with the same normal. This checks the limit and tangent masks (interior and boundary).
void ExpectLimitInvariant(const std::vector<Vec3f> &P, const std::vector<int> &idx, float tol) {
    LoopSubdivResult a = LoopSubdivide(P, idx, 1), b = LoopSubdivide(P, idx, 3);
    for (size_t v = 0; v < a.P.size(); ++v) {
        EXPECT_NEAR(Length(a.P[v] - b.P[v]), 0.f, tol) << "vertex " << v;
        EXPECT_GT(Dot(a.N[v], b.N[v]), 1 - tol) << "vertex " << v;
    }
}

TEST(LoopSubdiv, LimitPointsAndNormalsDoNotDependOnTheLevel) {
    ExpectLimitInvariant(TetraP, TetraIdx, 1e-5f);
    ExpectLimitInvariant(CubeP, CubeIdx, 1e-5f);  // valences 4 and 5 and 6
    // An open, non-planar fan (a boundary of valence 5) and a saddle.
    std::vector<Vec3f> P = {{0, 0, 0},    {1, 0, 0.3f},        {0.7f, 0.7f, -0.2f},
                            {0, 1, 0.4f}, {-0.7f, 0.7f, 0.1f}, {-1, 0, -0.3f}};
    ExpectLimitInvariant(P, {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5}, 1e-5f);
}

TEST(LoopSubdiv, RejectsBadInputAndHugeOutput) {
    EXPECT_THROW(LoopSubdivide(TetraP, TetraIdx, -1), std::invalid_argument);
    EXPECT_THROW(LoopSubdivide(TetraP, TetraIdx, MaxLoopSubdivLevels + 1), std::invalid_argument);
    EXPECT_THROW(LoopSubdivide(TetraP, {0, 1}, 1), std::invalid_argument);
    EXPECT_THROW(LoopSubdivide(TetraP, {0, 1, 7}, 1), std::invalid_argument);
    EXPECT_THROW(LoopSubdivide(TetraP, {0, -1, 2}, 1), std::invalid_argument);
    std::vector<int> many;
    for (int i = 0; i < 200; ++i) many.insert(many.end(), TetraIdx.begin(), TetraIdx.end());
    EXPECT_THROW(LoopSubdivide(TetraP, many, 8), std::invalid_argument);  // 800·4^8 > 4M
    LoopSubdivResult r = LoopSubdivide(TetraP, {0, 0, 1, 0, 1, 2}, 1);
    EXPECT_EQ(r.droppedFaces, 1);
    EXPECT_EQ(r.indices.size(), size_t(12));
}

TEST(LoopSubdiv, NonManifoldEdgeDoesNotCrash) {
    // Three triangles on one edge: treated as a crease.
    std::vector<Vec3f> P = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    LoopSubdivResult r = LoopSubdivide(P, {0, 1, 2, 1, 0, 3, 0, 1, 4}, 2);
    EXPECT_EQ(r.indices.size() / 3, size_t(3 * 16));
    for (const Vec3f &n : r.N) EXPECT_NEAR(Length(n), 1.f, 1e-5f);
}

}  // namespace
}  // namespace prism
