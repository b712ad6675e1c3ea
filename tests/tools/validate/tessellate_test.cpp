// Tessellated twins of the analytic shapes: vertices on the surface, winding that agrees with
// the analytic normal (through transforms, mirrors and ReverseOrientation), watertight closed
// meshes, and a chord error and shading-normal error that shrink as O(1/n^2).
#include "tools/validate/tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "geometry/accel.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/hyperboloid.h"
#include "geometry/paraboloid.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"

namespace prism {
namespace {

using Maker = std::unique_ptr<AnalyticShape> (*)(const Transform &, bool);

struct Case {
    const char *name;
    Maker make;
    bool closed;
};

const Case kCases[] = {
    {"sphere",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Sphere>(w, r, 1.3, -1.3, 1.3, 360);
     },
     true},
    {"partial-sphere",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Sphere>(w, r, 1, -0.5, 0.3, 270);
     },
     false},
    {"cylinder",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Cylinder>(w, r, 0.7, -1, 0.5, 360);
     },
     false},
    {"partial-cylinder",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Cylinder>(w, r, 0.7, -1, 0.5, 120);
     },
     false},
    {"disk",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Disk>(w, r, 0.2, 1, 0, 360);
     },
     false},
    {"annulus",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Disk>(w, r, 0.2, 1, 0.4, 300);
     },
     false},
    {"cone",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Cone>(w, r, 1, 1.5, 360);
     },
     false},
    {"paraboloid",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Paraboloid>(w, r, 1, 0, 1.5, 360);
     },
     false},
    {"partial-paraboloid",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Paraboloid>(w, r, 1, 0.3, 1.5, 200);
     },
     false},
    {"hyperboloid",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Hyperboloid>(w, r, Vec3d(1, -1, -1), Vec3d(1, 1, 1), 360);
     },
     false},
    {"hyperboloid-reversed",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Hyperboloid>(w, r, Vec3d(0.5, 1, 1), Vec3d(1, 0, -0.5), 250);
     },
     false},
    {"torus",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Torus>(w, r, 1, 0.3, 360);
     },
     true},
    {"partial-torus",
     [](const Transform &w, bool r) -> std::unique_ptr<AnalyticShape> {
         return std::make_unique<Torus>(w, r, 1, 0.3, 210);
     },
     false},
};

TEST(Tessellate, VerticesLieOnTheSurface) {
    for (const Case &c : kCases)
        for (int n : {8, 61, 256}) {
            auto s = c.make(Transform(), false);
            TessellatedMesh m;
            ASSERT_TRUE(Tessellate(*s, n, &m)) << c.name;
            Bounds3d b = s->ObjectBounds();
            double scale = Length(b.Diagonal());
            for (size_t i = 0; i < m.P.size(); ++i) {
                const Vec3d &p = m.P[i];
                // First-order distance from the shape's own implicit function (independent
                // of the tessellator's profile description).
                double g = Length(s->ImplicitGradient(p));
                double dist = g > 0 ? std::abs(s->Implicit(p)) / g : std::abs(s->Implicit(p));
                ASSERT_LE(dist, 1e-12 * scale) << c.name << " n=" << n << " vertex " << i;
                for (int k = 0; k < 3; ++k) {
                    ASSERT_GE(p[k], b.pMin[k] - 1e-12 * scale) << c.name;
                    ASSERT_LE(p[k], b.pMax[k] + 1e-12 * scale) << c.name;
                }
                ASSERT_NEAR(Length(m.N[i]), 1, 1e-12);
                ASSERT_GE(m.uv[i].x, -1e-12);
                ASSERT_LE(m.uv[i].x, 1 + 1e-12);
            }
        }
}

TEST(Tessellate, RingsFollowTheCurvature) {
    auto s = kCases[0].make(Transform(), false);
    TessellatedMesh m;
    ASSERT_TRUE(Tessellate(*s, 64, &m));
    EXPECT_EQ(m.nV, 32);  // n_theta = n_phi / 2 for the full sphere
    // Pole fans: 2 triangles per quad, 1 per pole cell.
    EXPECT_EQ(m.indices.size() / 3, size_t(64 * (2 * 32 - 2)));
    auto cyl = kCases[2].make(Transform(), false);
    ASSERT_TRUE(Tessellate(*cyl, 64, &m));
    EXPECT_EQ(m.nV, 1);  // straight profile: exact along z
}

