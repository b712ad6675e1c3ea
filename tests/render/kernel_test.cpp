// The kernels specialized per effect set (render/kernel.h): the kernel mask of real scenes;
// for each effect, a scene without it traces no ray of its kind; and the specialized kernel
// renders bit-identical images to the general one (--effects all). The effect set itself:
// tests/assembly/scene_effects_test.cpp.
#include "render/kernel.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "assembly/build_scene.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace prism {
namespace {

using namespace test;

RenderScene Build(const std::string &path, int w = 48, int h = 36, int spp = 2,
                  bool allEffects = false) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(path, diag);
    BuildSettings s;
    s.resolution = Vec2i(w, h);
    s.spp = spp;
    s.allEffects = allEffects;
    s.defaultIntegrator = "whitted";  // the kernel's scenes name none
    return BuildRenderScene(desc, s, diag);
}

struct Result {
    Image image;
    RenderStats stats;
};

Result RenderWith(const std::string &path, bool allEffects, int w = 48, int h = 36, int spp = 2) {
    RenderScene scene = Build(path, w, h, spp, allEffects);
    Result r;
    r.image = Render(scene, &r.stats);
    return r;
}

std::string Write(const std::string &name, const std::string &text) {
    return WriteTestFile(ScratchDir("kernel") / name, text);
}

const std::string Header =
    "LookAt 0 1 -5  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n"
    "Sampler \"stratified\" \"integer xsamples\" [ 2 ] \"integer ysamples\" [ 1 ]\n";
const std::string Floor =
    "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
    "  \"point3 P\" [ -10 0 -10  10 0 -10  10 0 10  -10 0 10 ]\n";

// Effects of one kind each, for scenes written here.
std::string DiffuseScene() {
    return Write("diffuse.pbrt", Header +
                                     "WorldBegin\n"
                                     "LightSource \"point\" \"point3 from\" [ 2 5 -3 ] "
                                     "\"rgb I\" [ 30 30 30 ]\n" +
                                     Floor + "Translate 0 1 0\nShape \"sphere\"\nWorldEnd\n");
}
std::string LensScene() {
    return Write("lens.pbrt",
                 "LookAt 0 1 -5  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ] "
                 "\"float lensradius\" [ 0.2 ] \"float focaldistance\" [ 5 ]\n"
                 "WorldBegin\nLightSource \"point\" \"point3 from\" [ 2 5 -3 ] \"rgb I\" [ 30 30 "
                 "30 ]\n" +
                     Floor + "Translate 0 1 0\nShape \"sphere\"\nWorldEnd\n");
}
std::string PassThroughScene() {
    return Write("none.pbrt", Header +
                                  "WorldBegin\n"
                                  "LightSource \"point\" \"point3 from\" [ 2 5 -3 ] "
                                  "\"rgb I\" [ 30 30 30 ]\n" +
                                  Floor +
                                  "AttributeBegin\nMaterial \"none\"\nTranslate 0 1 -1\n"
                                  "Shape \"sphere\" \"float radius\" 1.5\nAttributeEnd\n"
                                  "Translate 0 1 0\nShape \"sphere\"\nWorldEnd\n");
}
std::string AreaLightScene() {
    return Write("area.pbrt", Header +
                                  "WorldBegin\n"
                                  "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 "
                                  "4 ] \"integer nsamples\" [ 4 ]\nTranslate 0 4 0\n"
                                  "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n" +
                                  Floor + "Translate 0 1 0\nShape \"sphere\"\nWorldEnd\n");
}
// Lambertian with a texture (kd evaluated per hit), and with Oren–Nayar (the BSDF kernel).
std::string TexturedScene() {
    return Write("textured.pbrt",
                 Header +
                     "WorldBegin\nLightSource \"point\" \"point3 from\" [ 2 5 -3 ] "
                     "\"rgb I\" [ 30 30 30 ]\nLightSource \"distant\" \"point3 to\" [ 0 -1 1 ]\n"
                     "Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 8 "
                     "\"float vscale\" 8\nMaterial \"matte\" \"texture Kd\" \"c\"\n" +
                     Floor + "Translate 0 1 0\nShape \"sphere\"\nWorldEnd\n");
}
std::string OrenNayarScene() {
    return Write("oren.pbrt", Header +
                                  "WorldBegin\nLightSource \"point\" \"point3 from\" [ 2 5 -3 ] "
                                  "\"rgb I\" [ 30 30 30 ]\n" +
                                  Floor +
                                  "Material \"matte\" \"float sigma\" 20\nTranslate 0 1 0\n"
                                  "Shape \"sphere\"\nWorldEnd\n");
}
std::string DarkScene() {  // no light at all
    return Write("dark.pbrt", Header + "WorldBegin\n" + Floor + "WorldEnd\n");
}
// An OBJ scene (no integrator named: the distribution integrator), a diffuse and a glossy
// material.
std::string ObjScene() {
    fs::path dir = ScratchDir("kernel");
    WriteTestFile(dir / "k.mtl",
                  "newmtl white\nKd 0.7 0.7 0.7\n"
                  "newmtl shiny\nKd 0.2 0.2 0.6\nKs 0.5 0.5 0.5\nNs 60\n");
    return WriteTestFile(dir / "k.obj",
                         "mtllib k.mtl\n"
                         "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\n"
                         "v -1 0 0\nv 1 0 0\nv 0 2 0.5\n"
                         "usemtl white\nf 1 2 3\nf 1 3 4\n"
                         "usemtl shiny\nf 5 6 7\n");
}

std::string Scene(const std::string &name) { return Source + "/scenes/" + name; }

