// CSG (geometry/csg.h): union, intersection and difference of two overlapping spheres and of a
// sphere with a closed mesh cube, against the analytic answers, through one Accel, with shadow
// rays; and a lens (intersection of two spheres) that focuses like a thick lens.
#include "geometry/csg.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/accel.h"
#include "geometry/sphere.h"

namespace prism {
namespace {

std::unique_ptr<Sphere> MakeSphere(Vec3d c, double r) {
    return std::make_unique<Sphere>(Translate(c), false, r, -r, r, 360);
}

// The cube [-h, h]^3 as 12 triangles over 8 shared vertices; `inward` winds them inward.
std::unique_ptr<TriangleMesh> MakeCube(double h, bool inward = false) {
    std::vector<Vec3f> P;
    for (int i = 0; i < 8; ++i)
        P.push_back(Vec3f(float(i & 1 ? h : -h), float(i & 2 ? h : -h), float(i & 4 ? h : -h)));
    // Outward winding ((p1 - p0) x (p2 - p0) points out).
    std::vector<uint32_t> idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    if (inward)
        for (size_t t = 0; t < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
    return std::make_unique<TriangleMesh>(Transform(), false, P, idx);
}

// A = sphere r 1 at the origin (leaf 0), B = sphere r 0.9 at (1, 0, 0) (leaf 1).
std::unique_ptr<Accel> TwoSpheres(CsgOp op) {
    auto csg = std::make_unique<CsgShape>();
    int a = csg->AddLeaf(MakeSphere(Vec3d(0, 0, 0), 1));
    int b = csg->AddLeaf(MakeSphere(Vec3d(1, 0, 0), 0.9));
    csg->AddNode(op, {{true, a}, {true, b}});
    csg->Finish();
    auto accel = std::make_unique<Accel>();
    accel->AddAnalytic(std::move(csg));
    accel->Commit();
    return accel;
}

struct Expect {
    bool hit;
    Vec3f p, n;  // expected point and outward normal of the result
    int part;
};

void Check(const Accel &accel, Ray ray, const Expect &e, const char *what) {
    SCOPED_TRACE(what);
    SurfaceInteraction si;
    bool hit = accel.Intersect(ray, &si);
    ASSERT_EQ(hit, e.hit);
    // Shadow rays use the same routine: occluded up to just past the hit, free before it.
    EXPECT_EQ(accel.Occluded(ray), e.hit);
    if (!hit) return;
    EXPECT_NEAR(si.p.x, e.p.x, 1e-5f);
    EXPECT_NEAR(si.p.y, e.p.y, 1e-5f);
    EXPECT_NEAR(si.p.z, e.p.z, 1e-5f);
    Vec3f n = Normalize(e.n);
    EXPECT_NEAR(si.n.x, n.x, 1e-5f);
    EXPECT_NEAR(si.n.y, n.y, 1e-5f);
    EXPECT_NEAR(si.n.z, n.z, 1e-5f);
    EXPECT_EQ(si.instanceShape, e.part);
    EXPECT_NEAR(si.t, Length(si.p - ray.o) / Length(ray.d), 1e-5f);
    Ray before = ray;
    before.tMax = si.t * 0.999f;
    EXPECT_FALSE(accel.Occluded(before));
}

const float yA = std::sqrt(0.75f);          // |y| of A at x = 0.5
const float yB = std::sqrt(0.81f - 0.25f);  // |y| of B at x = 0.5

TEST(Csg, TwoSpheresUnion) {
    auto accel = TwoSpheres(CsgOp::Union);
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {true, {-1, 0, 0}, {-1, 0, 0}, 0}, "axis");
    Check(*accel, Ray{{5, 0, 0}, {-1, 0, 0}}, {true, {1.9f, 0, 0}, {1, 0, 0}, 1}, "axis back");
    Check(*accel, Ray{{-0.5f, -5, 0}, {0, 1, 0}}, {true, {-0.5f, -yA, 0}, {-0.5f, -yA, 0}, 0},
          "A only");
    Check(*accel, Ray{{1.5f, -5, 0}, {0, 1, 0}}, {true, {1.5f, -yB, 0}, {0.5f, -yB, 0}, 1},
          "B only");
    Check(*accel, Ray{{0.5f, -5, 0}, {0, 1, 0}}, {true, {0.5f, -yA, 0}, {0.5f, -yA, 0}, 0}, "both");
    Check(*accel, Ray{{3, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "neither");
    // From inside both: the exit of the union (A's surface).
    Check(*accel, Ray{{0.5f, 0, 0}, {0, 1, 0}}, {true, {0.5f, yA, 0}, {0.5f, yA, 0}, 0}, "inside");
    // tMax before the surface; tMin past the entry (then the exit at x = 1.9).
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, 3.9f}, {false, {}, {}, 0}, "tMax");
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, Infinity, 4.5f}, {true, {1.9f, 0, 0}, {1, 0, 0}, 1},
          "tMin");
}