TEST(Tessellate, WindingAgreesWithTheAnalyticNormal) {
    for (const Case &c : kCases)
        for (int n : {8, 40}) {
            auto s = c.make(Transform(), false);
            TessellatedMesh m;
            ASSERT_TRUE(Tessellate(*s, n, &m));
            for (size_t t = 0; t < m.indices.size(); t += 3) {
                const uint32_t *v = &m.indices[t];
                Vec3d cr = Cross(m.P[v[1]] - m.P[v[0]], m.P[v[2]] - m.P[v[0]]);
                ASSERT_GT(Length(cr), 0) << c.name << " degenerate triangle " << t / 3;
                for (int k = 0; k < 3; ++k)
                    ASSERT_GT(Dot(cr, m.N[v[k]]), 0) << c.name << " n=" << n << " tri " << t / 3;
            }
        }
}

// End to end through Embree: for each triangle, a ray at its centroid from the side its
// normal points to hits both the twin and the analytic shape with normals that agree, under a
// plain transform, a mirror, and ReverseOrientation.
TEST(Tessellate, TwinNormalsMatchAnalyticThroughTransforms) {
    const std::pair<Transform, bool> setups[] = {
        {Translate(Vec3d(0.5, -1, 2)) * Rotate(31, Vec3d(1, 1, 0)), false},
        {Scale(-1, 1, 1) * Rotate(10, Vec3d(0, 0, 1)), false},
        {Scale(1.5, 0.7, 1.2), true},
        {Scale(-2, 2, 2), true},
    };
    for (const Case &c : kCases)
        for (const auto &[w, rev] : setups) {
            Accel a, m(AccelOptions{Precision::Double, true, BvhQuality::Auto});
            a.AddAnalytic(c.make(w, rev));
            a.Commit();
            const AnalyticShape &s = *a.Analytic(0);
            m.AddMesh(MakeTessellatedMesh(s, 24));
            m.Commit();
            const TriangleMesh &tri = *m.Mesh(0);
            int checked = 0;
            for (size_t t = 0; t < tri.NumTriangles(); t += 3) {
                const uint32_t *v = tri.Triangle(t);
                Vec3f cen =
                    (tri.Position(v[0]) + tri.Position(v[1]) + tri.Position(v[2])) * (1.f / 3);
                Vec3f ng = tri.GeometricNormal(t);
                Ray r{cen + ng * 0.2f, -ng, Infinity, 0};
                SurfaceInteraction sa, sm;
                if (!a.Intersect(r, &sa) || !m.Intersect(r, &sm) || sm.prim != int(t)) continue;
                if (std::abs(sa.t - sm.t) > 0.1f) continue;  // a different sheet: not this patch
                ++checked;
                ASSERT_GT(Dot(sa.n, ng), 0.5f) << c.name << " triangle " << t;
                // The O(n^-2) bound of ShadingNormalsConvergeAsNSquared at n = 24 (11.8 degrees;
                // this was 26 degrees, which the cone's axis apex normal needed).
                const double step = 2 * Pi / 24;
                ASSERT_GT(Dot(sa.n, sm.ns), float(std::cos(3 * step * step)))
                    << c.name << " shading normal, triangle " << t;
            }
            EXPECT_GT(checked, 5) << c.name;
        }
}