bool SameBits(const Image &a, const Image &b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

void ExpectSameRays(const RayCounters &a, const RayCounters &b) {
    EXPECT_EQ(a.camera, b.camera);
    EXPECT_EQ(a.shadow, b.shadow);
    EXPECT_EQ(a.reflection, b.reflection);
    EXPECT_EQ(a.refraction, b.refraction);
    EXPECT_EQ(a.passThrough, b.passThrough);
    EXPECT_EQ(a.glossy, b.glossy);
    EXPECT_EQ(a.lensSamples, b.lensSamples);
}

TEST(Effects, KernelMasksOfRealScenes) {
    EXPECT_EQ(KernelMaskFor(Build(Scene("whitted.pbrt"))),
              KernelSpecular | KernelLightSamples | KernelBsdf);

    RenderScene csg = Build(Scene("csg.pbrt"));
    EXPECT_TRUE(csg.features.effects.Has(Effect::Csg));
    EXPECT_NE(csg.features.effects.reasons[size_t(Effect::Csg)].find("CSGBegin"),
              std::string::npos);
    EXPECT_TRUE(csg.features.effects.Has(Effect::Refraction));

    RenderScene glossy = Build(Scene("glossy.pbrt"));
    const EffectSet &g = glossy.features.effects;
    EXPECT_TRUE(g.Has(Effect::GlossyReflection));
    EXPECT_TRUE(g.Has(Effect::GlossyTransmission));
    EXPECT_TRUE(g.Has(Effect::SoftShadows));
    EXPECT_NE(g.reasons[size_t(Effect::SoftShadows)].find("AreaLightSource"), std::string::npos);
    EXPECT_TRUE(KernelMaskFor(glossy) & KernelGlossy);

    RenderScene diffuse = Build(Scene("diffuse.pbrt"));
    const EffectSet &d = diffuse.features.effects;
    EXPECT_EQ(d.mask, EffectBit(Effect::Shadows));
    EXPECT_EQ(d.maxUsefulDepth, 1);
    EXPECT_EQ(KernelMaskFor(diffuse), 0u);
    EXPECT_EQ(KernelMaskName(0), "Lambertian");
    EXPECT_EQ(KernelMaskName(KernelAll), "all");

    RenderScene lens = Build(LensScene());
    EXPECT_TRUE(lens.features.effects.Has(Effect::DepthOfField));
    EXPECT_NE(lens.features.effects.reasons[size_t(Effect::DepthOfField)].find("lensradius"),
              std::string::npos);
    EXPECT_EQ(KernelMaskFor(lens), uint32_t(KernelCameraSamples));
    EXPECT_EQ(KernelMaskFor(Build(PassThroughScene())), uint32_t(KernelPassThrough));
    EXPECT_EQ(KernelMaskFor(Build(TexturedScene())), 0u);
    EXPECT_TRUE(Build(TexturedScene()).features.effects.Has(Effect::Textures));
    EXPECT_EQ(KernelMaskFor(Build(OrenNayarScene())), uint32_t(KernelBsdf));

    RenderScene obj = Build(ObjScene());
    EXPECT_STREQ(obj.IntegratorName(), "distribution");
    EXPECT_TRUE(obj.features.effects.Has(Effect::GlossyReflection));
}

// For each effect, a scene without it traces none of its rays (and one with it does).
TEST(Effects, ScenesWithoutAnEffectTraceNoneOfItsRays) {
    const RayCounters d = RenderWith(DiffuseScene(), false).stats.rays;
    EXPECT_GT(d.shadow, 0u);
    EXPECT_EQ(d.reflection, 0u);
    EXPECT_EQ(d.refraction, 0u);
    EXPECT_EQ(d.glossy, 0u);
    EXPECT_EQ(d.passThrough, 0u);
    EXPECT_EQ(d.lensSamples, 0u);
    // The general kernel on the same scene does not trace them either.
    const RayCounters da = RenderWith(DiffuseScene(), true).stats.rays;
    ExpectSameRays(d, da);

    EXPECT_EQ(RenderWith(DarkScene(), false).stats.rays.shadow, 0u);
    EXPECT_GT(RenderWith(LensScene(), false).stats.rays.lensSamples, 0u);
    EXPECT_GT(RenderWith(PassThroughScene(), false).stats.rays.passThrough, 0u);
    const RayCounters w = RenderWith(Scene("whitted.pbrt"), false).stats.rays;
    EXPECT_GT(w.reflection, 0u);
    EXPECT_GT(w.refraction, 0u);
    EXPECT_EQ(w.glossy, 0u);
    const RayCounters g = RenderWith(Scene("glossy.pbrt"), false).stats.rays;
    EXPECT_GT(g.glossy, 0u);
    EXPECT_EQ(g.reflection, 0u);
    EXPECT_EQ(g.refraction, 0u);
}

// The specialized kernel and the general one (--effects all) give the same bits.
TEST(Effects, SpecializedAndGeneralKernelsAreBitIdentical) {
    for (const std::string &path :
         {Scene("whitted.pbrt"), Scene("csg.pbrt"), Scene("glossy.pbrt"), Scene("diffuse.pbrt"),
          ObjScene(), LensScene(), PassThroughScene(), AreaLightScene(), TexturedScene(),
          OrenNayarScene(), DarkScene()}) {
        SCOPED_TRACE(path);
        Result spec = RenderWith(path, false), all = RenderWith(path, true);
        EXPECT_EQ(all.stats.kernelMask, KernelAll);
        EXPECT_EQ(spec.stats.kernelMask, KernelMaskFor(Build(path)));
        EXPECT_TRUE(SameBits(spec.image, all.image));
        ExpectSameRays(spec.stats.rays, all.stats.rays);
    }
}

}  // namespace
}  // namespace prism