TEST(Csg, TwoSpheresIntersection) {
    auto accel = TwoSpheres(CsgOp::Intersection);
    // The lens [0.1, 1] on the axis: in through B, out through A.
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {true, {0.1f, 0, 0}, {-1, 0, 0}, 1}, "axis");
    Check(*accel, Ray{{5, 0, 0}, {-1, 0, 0}}, {true, {1, 0, 0}, {1, 0, 0}, 0}, "axis back");
    Check(*accel, Ray{{-0.5f, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "A only");
    Check(*accel, Ray{{1.5f, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "B only");
    Check(*accel, Ray{{0.5f, -5, 0}, {0, 1, 0}}, {true, {0.5f, -yB, 0}, {-0.5f, -yB, 0}, 1},
          "both");
    Check(*accel, Ray{{3, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "neither");
    Check(*accel, Ray{{0.5f, 0, 0}, {0, 1, 0}}, {true, {0.5f, yB, 0}, {-0.5f, yB, 0}, 1}, "inside");
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, 5.0f}, {false, {}, {}, 0}, "tMax");
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, Infinity, 5.5f}, {true, {1, 0, 0}, {1, 0, 0}, 0},
          "tMin");
}

TEST(Csg, TwoSpheresDifference) {
    auto accel = TwoSpheres(CsgOp::Difference);
    // A - B on the axis is [-1, 0.1]; at x = 0.1 the carved surface of B, its normal flipped.
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {true, {-1, 0, 0}, {-1, 0, 0}, 0}, "axis");
    Check(*accel, Ray{{5, 0, 0}, {-1, 0, 0}}, {true, {0.1f, 0, 0}, {1, 0, 0}, 1}, "axis back");
    Check(*accel, Ray{{-0.5f, -5, 0}, {0, 1, 0}}, {true, {-0.5f, -yA, 0}, {-0.5f, -yA, 0}, 0},
          "A only");
    Check(*accel, Ray{{1.5f, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "B only");
    Check(*accel, Ray{{0.5f, -5, 0}, {0, 1, 0}}, {true, {0.5f, -yA, 0}, {0.5f, -yA, 0}, 0}, "both");
    Check(*accel, Ray{{3, -5, 0}, {0, 1, 0}}, {false, {}, {}, 0}, "neither");
    // From inside B (outside the result): into A - B where the ray leaves B.
    Check(*accel, Ray{{0.5f, 0, 0}, {0, 1, 0}}, {true, {0.5f, yB, 0}, {0.5f, -yB, 0}, 1},
          "inside B");
    // From inside the result: out through B's carved surface.
    Check(*accel, Ray{{-0.5f, 0, 0}, {1, 0, 0}}, {true, {0.1f, 0, 0}, {1, 0, 0}, 1},
          "inside A - B");
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, 3.9f}, {false, {}, {}, 0}, "tMax");
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, Infinity, 4.5f}, {true, {0.1f, 0, 0}, {1, 0, 0}, 1},
          "tMin");
}