// Largest angle (radians) between the analytic normal and the twin's interpolated shading
// normal, over rays along the geometric normal at barycentric points of every triangle (up to
// about 3000 triangles, evenly strided), including points next to each vertex.
double MaxShadingNormalError(const Case &c, const Transform &w, bool rev, int n) {
    Accel a, m(AccelOptions{Precision::Double, true, BvhQuality::Auto});
    a.AddAnalytic(c.make(w, rev));
    a.Commit();
    m.AddMesh(MakeTessellatedMesh(*a.Analytic(0), n));
    m.Commit();
    const TriangleMesh &tri = *m.Mesh(0);
    size_t stride = std::max<size_t>(1, tri.NumTriangles() / 3000);
    const float bary[][2] = {{1 / 3.f, 1 / 3.f}, {0.9f, 0.05f}, {0.05f, 0.9f}, {0.05f, 0.05f},
                             {0.5f, 0.25f},      {0.25f, 0.5f}, {0.25f, 0.25f}};
    double worst = 0;
    int checked = 0;
    for (size_t t = 0; t < tri.NumTriangles(); t += stride) {
        const uint32_t *v = tri.Triangle(t);
        Vec3f ng = tri.GeometricNormal(t);
        for (const auto &b : bary) {
            Vec3f p = tri.Position(v[0]) * (1 - b[0] - b[1]) + tri.Position(v[1]) * b[0] +
                      tri.Position(v[2]) * b[1];
            Ray r{p + ng * 0.05f, -ng, Infinity, 0};
            SurfaceInteraction sa, sm;
            if (!a.Intersect(r, &sa) || !m.Intersect(r, &sm) || sm.prim != int(t)) continue;
            if (std::abs(sa.t - sm.t) > 0.04f) continue;  // a different sheet: not this patch
            ++checked;
            Vec3d x(sa.n), y(sm.ns);
            worst = std::max(worst, std::atan2(Length(Cross(x, y)), Dot(x, y)));
        }
    }
    EXPECT_GT(checked, 5 * std::min<int>(int(tri.NumTriangles()), 3000) / int(stride) / 2)
        << c.name << " n=" << n;
    return worst;
}

// Interpolated vertex normals converge as O(n^-2) everywhere, fans included: within
// 3 (2 pi / n)^2 radians (0.2 degrees at n = 64). At the cone's apex an axis normal was 56
// degrees off at every n, which no bound shrinking with n accepts.
TEST(Tessellate, ShadingNormalsConvergeAsNSquared) {
    const std::pair<Transform, bool> setups[] = {
        {Transform(), false},
        {Translate(Vec3d(0.5, -1, 2)) * Rotate(31, Vec3d(1, 1, 0)) * Scale(1.5, 0.7, 1.2), true},
    };
    for (const Case &c : kCases)
        for (const auto &[w, rev] : setups)
            for (int n : {16, 64, 256}) {
                double step = 2 * Pi / n;
                double worst = MaxShadingNormalError(c, w, rev, n);
                EXPECT_LE(worst, 3 * step * step)
                    << c.name << " n=" << n << ": " << Degrees(worst) << " degrees";
            }
}

TEST(Tessellate, ClosedShapesAreWatertight) {
    for (const Case &c : kCases) {
        if (!c.closed) continue;
        for (int n : {3, 8, 33, 128}) {
            auto s = c.make(Transform(), false);
            TessellatedMesh m;
            ASSERT_TRUE(Tessellate(*s, n, &m));
            // Edge-manifold and consistently oriented: every directed edge once, its reverse once.
            std::map<std::pair<uint32_t, uint32_t>, int> directed;
            for (size_t t = 0; t < m.indices.size(); t += 3)
                for (int k = 0; k < 3; ++k)
                    ++directed[{m.indices[t + k], m.indices[t + (k + 1) % 3]}];
            for (const auto &[e, count] : directed) {
                ASSERT_EQ(count, 1) << c.name << " n=" << n;
                ASSERT_EQ(directed.count({e.second, e.first}), 1u)
                    << c.name << " n=" << n << " open edge";
            }
            // Euler characteristic: 2 for the sphere, 0 for the torus.
            long V = long(m.P.size()), E = long(directed.size() / 2),
                 F = long(m.indices.size() / 3);
            EXPECT_EQ(V - E + F, std::string(c.name) == "sphere" ? 2 : 0) << c.name;
        }
    }
}

