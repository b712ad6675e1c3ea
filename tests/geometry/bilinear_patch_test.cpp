// Bilinear patch meshes (pbrt-v4's Shape "bilinearmesh"): the tessellation against the exact
// patch evaluated in long double (its departure within the tolerance, the vertices on the
// patch), winding against dp/du x dp/dv, uv and normals, the triangle cap, and each
// validation error.
#include "geometry/bilinear_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace prism {
namespace {

using LD = long double;

struct LDVec {
    LD x, y, z;
};

// The exact patch point at (u, v), written out independently of the library.
LDVec Exact(const BilinearMesh &m, size_t patch, LD u, LD v) {
    const int *ix = &m.indices[4 * patch];
    auto c = [&](int k, int axis) -> LD {
        const Vec3f &p = m.P[size_t(ix[k])];
        return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
    };
    LDVec r;
    LD *out[3] = {&r.x, &r.y, &r.z};
    for (int a = 0; a < 3; ++a)
        *out[a] =
            (1 - u) * ((1 - v) * c(0, a) + v * c(2, a)) + u * ((1 - v) * c(1, a) + v * c(3, a));
    return r;
}

LD Dist(const LDVec &a, const LDVec &b) {
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                     (a.z - b.z) * (a.z - b.z));
}

BilinearMesh Saddle(float h) {
    BilinearMesh m;
    m.P = {{-1, -h, -1}, {1, h, -1}, {-1, h, 1}, {1, -h, 1}};
    m.indices = {0, 1, 2, 3};
    return m;
}

TEST(BilinearPatch, FlatQuadIsTwoTrianglesWithItsUV) {
    BilinearMesh m;
    m.P = {{0, 0, 0}, {2, 0, 0}, {0, 0, 3}, {2, 0, 3}};
    m.indices = {0, 1, 2, 3};
    std::vector<int> seg = BilinearSegments(m);
    ASSERT_EQ(seg, std::vector<int>{1});
    PatchMesh t = TessellateBilinearMesh(m, seg);
    ASSERT_EQ(t.indices.size(), 6u);
    EXPECT_TRUE(t.N.empty());  // flat: no shading normals
    ASSERT_EQ(t.uv.size(), 4u);
    EXPECT_EQ(t.uv[0], Vec2f(0, 0));
    EXPECT_EQ(t.uv[1], Vec2f(1, 0));
    EXPECT_EQ(t.uv[2], Vec2f(0, 1));
    EXPECT_EQ(t.uv[3], Vec2f(1, 1));
    // dp/du = +x, dp/dv = +z: the triangles face +x cross +z = -y.
    for (size_t k = 0; k < t.indices.size(); k += 3) {
        Vec3f p0 = t.P[size_t(t.indices[k])], p1 = t.P[size_t(t.indices[k + 1])],
              p2 = t.P[size_t(t.indices[k + 2])];
        Vec3f n = Cross(p1 - p0, p2 - p0);
        EXPECT_LT(n.y, 0);
        EXPECT_EQ(n.x, 0);
        EXPECT_EQ(n.z, 0);
    }
}

// The saddle's tessellation stays within the tolerance of the exact patch at random points
// (each compared with the point of its triangle at the same (u, v)), and every vertex lies on
// the patch.
TEST(BilinearPatch, TessellationIsWithinTheToleranceOfTheExactPatch) {
    for (double relTol : {2e-4, 1e-3, 1e-2}) {
        SCOPED_TRACE(relTol);
        BilinearMesh m = Saddle(0.6f);
        std::vector<int> seg = BilinearSegments(m, relTol);
        const int n = seg[0];
        ASSERT_GT(n, 1);
        PatchMesh t = TessellateBilinearMesh(m, seg);
        ASSERT_EQ(t.indices.size(), size_t(6 * n * n));
        // The patch's bounding box is 2 x 1.2 x 2.
        const LD tol = LD(relTol) * std::sqrt(LD(2 * 2 + 1.2 * 1.2 + 2 * 2));
        for (size_t i = 0; i < t.P.size(); ++i) {
            const Vec2f uv = t.uv[i];
            LDVec e = Exact(m, 0, uv.x, uv.y);
            EXPECT_LT(Dist(e, LDVec{t.P[i].x, t.P[i].y, t.P[i].z}), 1e-6L);
        }
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> U(0, 1);
        LD worst = 0;
        for (int s = 0; s < 20000; ++s) {
            const LD u = U(rng), v = U(rng);
            // The cell and the triangle of (u, v): (0,0)-(1,0)-(1,1) when its x >= y.
            const int i = std::min(n - 1, int(u * n)), j = std::min(n - 1, int(v * n));
            const LD x = u * n - i, y = v * n - j;
            auto corner = [&](int di, int dj) {
                return Exact(m, 0, LD(i + di) / n, LD(j + dj) / n);
            };
            LDVec a = corner(0, 0), b = x >= y ? corner(1, 0) : corner(1, 1),
                  c = x >= y ? corner(1, 1) : corner(0, 1);
            // Barycentric weights of the planar triangle at (x, y).
            LD wa, wb, wc;
            if (x >= y) {
                wa = 1 - x, wb = x - y, wc = y;
            } else {
                wa = 1 - y, wb = x, wc = y - x;
            }
            LDVec p{wa * a.x + wb * b.x + wc * c.x, wa * a.y + wb * b.y + wc * c.y,
                    wa * a.z + wb * b.z + wc * c.z};
            worst = std::max(worst, Dist(p, Exact(m, 0, u, v)));
        }
        EXPECT_LE(worst, tol);
        // And not far finer than it needs: the grid one coarser would exceed the tolerance.
        const LD twist = std::sqrt(LD(4 * 1.2 * 1.2));
        EXPECT_GT(twist / (4 * LD(n - 1) * (n - 1)), tol);
    }
}