TEST(Csg, DifferenceIsFirstMinusRest) {
    auto csg = std::make_unique<CsgShape>();
    int a = csg->AddLeaf(MakeSphere(Vec3d(0, 0, 0), 1));
    int b = csg->AddLeaf(MakeSphere(Vec3d(1, 0, 0), 0.5));
    int c = csg->AddLeaf(MakeSphere(Vec3d(-1, 0, 0), 0.5));
    csg->AddNode(CsgOp::Difference, {{true, a}, {true, b}, {true, c}});
    csg->Finish();
    auto crossings = csg->Crossings({-5, 0, 0}, {1, 0, 0}, 0, Precision::Double);
    ASSERT_EQ(crossings.size(), 2u);
    EXPECT_NEAR(crossings[0].first, 4.5, 1e-9);  // x = -0.5, leaving C
    EXPECT_TRUE(crossings[0].second);
    EXPECT_NEAR(crossings[1].first, 5.5, 1e-9);  // x = 0.5, entering B
    EXPECT_FALSE(crossings[1].second);
}

TEST(Csg, NestedNodes) {
    // (A ∪ B) ∩ C with C a big sphere that clips the union at x = 1.5.
    auto csg = std::make_unique<CsgShape>();
    int a = csg->AddLeaf(MakeSphere(Vec3d(0, 0, 0), 1));
    int b = csg->AddLeaf(MakeSphere(Vec3d(1, 0, 0), 0.9));
    int u = csg->AddNode(CsgOp::Union, {{true, a}, {true, b}});
    int c = csg->AddLeaf(MakeSphere(Vec3d(-1.5, 0, 0), 3));
    csg->AddNode(CsgOp::Intersection, {{false, u}, {true, c}});
    csg->Finish();
    auto crossings = csg->Crossings({-5, 0, 0}, {1, 0, 0}, 0, Precision::Double);
    ASSERT_EQ(crossings.size(), 2u);
    EXPECT_NEAR(crossings[0].first, 4, 1e-9);
    EXPECT_NEAR(crossings[1].first, 6.5, 1e-9);
}

// Sphere of radius 1.3 (leaf 0) and the cube [-1, 1]^3 (leaf 1).
std::unique_ptr<Accel> SphereCube(CsgOp op, bool inwardCube = false) {
    auto csg = std::make_unique<CsgShape>();
    EXPECT_EQ(MeshClosedError(*MakeCube(1)), "");
    int s = csg->AddLeaf(MakeSphere(Vec3d(0, 0, 0), 1.3));
    int c = csg->AddLeaf(MakeCube(1, inwardCube));
    if (op == CsgOp::Difference)
        csg->AddNode(op, {{true, c}, {true, s}});  // the cube minus the sphere
    else
        csg->AddNode(op, {{true, s}, {true, c}});
    csg->Finish();
    auto accel = std::make_unique<Accel>();
    accel->AddAnalytic(std::move(csg));
    accel->Commit();
    return accel;
}

const float xs = std::sqrt(1.69f - 1.28f);  // |x| of the sphere on the line y = z = 0.8

TEST(Csg, SphereCubeUnion) {
    auto accel = SphereCube(CsgOp::Union);
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {true, {-1.3f, 0, 0}, {-1, 0, 0}, 0}, "axis");
    // Near a cube edge, outside the sphere: the cube's face.
    Check(*accel, Ray{{-5, 0.8f, 0.8f}, {1, 0, 0}}, {true, {-1, 0.8f, 0.8f}, {-1, 0, 0}, 1},
          "cube only");
    Check(*accel, Ray{{-5, 1.2f, 0}, {1, 0, 0}},
          {true, {-std::sqrt(1.69f - 1.44f), 1.2f, 0}, {-std::sqrt(1.69f - 1.44f), 1.2f, 0}, 0},
          "sphere only");
    Check(*accel, Ray{{-5, 1.5f, 0}, {1, 0, 0}}, {false, {}, {}, 0}, "neither");
    Check(*accel, Ray{{0, 0.8f, 0.8f}, {1, 0, 0}}, {true, {1, 0.8f, 0.8f}, {1, 0, 0}, 1}, "inside");
}

