// The Whitted integrator against closed forms: Lambertian shading under a point light, a
// mirror's reflectance, and the Fresnel loss of glass at normal incidence.
#include "render/whitted.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/sphere.h"
#include "render/bsdf.h"
#include "render/materials.h"
#include "render/render_scene.h"

namespace prism {
namespace {

TexturePtr Const(RGB v) { return std::make_shared<ConstantTexture>(v); }

Material Matte(RGB kd) {
    return Material(std::make_shared<MatteMaterial>(Const(kd), Const(RGB(0))), "matte");
}

Material Mirror(RGB kr) { return Material(std::make_shared<MirrorMaterial>(Const(kr)), "mirror"); }

// A scene with a large matte floor (y = 0, normal +y) lit by one point light.
struct TestScene {
    RenderScene scene;
    explicit TestScene(int maxDepth = 5) {
        scene.accel = std::make_unique<Accel>();
        scene.materials.push_back(Matte(RGB(0.5f, 0.25f, 0.125f)));
        scene.trace.maxDepth = maxDepth;
        AddQuad({{-100, 0, -100}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}}, 0);
    }
    void AddQuad(std::vector<Vec3f> P, int material) {
        int s = scene.accel->AddMesh(std::make_unique<TriangleMesh>(
            Transform(), false, P, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        AddShapeInfo(s, material);
    }
    void AddShapeInfo(int s, int material) {
        if (int(scene.shapes.size()) <= s) scene.shapes.resize(size_t(s) + 1);
        scene.shapes[size_t(s)].material = material;
    }
    int AddMaterial(Material m) {
        scene.materials.push_back(std::move(m));
        return int(scene.materials.size()) - 1;
    }
    RGB Li(const Ray &r) {
        if (!committed) {
            scene.accel->Commit();
            committed = true;
        }
        RayCounters c;
        return WhittedTracer(scene).Li(r, 0, c);
    }
    bool committed = false;
};

void ExpectRelNear(const RGB &got, const RGB &want, double rel) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], rel * std::abs(want[c])) << "channel " << c;
}

TEST(Whitted, LambertianUnderPointLight) {
    TestScene ts;
    Vec3f light(0.3f, 2.f, -0.4f);
    RGB I(10, 20, 30);
    ts.scene.lights.push_back(std::make_unique<PointLight>(light, I));
    Vec3f p(0.7f, 0.f, 0.3f);
    Vec3f eye(-1.f, 1.5f, -2.f);
    RGB L = ts.Li(Ray{eye, Normalize(p - eye), Infinity});
    double r2 = LengthSquared(Vec3d(light) - Vec3d(p));
    double cosTheta = double(light.y) / std::sqrt(r2);
    RGB kd(0.5f, 0.25f, 0.125f);
    RGB want = kd * I * float(cosTheta / (Pi * r2));
    ExpectRelNear(L, want, 1e-4);
}

TEST(Whitted, ShadowRayBlockedByOccluder) {
    TestScene ts;
    ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0, 4, 0), RGB(10)));
    int s = ts.scene.accel->AddAnalytic(
        std::make_unique<Sphere>(Translate(Vec3d(0, 2, 0)), false, 0.5, -0.5, 0.5, 360));
    ts.AddShapeInfo(s, 0);
    RGB shadowed = ts.Li(Ray{{0, 3, -3}, Normalize(Vec3f(0, -3, 3)), Infinity});
    EXPECT_EQ(shadowed, RGB(0));
}