// docs/SHAPES.md T2 on the twins: rays from inside toward every vertex and edge midpoint
// (the hardest targets for watertightness) never escape the robust BVH.
TEST(Tessellate, NoLeaksTowardVerticesAndEdges) {
    for (const Case &c : kCases) {
        if (std::string(c.name) != "sphere") continue;
        for (const Transform &w :
             {Transform(), Translate(Vec3d(1e4, 0, 0)) * Scale(1e-3, 1e-3, 1e-3)}) {
            auto s = c.make(w, false);
            Accel m(AccelOptions{Precision::Double, true, BvhQuality::Auto});
            auto mesh = MakeTessellatedMesh(*s, 96);
            const TriangleMesh *tri = mesh.get();
            m.AddMesh(std::move(mesh));
            m.Commit();
            Vec3f centre = Vec3f(w.Point(Vec3d(0.1, -0.05, 0.2)));
            int edgeLeaks = 0, vertexLeaks = 0, total = 0;
            for (size_t t = 0; t < tri->NumTriangles(); ++t) {
                const uint32_t *v = tri->Triangle(t);
                for (int k = 0; k < 3; ++k) {
                    Vec3f a = tri->Position(v[k]), b = tri->Position(v[(k + 1) % 3]);
                    RawHit h;
                    ++total;
                    if (!m.IntersectRaw(Ray{centre, (a + b) * 0.5f - centre, Infinity, 0}, &h))
                        ++edgeLeaks;
                    if (!m.IntersectRaw(Ray{centre, a - centre, Infinity, 0}, &h)) ++vertexLeaks;
                }
            }
            EXPECT_EQ(edgeLeaks, 0) << total << " rays";
            // Rays aimed exactly at a vertex may slip through Embree's ROBUST mode
            // (docs/SHAPES.md T2 accepts <= 0.5% as a documented Embree limitation).
            EXPECT_LE(vertexLeaks, total / 200) << total << " rays";
        }
    }
}

TEST(Tessellate, ChordErrorIsSecondOrder) {
    for (const Case &c : kCases) {
        auto s = c.make(Transform(), false);
        RevolutionProfile pr;
        ASSERT_TRUE(s->Revolution(&pr));
        TessellatedMesh m32, m128;
        ASSERT_TRUE(Tessellate(*s, 32, &m32));
        ASSERT_TRUE(Tessellate(*s, 128, &m128));
        double h32 = ChordError(pr, m32), h128 = ChordError(pr, m128);
        ASSERT_GT(h32, 0) << c.name;
        double ratio = h32 / h128;  // 16 for O(1/n^2)
        // ceil() of the derived ring count keeps short, gently curved profiles off the exact 16.
        EXPECT_GT(ratio, 8) << c.name;
        EXPECT_LT(ratio, 20) << c.name;
    }
    // The sphere's band is the classic sagitta r (1 - cos(pi/n)) (docs/SHAPES.md V1), up to
    // the contribution of the theta direction.
    auto s = kCases[0].make(Transform(), false);
    RevolutionProfile pr;
    s->Revolution(&pr);
    TessellatedMesh m;
    Tessellate(*s, 64, &m);
    double sag = 1.3 * (1 - std::cos(Pi / 64));
    double h = ChordError(pr, m);
    EXPECT_GE(h, sag * 0.99);
    EXPECT_LE(h, sag * 2.01);
}

TEST(Tessellate, DistancesToSilhouetteAndBoundary) {
    Sphere sph(Transform(), false, 1, -1, 1, 360);
    RevolutionProfile pr;
    ASSERT_TRUE(sph.Revolution(&pr));
    // A ray passing at distance 1.01 from the centre: a near miss by 0.01.
    EXPECT_NEAR(DistanceToTangency(pr, Vec3d(-3, 1.01, 0), Vec3d(1, 0, 0), 0, 6), 0.01, 1e-9);
    // At 0.98: a graze 0.02 deep.
    EXPECT_NEAR(DistanceToTangency(pr, Vec3d(-3, 0.98, 0), Vec3d(1, 0, 0), 0, 6), 0.02, 1e-9);
    // Through the centre: a transversal crossing, depth r.
    EXPECT_NEAR(DistanceToTangency(pr, Vec3d(-3, 0, 0), Vec3d(1, 0, 0), 0, 6), 1, 1e-9);
    // A full sphere has no boundary.
    EXPECT_TRUE(std::isinf(DistanceToBoundary(pr, Vec3d(-3, 0, 0), Vec3d(1, 0, 0), 0, 6)));
    // A cylinder's rim at z = 0.5, radius 1: a ray along x at height 0.6 through the axis.
    Cylinder cyl(Transform(), false, 1, -0.5, 0.5, 360);
    ASSERT_TRUE(cyl.Revolution(&pr));
    EXPECT_NEAR(DistanceToBoundary(pr, Vec3d(-3, 0, 0.6), Vec3d(1, 0, 0), 0, 6), 0.1, 1e-9);
}

}  // namespace
}  // namespace prism