TEST(Csg, SphereCubeIntersection) {
    for (bool inward : {false, true}) {  // the mesh's winding does not matter
        auto accel = SphereCube(CsgOp::Intersection, inward);
        Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {true, {-1, 0, 0}, {-1, 0, 0}, 1}, "axis");
        Check(*accel, Ray{{-5, 0.8f, 0.8f}, {1, 0, 0}},
              {true, {-xs, 0.8f, 0.8f}, {-xs, 0.8f, 0.8f}, 0}, "both, sphere first");
        Check(*accel, Ray{{-5, 1.2f, 0}, {1, 0, 0}}, {false, {}, {}, 0}, "sphere only");
        Check(*accel, Ray{{0, 0, 0}, {0, 0, -1}}, {true, {0, 0, -1}, {0, 0, -1}, 1}, "inside");
        Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}, Infinity, 4.5f}, {true, {1, 0, 0}, {1, 0, 0}, 1},
              "tMin");
    }
}

TEST(Csg, CubeMinusSphere) {
    auto accel = SphereCube(CsgOp::Difference);
    // Leaves: 0 the sphere, 1 the cube; the node is cube - sphere.
    Check(*accel, Ray{{-5, 0, 0}, {1, 0, 0}}, {false, {}, {}, 0}, "axis: carved away");
    Check(*accel, Ray{{-5, 0.8f, 0.8f}, {1, 0, 0}}, {true, {-1, 0.8f, 0.8f}, {-1, 0, 0}, 1},
          "corner piece");
    Check(*accel, Ray{{-0.9f, 0.8f, 0.8f}, {1, 0, 0}},
          {true, {-xs, 0.8f, 0.8f}, {xs, -0.8f, -0.8f}, 0}, "inside: out through the carving");
    Check(*accel, Ray{{0, 0.8f, 0.8f}, {1, 0, 0}}, {true, {xs, 0.8f, 0.8f}, {-xs, -0.8f, -0.8f}, 0},
          "inside the sphere: into the far corner piece");
    Check(*accel, Ray{{-5, 0.8f, 0.8f}, {1, 0, 0}, 3.9f}, {false, {}, {}, 0}, "tMax");
}

TEST(Csg, OpenMeshIsReported) {
    std::vector<Vec3f> P = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    TriangleMesh tri(Transform(), false, P, {0, 1, 2});
    EXPECT_NE(MeshClosedError(tri).find("not closed"), std::string::npos);
    // A cube with split vertices (24, one quad per face) is still closed.
    std::vector<Vec3f> Q;
    std::vector<uint32_t> idx;
    for (int axis = 0; axis < 3; ++axis)
        for (int s = -1; s <= 1; s += 2) {
            uint32_t base = uint32_t(Q.size());
            for (int k = 0; k < 4; ++k) {
                Vec3f p;
                p[axis] = float(s);
                p[(axis + 1) % 3] = (k == 1 || k == 2) ? 1.f : -1.f;
                p[(axis + 2) % 3] = (k >= 2) ? 1.f : -1.f;
                Q.push_back(p);
            }
            for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + i);
        }
    TriangleMesh cube(Transform(), false, Q, idx);
    EXPECT_EQ(MeshClosedError(cube), "");
}

// Snell refraction of unit w about unit n (n against w), eta = n_i / n_t.
bool Refract(Vec3d w, Vec3d n, double eta, Vec3d *out) {
    double cosi = -Dot(n, w);
    double k = 1 - eta * eta * (1 - cosi * cosi);
    if (k < 0) return false;
    *out = Normalize(w * eta + n * (eta * cosi - std::sqrt(k)));
    return true;
}