TEST(Whitted, CameraPacketsMatchSingleRaysExactly) {
    // LiCamera from hits traced in a 16-ray packet (rtcIntersect16) returns exactly Li's
    // radiance, rays and counters: floor, occluder, mirror, two lights, misses.
    TestScene ts;
    ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0, 4, 0), RGB(10)));
    ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(3, 2, -1), RGB(5, 6, 7)));
    int s = ts.scene.accel->AddAnalytic(
        std::make_unique<Sphere>(Translate(Vec3d(0, 2, 0)), false, 0.5, -0.5, 0.5, 360));
    ts.AddShapeInfo(s, 0);
    Material mirror = Mirror(RGB(0.9f));
    ts.AddQuad({{2, -1, -5}, {2, 5, -5}, {2, 5, 5}, {2, -1, 5}}, ts.AddMaterial(mirror));
    ts.Li(Ray{{0, 3, -3}, {0, 0, 1}, Infinity});  // commits
    WhittedTracer integrator(ts.scene);
    for (int n = 1; n <= 16; n += 5) {
        Ray rays[16];
        RawHit hits[16];
        SampleContext scs[16];
        for (int i = 0; i < n; ++i) {
            Vec3f target(-3.f + 0.4f * float(i), 0.f, float(i % 4) - 1.5f);
            Vec3f eye(-1.f, 3.f, -4.f);
            rays[i] = Ray{eye, Normalize(target - eye), Infinity};
            if (i % 7 == 6) rays[i].d = Vec3f(0, 1, 0);  // a miss
            scs[i] = SampleContext{i, n, 0, 1};
        }
        ts.scene.accel->IntersectPacket(rays, n, hits);
        RayCounters cp, c1;
        for (int i = 0; i < n; ++i) {
            RGB single = integrator.Li(rays[i], 0, c1, scs[i]);
            EXPECT_EQ(integrator.LiCamera(rays[i], hits[i], cp, scs[i]), single) << "ray " << i;
        }
        EXPECT_EQ(cp.shadow, c1.shadow);
        EXPECT_EQ(cp.reflection, c1.reflection);
    }
}

TEST(Whitted, MirrorReturnsKrTimesRadiance) {
    // The floor point P seen directly, and via a vertical mirror with Kr 0.9 at x = 2.
    TestScene ts;
    ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0.5f, 3, 0), RGB(40)));
    Material mirror = Mirror(RGB(0.9f));
    int m = ts.AddMaterial(mirror);
    ts.AddQuad({{2, -1, -5}, {2, 5, -5}, {2, 5, 5}, {2, -1, 5}}, m);
    Vec3f p(1.f, 0.f, 0.f);
    Vec3f eyeDirect(-2.f, 2.f, 0.f);
    RGB direct = ts.Li(Ray{eyeDirect, Normalize(p - eyeDirect), Infinity});
    // Mirror image of p in the plane x = 2 is (3, 0, 0); aim at it from (0, 1, 0): the ray
    // hits the mirror at x = 2 and continues to p.
    Vec3f eye(0.f, 1.f, 0.f), image(3.f, 0.f, 0.f);
    RGB viaMirror = ts.Li(Ray{eye, Normalize(image - eye), Infinity});
    ASSERT_GT(direct.r, 0.f);
    ExpectRelNear(viaMirror, direct * 0.9f, 1e-4);
}

TEST(Whitted, GlassAtNormalIncidenceLosesFresnelTwice) {
    // A glass sphere between the eye and a lit floor point, ray through its centre.
    // maxdepth 3 admits exactly the path front-transmit, back-transmit, floor: (1-F)^2.
    for (int maxDepth : {3}) {
        TestScene ts(maxDepth);
        ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0, 5, 2), RGB(50)));
        Material glass(std::make_shared<GlassMaterial>(Const(RGB(1)), Const(RGB(1)),
                                                       Const(RGB(1.5f)), Roughness{}),
                       "glass");
        int g = ts.AddMaterial(glass);
        Vec3f p(0, 0, 0);
        Vec3f eye(0, 4, -4);
        Vec3f dir = Normalize(p - eye);
        RGB direct = ts.Li(Ray{eye, dir, Infinity});
        TestScene ts2(maxDepth);
        ts2.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0, 5, 2), RGB(50)));
        int g2 = ts2.AddMaterial(glass);
        (void)g;
        Vec3f c = eye + dir * 2.5f;
        int s = ts2.scene.accel->AddAnalytic(
            std::make_unique<Sphere>(Translate(Vec3d(c)), false, 0.6, -0.6, 0.6, 360));
        ts2.AddShapeInfo(s, g2);
        RGB through = ts2.Li(Ray{eye, dir, Infinity});
        float F = FrDielectric(1.f, 1.f, 1.5f);
        EXPECT_NEAR(F, 0.04f, 1e-6f);
        ExpectRelNear(through, direct * ((1 - F) * (1 - F)), 1e-3);
    }
}