TEST(BilinearPatch, CurvedPatchesGetNormalsFacingDpduCrossDpdv) {
    BilinearMesh m = Saddle(0.6f);
    PatchMesh t = TessellateBilinearMesh(m, BilinearSegments(m));
    ASSERT_EQ(t.N.size(), t.P.size());
    for (size_t k = 0; k < t.indices.size(); k += 3) {
        const int a = t.indices[k], b = t.indices[k + 1], c = t.indices[k + 2];
        Vec3f ng = Cross(t.P[size_t(b)] - t.P[size_t(a)], t.P[size_t(c)] - t.P[size_t(a)]);
        EXPECT_GT(Dot(ng, t.N[size_t(a)] + t.N[size_t(b)] + t.N[size_t(c)]), 0);
    }
    // At the patch's centre dp/du = (2, 0, 0), dp/dv = (0, 0, 2): the normal is -y.
    for (size_t i = 0; i < t.P.size(); ++i)
        if (t.uv[i] == Vec2f(0.5f, 0.5f)) {
            EXPECT_NEAR(t.N[i].y, -1, 1e-6);
        }
}

TEST(BilinearPatch, GivenUVAndNormalsAreInterpolated) {
    BilinearMesh m = Saddle(0.6f);
    m.uv = {{0, 0}, {4, 0}, {0, 2}, {4, 2}};
    m.N = {{0, 1, 0}, {0, 1, 0}, {1, 0, 0}, {1, 0, 0}};
    PatchMesh t = TessellateBilinearMesh(m, BilinearSegments(m));
    ASSERT_EQ(t.N.size(), t.P.size());
    for (size_t i = 0; i < t.P.size(); ++i) {
        // uv = (4u, 2v); N = normalize(lerp(v, +y, +x)).
        const Vec2f uv = t.uv[i];
        const float v = uv.y / 2;
        const Vec3f want = Normalize(Vec3f(v, 1 - v, 0));
        EXPECT_NEAR(t.N[i].x, want.x, 1e-5);
        EXPECT_NEAR(t.N[i].y, want.y, 1e-5);
        EXPECT_NEAR(t.N[i].z, 0, 1e-6);
    }
}

TEST(BilinearPatch, TheMeshStaysWithinItsTriangleCap) {
    BilinearMesh m = Saddle(0.6f);
    for (int k = 1; k < 100; ++k) {
        for (int c = 0; c < 4; ++c) m.P.push_back(m.P[size_t(c)] + Vec3f(3.f * k, 0, 0));
        for (int c = 0; c < 4; ++c) m.indices.push_back(4 * k + c);
    }
    std::vector<int> free = BilinearSegments(m, 2e-4);
    ASSERT_GT(BilinearTriangles(free), 10000u);
    std::vector<int> capped = BilinearSegments(m, 2e-4, 10000);
    EXPECT_LE(BilinearTriangles(capped), 10000u);
    EXPECT_GT(BilinearTriangles(capped), 5000u);
}

TEST(BilinearPatch, ValidationNamesTheParameter) {
    auto err = [](BilinearMesh m) -> std::string {
        try {
            ValidateBilinearMesh(m);
        } catch (const PatchParamError &e) {
            return std::string(e.param) + ": " + e.what();
        }
        return "none";
    };
    BilinearMesh ok = Saddle(0.5f);
    EXPECT_EQ(err(ok), "none");
    BilinearMesh m = ok;
    m.P.clear();
    EXPECT_EQ(err(m).rfind("P: ", 0), 0u) << err(m);
    m = ok;
    m.indices.clear();
    EXPECT_EQ(err(m).rfind("indices: ", 0), 0u) << err(m);
    m = ok;
    m.indices.push_back(0);
    EXPECT_NE(err(m).find("not a multiple of 4"), std::string::npos) << err(m);
    m = ok;
    m.indices[2] = 4;
    EXPECT_NE(err(m).find("out of range"), std::string::npos) << err(m);
    m = ok;
    m.indices[2] = -1;
    EXPECT_NE(err(m).find("out of range"), std::string::npos) << err(m);
    m = ok;
    m.N = {{0, 1, 0}};
    EXPECT_EQ(err(m).rfind("N: ", 0), 0u) << err(m);
    m = ok;
    m.uv = {{0, 0}, {1, 1}};
    EXPECT_EQ(err(m).rfind("uv: ", 0), 0u) << err(m);
    m = ok;
    m.P[3].x = NAN;
    EXPECT_NE(err(m).find("not finite"), std::string::npos) << err(m);
}

}  // namespace
}  // namespace prism