TEST(Csg, LensFocusesLikeAThickLens) {
    // Biconvex lens: spheres of radius R centred at z = +-c (intersection), thickness 2 (R - c).
    const double R = 10, c = 9.5, ior = 1.5, d = 2 * (R - c);
    auto csg = std::make_unique<CsgShape>();
    int a = csg->AddLeaf(MakeSphere(Vec3d(0, 0, c), R));
    int b = csg->AddLeaf(MakeSphere(Vec3d(0, 0, -c), R));
    csg->AddNode(CsgOp::Intersection, {{true, a}, {true, b}});
    csg->Finish();
    Accel accel;
    accel.AddAnalytic(std::move(csg));
    accel.Commit();
    // Thick-lens back focal distance (R1 = R, R2 = -R), from the back vertex at z = R - c.
    double power = (ior - 1) * (2 / R - (ior - 1) * d / (ior * R * R));
    double f = 1 / power;
    double bfd = f * (1 - (ior - 1) * d / (ior * R));
    double zFocus = (R - c) + bfd;
    for (double h : {0.05, 0.1, 0.2}) {
        Ray ray{{float(h), 0, -20}, {0, 0, 1}};
        SurfaceInteraction si;
        ASSERT_TRUE(accel.Intersect(ray, &si));
        Vec3d w(0, 0, 1), t1, t2;
        ASSERT_LT(Dot(Vec3d(si.n), w), 0);  // entering: the normal faces the ray
        ASSERT_TRUE(Refract(w, Vec3d(si.n), 1 / ior, &t1));
        Ray inside = si.SpawnRay(Vec3f(t1));
        SurfaceInteraction so;
        ASSERT_TRUE(accel.Intersect(inside, &so));
        ASSERT_GT(Dot(Vec3d(so.n), t1), 0);  // leaving: the normal points out
        ASSERT_TRUE(Refract(t1, -Vec3d(so.n), ior, &t2));
        // Where the outgoing ray crosses the axis.
        double s = -double(so.p.x) / t2.x;
        double z = double(so.p.z) + s * t2.z;
        EXPECT_NEAR(z, zFocus, 0.01 * zFocus) << "h = " << h;
    }
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

// Rays spawned off a convex CSG solid (a sphere intersected with a mesh cube) toward the
// outside never hit it again, and rays spawned inward always do.
TEST(Csg, SpawnedRaysLeaveTheSurface) {
    auto accel = SphereCube(CsgOp::Intersection);
    int selfHits = 0, missesInside = 0, hits = 0;
    for (int i = 0; i < 4000; ++i) {
        // Rays from outside toward points spread over the solid.
        double a = 0.37 * i, b = 0.113 * i;
        Vec3f target(float(0.9 * std::sin(a)), float(0.9 * std::cos(a) * std::sin(b)),
                     float(0.9 * std::cos(b)));
        Vec3f o(float(5 * std::cos(0.7 * i)), float(5 * std::sin(0.7 * i)),
                float(3 * std::sin(0.3 * i)));
        Ray ray{o, target - o};
        SurfaceInteraction si;
        if (!accel->Intersect(ray, &si)) continue;
        ++hits;
        Vec3f n = si.n;
        Vec3f w = Normalize(ray.d);
        Vec3f r = w - n * (2 * Dot(w, n));  // mirror reflection: away from the convex solid
        if (accel->Intersect(si.SpawnRay(r), &si)) ++selfHits;
        SurfaceInteraction s2;
        if (!accel->Intersect(ray, &s2)) continue;
        if (!accel->Intersect(s2.SpawnRay(w), &s2)) ++missesInside;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_EQ(selfHits, 0);
    EXPECT_EQ(missesInside, 0);
}

}  // namespace
}  // namespace prism
