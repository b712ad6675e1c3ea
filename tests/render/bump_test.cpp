// Bump and normal mapping (render/bump.cpp): on a flat quad, pbrt's bumpmap of a sine height
// field gives the analytic normal field, and normal maps give the normal they encode (a flat
// one changes nothing).
#include <gtest/gtest.h>

#include <cmath>

#include "render/material.h"
#include "render/materials.h"

namespace prism {
namespace {

constexpr float A = 0.02f;  // amplitude
constexpr float K = 2.0f;   // periods per unit of u

// h(u, v) = A sin(2 pi K u) cos(2 pi v), a height field over uv.
class SineHeight final : public Texture {
  public:
    RGB Evaluate(const TextureContext &c) const override {
        return RGB(A * std::sin(2 * float(Pi) * K * c.uv.x) * std::cos(2 * float(Pi) * c.uv.y));
    }
};

// The flat quad z = 0 with p = (u, v, 0): dp/du = x, dp/dv = y, n = z.
SurfaceInteraction FlatHit(float u, float v) {
    SurfaceInteraction si;
    si.p = Vec3f(u, v, 0);
    si.uv = Vec2f(u, v);
    si.n = si.ns = Vec3f(0, 0, 1);
    si.dpdu = Vec3f(1, 0, 0);
    si.dpdv = Vec3f(0, 1, 0);
    si.wo = Vec3f(0, 0, 1);
    return si;
}

Material Matte() {
    return Material(std::make_shared<MatteMaterial>(std::make_shared<ConstantTexture>(RGB(0.5f)),
                                                    std::make_shared<ConstantTexture>(RGB(0))),
                    "matte");
}

TEST(Bump, SineHeightFieldGivesTheAnalyticNormals) {
    Material m = Matte();
    m.bump = std::make_shared<SineHeight>();
    m.Prepare();
    EXPECT_TRUE(m.PerturbsShading());
    EXPECT_EQ(m.SurfaceNeeds(), unsigned(NeedAll));
    const float twoPi = 2 * float(Pi);
    for (float u : {0.05f, 0.2f, 0.37f, 0.5f, 0.81f})
        for (float v : {0.1f, 0.3f, 0.66f}) {
            SurfaceInteraction si = FlatHit(u, v);
            m.PerturbShading(si);
            // The surface (u, v, h): normal (-h_u, -h_v, 1), normalized.
            float hu = A * twoPi * K * std::cos(twoPi * K * u) * std::cos(twoPi * v);
            float hv = -A * twoPi * std::sin(twoPi * K * u) * std::sin(twoPi * v);
            Vec3f expected = Normalize(Vec3f(-hu, -hv, 1));
            // Finite differences of step .0005 (pbrt's fallback) are off by ~h'' du / 2.
            EXPECT_NEAR(si.ns.x, expected.x, 1e-3) << u << " " << v;
            EXPECT_NEAR(si.ns.y, expected.y, 1e-3) << u << " " << v;
            EXPECT_NEAR(si.ns.z, expected.z, 1e-3) << u << " " << v;
            EXPECT_NEAR(Length(si.ns), 1, 1e-6);
            // The geometric normal is untouched.
            EXPECT_EQ(si.n, Vec3f(0, 0, 1));
        }
}

TEST(Bump, BumpOnAFlippedSurfaceStaysOnTheGeometricSide) {
    Material m = Matte();
    m.bump = std::make_shared<SineHeight>();
    SurfaceInteraction si = FlatHit(0.2f, 0.1f);
    si.n = si.ns = Vec3f(0, 0, -1);  // reverse orientation: n against dpdu x dpdv
    m.PerturbShading(si);
    EXPECT_LT(si.ns.z, 0);
    SurfaceInteraction up = FlatHit(0.2f, 0.1f);
    m.PerturbShading(up);
    // The height now rises along -z: the surface (u, v, -h), whose downward normal is
    // (-h_u, -h_v, -1): the same tangential part, mirrored z.
    EXPECT_NEAR(si.ns.x, up.ns.x, 1e-6);
    EXPECT_NEAR(si.ns.y, up.ns.y, 1e-6);
    EXPECT_NEAR(si.ns.z, -up.ns.z, 1e-6);
}

TEST(NormalMap, FlatNormalChangesNothing) {
    Material m = Matte();
    m.normalMap = std::make_shared<ConstantTexture>(RGB(0.5f, 0.5f, 1.f));
    for (Vec3f n : {Vec3f(0, 0, 1), Normalize(Vec3f(0.3f, -0.2f, 0.9f))}) {
        SurfaceInteraction si = FlatHit(0.3f, 0.7f);
        si.ns = n;
        m.PerturbShading(si);
        EXPECT_NEAR(si.ns.x, n.x, 1e-6);
        EXPECT_NEAR(si.ns.y, n.y, 1e-6);
        EXPECT_NEAR(si.ns.z, n.z, 1e-6);
    }
}

TEST(NormalMap, EncodedNormalInTheTangentFrame) {
    // Tangent-space (0.3, -0.2, 1): x along dp/du, y along dp/dv, z along n; glTF's scale
    // multiplies x and y.
    for (float scale : {1.f, 2.f}) {
        Material m = Matte();
        m.normalMap = std::make_shared<ConstantTexture>(RGB(0.65f, 0.4f, 1.f));
        m.normalScale = scale;
        SurfaceInteraction si = FlatHit(0.3f, 0.7f);
        // A tangent frame turned about z: dp/du = (0, 1, 0), dp/dv = (-1, 0, 0).
        si.dpdu = Vec3f(0, 2, 0);
        si.dpdv = Vec3f(-3, 0, 0);
        m.PerturbShading(si);
        Vec3f expected = Normalize(Vec3f(0.2f * scale, 0.3f * scale, 1));
        EXPECT_NEAR(si.ns.x, expected.x, 1e-5) << scale;
        EXPECT_NEAR(si.ns.y, expected.y, 1e-5) << scale;
        EXPECT_NEAR(si.ns.z, expected.z, 1e-5) << scale;
    }
}

}  // namespace
}  // namespace prism
