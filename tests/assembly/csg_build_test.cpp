// CSG through the render scene: each operand keeps its own material (RenderScene::Info), and a
// glass lens made as the intersection of two spheres focuses parallel rays, refracted by the
// glass material's own BSDF, where the thick-lens formula says.
#include <gtest/gtest.h>

#include <cmath>

#include "assembly/build_scene.h"
#include "render/bsdf.h"
#include "scene/pbrt_parser.h"

namespace prism {
namespace {

RenderScene Build(const std::string &world) {
    Diagnostics diag(false);
    SceneDescription d = ParsePbrtString("WorldBegin\n" + world, "csg.pbrt", diag);
    BuildSettings s;
    s.cameraRelative = false;  // render space = world space
    return BuildRenderScene(d, s, diag);
}

TEST(CsgBuild, OperandsKeepTheirMaterials) {
    RenderScene scene = Build(R"(
CSGBegin "difference"
  Material "matte" "rgb Kd" [ 0.8 0.1 0.1 ]
  Shape "sphere" "float radius" 1
  Material "mirror"
  AttributeBegin Translate 1 0 0 Shape "sphere" "float radius" 0.9 AttributeEnd
CSGEnd
)");
    EXPECT_EQ(scene.features.csgNodes, 1);
    SurfaceInteraction a, b;
    ASSERT_TRUE(scene.accel->Intersect(Ray{{-5, 0, 0}, {1, 0, 0}}, &a));  // A at x = -1
    ASSERT_TRUE(scene.accel->Intersect(Ray{{5, 0, 0}, {-1, 0, 0}}, &b));  // B's carving
    EXPECT_NEAR(a.p.x, -1, 1e-5);
    EXPECT_NEAR(b.p.x, 0.1, 1e-5);
    const Material &ma = scene.materials[size_t(scene.Info(a).material)];
    const Material &mb = scene.materials[size_t(scene.Info(b).material)];
    EXPECT_FALSE(ma.MayReflectSpecularly());
    EXPECT_TRUE(mb.MayReflectSpecularly());
    EXPECT_EQ(scene.Info(a).type, "sphere");
}

TEST(CsgBuild, GlassLensFocusesParallelRays) {
    const double R = 10, c = 9.5, ior = 1.5, d = 2 * (R - c);
    RenderScene scene = Build(R"(
Material "glass" "float index" 1.5
CSGBegin "intersection"
  AttributeBegin Translate 0 0 9.5 Shape "sphere" "float radius" 10 AttributeEnd
  AttributeBegin Translate 0 0 -9.5 Shape "sphere" "float radius" 10 AttributeEnd
CSGEnd
)");
    double power = (ior - 1) * (2 / R - (ior - 1) * d / (ior * R * R));
    double bfd = (1 / power) * (1 - (ior - 1) * d / (ior * R));
    double zFocus = (R - c) + bfd;  // from the back vertex at z = R - c
    for (float h : {0.05f, 0.1f, 0.2f}) {
        Ray ray{{h, 0, -20}, {0, 0, 1}};
        // Two refractions, each through the hit material's specular transmission lobe.
        for (int surface = 0; surface < 2; ++surface) {
            SurfaceInteraction si;
            ASSERT_TRUE(scene.accel->Intersect(ray, &si));
            const Material &m = scene.materials[size_t(scene.Info(si).material)];
            ASSERT_TRUE(m.MayTransmit());
            BSDF bsdf = m.GetBSDF(si, TextureContext{si.uv, si.p, si.uv1});
            Vec3f wi;
            RGB weight;
            bool refracted = false;
            for (int part = 0; part < bsdf.NumParts() && !refracted; ++part)
                refracted = bsdf.SampleSpecularTransmission(part, si.wo, &wi, &weight);
            ASSERT_TRUE(refracted);
            ray = si.SpawnRay(wi);
        }
        SurfaceInteraction none;
        EXPECT_FALSE(scene.accel->Intersect(ray, &none));  // out of the lens for good
        double s = -double(ray.o.x) / double(ray.d.x);
        double z = double(ray.o.z) + s * double(ray.d.z);
        EXPECT_NEAR(z, zFocus, 0.01 * zFocus) << "h = " << h;
    }
}

}  // namespace
}  // namespace prism
