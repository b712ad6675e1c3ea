// Curvature (the normal derivatives that specular ray differentials read,
// AnalyticShape::NormalDerivatives, TriangleMesh::NormalDerivatives, Accel::NormalDerivatives):
// each analytic shape under non-uniform, mirroring and reversed transforms against central
// differences, in double, of the unit normal of its own parametric surface
// (RevolutionProfile::Surface); interpolated mesh normals against differences of the mesh's
// shading normal; instances and CSG operands against the shape they stand for.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/rng.h"
#include "geometry/accel.h"
#include "geometry/csg.h"
#include "geometry/revolution.h"
#include "shape_test_util.h"

namespace prism {
namespace {

using testing_util::AllKinds;
using testing_util::Kind;
using testing_util::KindName;
using testing_util::MakeShape;

// Rotation, a non-uniform scale (0.5..2 per axis, a mirror when asked) and a moderate
// translation, so that the render-space normal goes through the inverse transpose.
Transform SkewTransform(PCG32 &rng, bool mirror) {
    const Vec3d t(10 * (rng.UniformDouble() - 0.5), 10 * (rng.UniformDouble() - 0.5),
                  10 * (rng.UniformDouble() - 0.5));
    auto s = [&] { return 0.5 + 1.5 * rng.UniformDouble(); };
    const double sx = s(), sy = s(), sz = s();
    return Translate(t) * Rotate(360 * rng.UniformDouble(), testing_util::RandomDirD(rng)) *
           Scale(mirror ? -sx : sx, sy, sz);
}

// The render-space surface point, its tangents along phi and v, and its unit normal, all by
// central differences of the profile in double (object space, then through the transform).
struct SurfaceFrame {
    Vec3d p, dpdphi, dpdv, n;
};
SurfaceFrame Frame(const RevolutionProfile &pr, const Transform &xf, double phi, double v) {
    const double h = 1e-6;
    SurfaceFrame f;
    f.p = xf.Point(pr.Surface(phi, v));
    f.dpdphi = xf.Vector((pr.Surface(phi + h, v) - pr.Surface(phi - h, v)) / (2 * h));
    f.dpdv = xf.Vector((pr.Surface(phi, v + h) - pr.Surface(phi, v - h)) / (2 * h));
    f.n = Normalize(Cross(f.dpdphi, f.dpdv));
    return f;
}

TEST(Curvature, AnalyticShapesMatchDifferencesOfTheirSurfaceNormal) {
    PCG32 rng(2611);
    for (Kind kind : AllKinds) {
        double worst = 0;
        for (int trial = 0; trial < 40; ++trial) {
            const bool mirror = trial % 4 == 1, reverse = trial % 3 == 2;
            const Transform xf = SkewTransform(rng, mirror);
            auto shape = MakeShape(kind, xf, false, rng, reverse);
            RevolutionProfile pr;
            ASSERT_TRUE(shape->Revolution(&pr)) << KindName(kind);
            const double phi = pr.phiMax * (0.05 + 0.9 * rng.UniformDouble());
            const double v = 0.1 + 0.8 * rng.UniformDouble();
            const SurfaceFrame f = Frame(pr, xf, phi, v);
            SurfaceInteraction si;
            si.p = Vec3f(f.p);
            si.n = si.ns = Vec3f(f.n);
            const Vec3f dp[2] = {Vec3f(f.dpdphi), Vec3f(f.dpdv)};
            Vec3f dn[2], dnFlipped[2];
            shape->NormalDerivatives(si, si.n, dp, dn, 2);
            shape->NormalDerivatives(si, -si.n, dp, dnFlipped, 2);
            // The reference: central differences of the unit normal along phi and v.
            const double H = 1e-4;
            const Vec3d refPhi =
                (Frame(pr, xf, phi + H, v).n - Frame(pr, xf, phi - H, v).n) / (2 * H);
            const Vec3d refV =
                (Frame(pr, xf, phi, v + H).n - Frame(pr, xf, phi, v - H).n) / (2 * H);
            // Relative to the derivative itself, or for a ruled direction (a cylinder's or a
            // cone's axis, where it is 0) to the other one's size (the hit point is a float:
            // near the cone's apex its rounding moves the normal by ~1e-5 of that).
            const double size = Length(refPhi) + Length(refV) + 1e-12;
            int i = 0;
            for (const Vec3d &ref : {refPhi, refV}) {
                const double err = Length(Vec3d(dn[i]) - ref);
                worst = std::max(worst, err / std::max({Length(ref), 0.1 * size, 1e-3}));
                EXPECT_LT(err, 1e-4 * Length(ref) + 5e-5 * size + 1e-7)
                    << KindName(kind) << " trial " << trial << " axis " << i << " ref " << ref.x
                    << " " << ref.y << " " << ref.z << " got " << dn[i].x << " " << dn[i].y << " "
                    << dn[i].z;
                // Oriented as the normal it is asked for.
                EXPECT_EQ(dnFlipped[i], -dn[i]);
                // A unit vector's derivative is perpendicular to it.
                EXPECT_LT(std::abs(Dot(Vec3d(dn[i]), f.n)), 1e-5 * (1 + Length(ref)));
                ++i;
            }
            if (kind == Kind::Disk) EXPECT_EQ(dn[0], Vec3f());
            if (kind != Kind::Disk) EXPECT_GT(Length(refPhi) + Length(refV), 0.1);
        }
        std::printf("%-12s worst relative error of dn %.2e\n", KindName(kind), worst);
    }
}

// A small patch of the unit sphere as a two-triangle mesh with its exact vertex normals.
std::unique_ptr<TriangleMesh> SpherePatch(const Transform &xf, bool withNormals) {
    std::vector<Vec3f> P = {Normalize(Vec3f(0.2f, -0.3f, 1)), Normalize(Vec3f(0.5f, 0.1f, 1)),
                            Normalize(Vec3f(-0.1f, 0.4f, 1)), Normalize(Vec3f(-0.4f, -0.2f, 1))};
    std::vector<Vec3f> N = P;
    return std::make_unique<TriangleMesh>(xf, false, P, std::vector<uint32_t>{0, 1, 2, 0, 2, 3},
                                          withNormals ? N : std::vector<Vec3f>{});
}

TEST(Curvature, MeshNormalsMatchDifferencesOfTheShadingNormal) {
    const Transform xf = Translate(Vec3d(1, 2, -3)) * Rotate(30, Vec3d(1, 1, 0)) * Scale(2, 1, 3);
    auto mesh = SpherePatch(xf, true);
    for (size_t prim : {size_t(0), size_t(1)}) {
        const uint32_t *vi = mesh->Triangle(prim);
        const Vec3f p0 = mesh->Position(vi[0]), p1 = mesh->Position(vi[1]),
                    p2 = mesh->Position(vi[2]);
        const float b1 = 0.3f, b2 = 0.25f, h = 1e-2f;
        const Vec3f rayDir = -Normalize(Cross(p1 - p0, p2 - p0));
        auto ns = [&](float u, float v) {
            return Vec3d(mesh->Interaction(prim, u, v, 1, rayDir).ns);
        };
        const SurfaceInteraction si = mesh->Interaction(prim, b1, b2, 1, rayDir);
        // Along the barycentric directions: dp/db1 = p1 - p0, dp/db2 = p2 - p0.
        const Vec3f dp[2] = {p1 - p0, p2 - p0};
        Vec3f dn[2];
        mesh->NormalDerivatives(prim, si, si.ns, dp, dn, 2);
        const Vec3d ref[2] = {(ns(b1 + h, b2) - ns(b1 - h, b2)) / double(2 * h),
                              (ns(b1, b2 + h) - ns(b1, b2 - h)) / double(2 * h)};
        for (int i = 0; i < 2; ++i) {
            EXPECT_GT(Length(ref[i]), 0.1);
            EXPECT_LT(Length(Vec3d(dn[i]) - ref[i]), 2e-3 * Length(ref[i])) << prim << " " << i;
        }
    }
    // Flat faces (no vertex normals): zero.
    auto flat = SpherePatch(xf, false);
    const SurfaceInteraction si = flat->Interaction(0, 0.3f, 0.3f, 1, Vec3f(0, 0, -1));
    const Vec3f dp[1] = {Vec3f(1, 0, 0)};
    Vec3f dn[1] = {Vec3f(1, 1, 1)};
    flat->NormalDerivatives(0, si, si.n, dp, dn, 1);
    EXPECT_EQ(dn[0], Vec3f());
}

// The derivatives through Accel at the hit of a ray, for the tangents dpdu, dpdv of the hit.
void AccelDerivatives(const Accel &accel, const Ray &ray, SurfaceInteraction *si, Vec3f dn[2]) {
    ASSERT_TRUE(accel.Intersect(ray, si));
    const Vec3f dp[2] = {si->dpdu, si->dpdv};
    accel.NormalDerivatives(*si, si->ns, dp, dn, 2);
}

TEST(Curvature, InstancesAndCsgOperandsAreTheirShapes) {
    const Transform inst =
        Translate(Vec3d(0.5, -1, 4)) * Rotate(40, Vec3d(0, 1, 1)) * Scale(1.5, 0.8, 1.2);
    const Transform local = Translate(Vec3d(0, 0.2, 0)) * Scale(1, 1.4, 1);
    const Ray ray{Vec3f(0.3f, -0.6f, -2), Normalize(Vec3f(0.05f, 0.02f, 1)), Infinity};

    // The sphere declared with the combined transform, and as an instance of a prototype.
    Accel direct;
    direct.AddAnalytic(std::make_unique<Sphere>(inst * local, false, 1, -1, 1, 360));
    direct.Commit();
    auto proto = std::make_shared<Accel>();
    proto->AddAnalytic(std::make_unique<Sphere>(local, false, 1, -1, 1, 360));
    proto->Commit();
    Accel instanced;
    instanced.AddInstance(proto, inst);
    instanced.Commit();
    SurfaceInteraction a, b;
    Vec3f dnA[2], dnB[2];
    AccelDerivatives(direct, ray, &a, dnA);
    AccelDerivatives(instanced, ray, &b, dnB);
    ASSERT_LT(Length(a.p - b.p), 1e-4f);
    for (int i = 0; i < 2; ++i) {
        EXPECT_GT(Length(dnA[i]), 0.1f);
        EXPECT_LT(Length(dnA[i] - dnB[i]), 1e-4f * Length(dnA[i])) << i;
    }

    // A sphere with a smaller one carved out of its front: the carved surface is the small
    // sphere's, seen from inside (its normal turned around, so its derivatives too).
    const Transform big = Scale(1.5, 1, 1), small = Translate(Vec3d(0, 0, -1));
    auto csg = std::make_unique<CsgShape>();
    const int l0 = csg->AddLeaf(std::make_unique<Sphere>(big, false, 1, -1, 1, 360));
    const int l1 = csg->AddLeaf(std::make_unique<Sphere>(small, false, 0.6, -0.6, 0.6, 360));
    csg->AddNode(CsgOp::Difference, {{true, l0}, {true, l1}});
    csg->Finish();
    Accel carved;
    carved.AddAnalytic(std::move(csg));
    carved.Commit();
    Accel smallOnly;
    smallOnly.AddAnalytic(std::make_unique<Sphere>(small, false, 0.6, -0.6, 0.6, 360));
    smallOnly.Commit();
    const Ray front{Vec3f(0.1f, 0.05f, -5), Normalize(Vec3f(0.02f, 0.03f, 1)), Infinity};
    SurfaceInteraction c, s;
    Vec3f dnC[2], dnS[2];
    AccelDerivatives(carved, front, &c, dnC);
    ASSERT_EQ(c.instanceShape, l1);
    // The ray's second crossing of the small sphere (from inside) is the carved surface.
    ASSERT_TRUE(smallOnly.Intersect(front, &s));
    ASSERT_TRUE(smallOnly.Intersect(s.SpawnRay(front.d), &s));
    ASSERT_LT(Length(c.p - s.p), 1e-4f);
    // Along the same tangents, oriented as the CSG hit's normal.
    const Vec3f dp[2] = {c.dpdu, c.dpdv};
    smallOnly.NormalDerivatives(s, c.ns, dp, dnS, 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_GT(Length(dnC[i]), 0.1f);
        EXPECT_LT(Length(dnC[i] - dnS[i]), 1e-4f * Length(dnC[i])) << i;
    }
    // A sphere's outward unit normal (p - c) / r changes by dp / r: the carved surface's,
    // which points inward, by -dp / r.
    EXPECT_LT(Length(dnC[0] + c.dpdu / 0.6f), 1e-4f * Length(dnC[0]));
    EXPECT_LT(Length(dnC[1] + c.dpdv / 0.6f), 1e-4f * Length(dnC[1]));
}

}  // namespace
}  // namespace prism