TEST(Whitted, TotalInternalReflectionHasNoTransmission) {
    BSDF b;
    b.SetFrame({0, 0, 1}, {1, 0, 0}, {0, 0, 1});
    BxDFLobes &l = b.AddPart();
    l.kr = RGB(1);
    l.kt = RGB(1);
    l.eta = 1.5f;
    l.specularFresnel.kind = FresnelKind::Dielectric;
    l.specularFresnel.etaT = 1.5f;
    // From inside the glass (wo below the surface) at 60 degrees: beyond the critical angle.
    Vec3f wo = Normalize(Vec3f(std::sin(1.047f), 0, -std::cos(1.047f)));
    Vec3f wi;
    RGB w;
    EXPECT_FALSE(b.SampleSpecularTransmission(0, wo, &wi, &w));
    ASSERT_TRUE(b.SampleSpecularReflection(0, wo, &wi, &w));
    EXPECT_NEAR(w.r, 1.f, 1e-6f);
    // Energy: at 30 degrees from outside, reflected + transmitted (undoing the eta^2 scale) = 1.
    Vec3f wo2 = Normalize(Vec3f(std::sin(0.5236f), 0, std::cos(0.5236f)));
    RGB wr, wt;
    ASSERT_TRUE(b.SampleSpecularReflection(0, wo2, &wi, &wr));
    ASSERT_TRUE(b.SampleSpecularTransmission(0, wo2, &wi, &wt));
    EXPECT_NEAR(wr.r + wt.r * 1.5f * 1.5f, 1.f, 1e-5f);
}

TEST(Whitted, MaxDepthLimitsRecursion) {
    TestScene ts(1);  // camera rays only: specular surfaces contribute no recursion
    ts.scene.lights.push_back(std::make_unique<PointLight>(Vec3f(0, 3, 0), RGB(40)));
    Material mirror = Mirror(RGB(0.9f));
    ts.AddQuad({{2, -1, -5}, {2, 5, -5}, {2, 5, 5}, {2, -1, 5}}, ts.AddMaterial(mirror));
    EXPECT_EQ(ts.Li(Ray{{0, 1, 0}, Normalize(Vec3f(3, -1, 0)), Infinity}), RGB(0));
}

TEST(Bsdf, PlasticHighlightPeaksAtMirrorDirection) {
    BSDF b;
    b.SetFrame({0, 0, 1}, {1, 0, 0}, {0, 0, 1});
    BxDFLobes &l = b.AddPart();
    l.ks = RGB(1);
    l.alphaX = l.alphaY = RoughnessToAlpha(0.1f);
    l.glossyFresnel.kind = FresnelKind::Dielectric;
    l.glossyFresnel.etaI = 1.5f;
    l.glossyFresnel.etaT = 1.f;
    Vec3f wo = Normalize(Vec3f(0.3f, 0, 1));
    float peak = b.f(wo, Normalize(Vec3f(-0.3f, 0, 1))).r;
    float off = b.f(wo, Normalize(Vec3f(0.3f, 0.4f, 1))).r;
    EXPECT_GT(peak, 1.5f * off);
    // The closed form at the peak: D = 1/(pi a^2), G ~ 1, F = Fresnel(1.5 -> 1) at cos 16.7 deg.
    float a = l.alphaX;
    float cosI = Normalize(Vec3f(-0.3f, 0, 1)).z;
    float G = 1 / (1 + 2 * (-1 + std::sqrt(1 + a * a * (1 - cosI * cosI) / (cosI * cosI))) / 2);
    float want = float(1 / (Pi * a * a)) * G * FrDielectric(cosI, 1.5f, 1.f) / (4 * cosI * cosI);
    EXPECT_NEAR(peak, want, 1e-5f * want + 1e-7f);
}

}  // namespace
}  // namespace prism
