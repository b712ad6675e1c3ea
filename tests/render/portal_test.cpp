// pbrt-v4's portal of an infinite light (render/infinite_light.h, LightSource "infinite"
// "portal"): which directions emit, the light samples through the rectangle against its solid
// angle and PdfLi, its errors, and a room lit through a window converging to the same image with
// and without it.
#include <gtest/gtest.h>

#include <cmath>

#include "image/image.h"
#include "render/infinite_light.h"
#include "support/image_stats.h"
#include "support/render_text.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

// A 2 x 1 rectangle in the plane z = 3 centred on the z axis, facing +z.
LightPortal Window() {
    LightPortal p;
    p.p0 = Vec3f(-1, -0.5f, 3);
    p.u = Vec3f(2, 0, 0);  // to the fourth corner
    p.v = Vec3f(0, 1, 0);  // to the second
    p.n = Vec3f(0, 0, 1);  // u x v
    p.area = 2;
    return p;
}

TEST(Portal, SamplesTheWindowAndEmitsOutward) {
    auto map = std::make_shared<Image>(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) map->SetRGB(x, y, RGB(0.5f + 0.1f * float(x), 1, 2));
    const InfiniteLight light(Transform(), RGB(1), map, 1, InfiniteLight::Projection::EqualArea,
                              Window());
    // Only directions toward the portal's outer side emit.
    EXPECT_FALSE(light.Le(Ray{Vec3f(0, 0, 0), Vec3f(0.3f, 0.2f, 1)}).IsBlack());
    EXPECT_TRUE(light.Le(Ray{Vec3f(0, 0, 0), Vec3f(0.3f, 0.2f, -1)}).IsBlack());
    EXPECT_TRUE(light.Le(Ray{Vec3f(0, 0, 0), Vec3f(1, 0, 0)}).IsBlack());

    // From a point on the axis 2 units inside, the samples cover the window's solid angle,
    // 4 asin(ab / sqrt((a² + d²)(b² + d²))) with half-sides a = 1, b = 0.5 and d = 2.
    SurfaceInteraction si;
    si.p = Vec3f(0, 0, 1);
    si.n = si.ns = Vec3f(0, 0, 1);
    si.wo = Vec3f(0, 0, 1);
    const double want = 4 * std::asin(0.5 / std::sqrt((1 + 4) * (0.25 + 4)));
    double solidAngle = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        LightSample ls;
        const Vec2f u((float(i % 200) + 0.5f) / 200, (float(i / 200) + 0.5f) / 100);
        ASSERT_TRUE(light.SampleLi(si, u, &ls));
        ASSERT_GT(ls.wi.z, 0.f);
        ASSERT_NEAR(light.PdfLi(si, ls.wi, nullptr), ls.pdf, 1e-3f * ls.pdf) << i;
        EXPECT_EQ(ls.Li, light.Le(Ray{si.p, ls.wi}));
        solidAngle += 1 / double(ls.pdf);
    }
    EXPECT_NEAR(solidAngle / n, want, 1e-3 * want);
    // Directions that miss the window have no density; nor does anything from outside.
    EXPECT_EQ(light.PdfLi(si, Normalize(Vec3f(1, 0, 1)), nullptr), 0.f);
    EXPECT_EQ(light.PdfLi(si, Vec3f(0, 0, -1), nullptr), 0.f);
    si.p = Vec3f(0, 0, 4);
    LightSample ls;
    EXPECT_FALSE(light.SampleLi(si, Vec2f(0.5f, 0.5f), &ls));
    EXPECT_EQ(light.PdfLi(si, Vec3f(0, 0, -1), nullptr), 0.f);
    // The power counts the half of the sphere that emits: about half the light's without.
    const InfiniteLight whole(Transform(), RGB(1), map, 1, InfiniteLight::Projection::EqualArea);
    EXPECT_NEAR(light.Power(1), 0.5 * whole.Power(1), 0.1 * whole.Power(1));
}

// A closed room whose one window faces the sky map: the portal changes the noise, not the image.
std::string Room(const std::string &portal) {
    auto quad = [](const std::string &p) {
        return "Shape \"trianglemesh\" \"point3 P\" [" + p +
               "] \"integer indices\" [0 1 2 0 2 3]\n";
    };
    return "LookAt 0 1.3 -1.7  0 1 3  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
           "Sampler \"independent\"\nWorldBegin\nAttributeBegin\nRotate -90 1 0 0\n"
           "LightSource \"infinite\" \"string filename\" \"sky.pfm\" " +
           portal + "\nAttributeEnd\nMaterial \"diffuse\" \"rgb reflectance\" [0.6 0.6 0.6]\n" +
           quad("-2 0 -2 2 0 -2 2 0 3 -2 0 3") + quad("-2 2.5 -2 -2 2.5 3 2 2.5 3 2 2.5 -2") +
           quad("-2 0 -2 -2 2.5 -2 2 2.5 -2 2 0 -2") + quad("-2 0 -2 -2 0 3 -2 2.5 3 -2 2.5 -2") +
           quad("2 0 -2 2 2.5 -2 2 2.5 3 2 0 3") + quad("-2 0 3 2 0 3 2 0.8 3 -2 0.8 3") +
           quad("-2 2 3 2 2 3 2 2.5 3 -2 2.5 3") + quad("-2 0.8 3 -1 0.8 3 -1 2 3 -2 2 3") +
           quad("1 0.8 3 2 0.8 3 2 2 3 1 2 3");
}

TEST(Portal, RoomThroughAWindowConvergesToTheSameImage) {
    // The sky: a square equal-area map, brighter toward one side.
    const std::string dir = "portal";
    std::string pfm = "PF\n16 16\n-1\n";
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (float v : {0.4f + 0.2f * float(y), 1.f, 2.f})
                pfm.append(reinterpret_cast<const char *>(&v), sizeof v);
    WriteTestFile(ScratchDir(dir) / "sky.pfm", pfm);
    const std::string portal = "\"point3 portal\" [-1 0.8 3  -1 2 3  1 2 3  1 0.8 3]";
    const Rendered reference = RenderSceneText(dir, "ref", Room(""), SizedSettings(24, 18, 1024));
    const Rendered without = RenderSceneText(dir, "without", Room(""), SizedSettings(24, 18, 64));
    const Rendered with = RenderSceneText(dir, "with", Room(portal), SizedSettings(24, 18, 64));
    EXPECT_TRUE(with.warnings.empty()) << with.warnings[0].ToString();
    const double errWithout = RelL1(without.image, reference.image),
                 errWith = RelL1(with.image, reference.image);
    EXPECT_LT(errWith, 0.5 * errWithout);
    EXPECT_NEAR(MeanValue(with.image), MeanValue(reference.image),
                0.03 * MeanValue(reference.image));
}

}  // namespace
}  // namespace prism
