// The effect set (assembly/scene_effects.h, render/effects.h): which effects a scene calls for,
// each with the reason and location of the directive that turned it on; each light's shadows;
// the maximum useful depth; which materials count as specular or glossy under each integrator.
#include "assembly/scene_effects.h"

#include <gtest/gtest.h>

#include <string>

#include "assembly/build_scene.h"
#include "scene/load_scene.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

RenderScene Build(const std::string &path, const std::string &integrator = "") {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(path, diag);
    BuildSettings s;
    s.buildBvh = false;
    s.integrator = integrator;
    s.defaultIntegrator = "whitted";
    return BuildRenderScene(desc, s, diag);
}

std::string Write(const std::string &name, const std::string &text) {
    return WriteTestFile(ScratchDir("scene_effects") / name, text);
}

std::string Scene(const std::string &name) { return Source + "/scenes/" + name; }

const std::string Header =
    "LookAt 0 1 -5  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n";

const std::string &Reason(const RenderScene &s, Effect e) {
    return s.features.effects.reasons[size_t(e)];
}

TEST(Effects, WhittedSceneListsItsEffectsWithLocations) {
    RenderScene s = Build(Scene("whitted.pbrt"));
    const EffectSet &e = s.features.effects;
    EXPECT_TRUE(e.Has(Effect::Shadows));
    EXPECT_TRUE(e.Has(Effect::SpecularReflection));
    EXPECT_NE(e.reasons[size_t(Effect::SpecularReflection)].find("material \"mirror\" at "),
              std::string::npos)
        << e.reasons[size_t(Effect::SpecularReflection)];
    EXPECT_NE(e.reasons[size_t(Effect::Refraction)].find("material \"glass\" at "),
              std::string::npos);
    EXPECT_NE(e.reasons[size_t(Effect::Refraction)].find("whitted.pbrt:39"), std::string::npos)
        << e.reasons[size_t(Effect::Refraction)];
    EXPECT_TRUE(e.Has(Effect::Textures));
    EXPECT_TRUE(e.Has(Effect::Environment));
    EXPECT_NE(e.reasons[size_t(Effect::Environment)].find("whitted.pbrt:19"), std::string::npos);
    // Integrator "whitted" traces no glossy rays.
    EXPECT_FALSE(e.Has(Effect::GlossyReflection));
    EXPECT_FALSE(e.Has(Effect::SoftShadows));
    EXPECT_FALSE(e.Has(Effect::DepthOfField));
    EXPECT_FALSE(e.Has(Effect::MotionBlur));
    EXPECT_FALSE(e.Has(Effect::Csg));
    EXPECT_FALSE(e.Has(Effect::Instancing));
    ASSERT_EQ(e.lights.size(), 3u);
    EXPECT_EQ(e.lights[0].shadowRays, 1);
    EXPECT_EQ(e.lights[2].shadowRays, 4);  // the infinite light's nsamples
    EXPECT_EQ(e.maxUsefulDepth, 6);
}

TEST(Effects, InstancingIsNoted) {
    std::string path =
        Write("inst.pbrt", Header +
                               "WorldBegin\nLightSource \"point\" \"point3 from\" [ 2 5 -3 ]\n"
                               "ObjectBegin \"ball\"\nShape \"sphere\"\nObjectEnd\n"
                               "ObjectInstance \"ball\"\nWorldEnd\n");
    RenderScene s = Build(path);
    EXPECT_TRUE(s.features.effects.Has(Effect::Instancing));
    EXPECT_NE(s.features.effects.reasons[size_t(Effect::Instancing)].find("inst.pbrt:8"),
              std::string::npos)
        << s.features.effects.reasons[size_t(Effect::Instancing)];
}

TEST(Effects, DistributionTurnsRoughGlassAndMetalGlossy) {
    std::string path = Write("rough.pbrt", Header +
                                               "WorldBegin\n"
                                               "LightSource \"point\" \"point3 from\" [ 0 5 0 ]\n"
                                               "Material \"glass\" \"float roughness\" [ 0.1 ]\n"
                                               "Shape \"sphere\"\n"
                                               "Material \"metal\" \"float roughness\" [ 0.2 ]\n"
                                               "Shape \"sphere\"\nWorldEnd\n");
    // Whitted follows rough glass as smooth (pbrt-v3) and shades rough metal by light samples.
    RenderScene w = Build(path, "whitted");
    EXPECT_TRUE(w.features.effects.Has(Effect::SpecularReflection));
    EXPECT_TRUE(w.features.effects.Has(Effect::Refraction));
    EXPECT_FALSE(w.features.effects.Has(Effect::GlossyReflection));
    EXPECT_EQ(w.features.effects.maxUsefulDepth, 5);
    // Distribution: both glossy, nothing specular.
    RenderScene d = Build(path, "distribution");
    EXPECT_FALSE(d.features.effects.Has(Effect::SpecularReflection));
    EXPECT_FALSE(d.features.effects.Has(Effect::Refraction));
    EXPECT_TRUE(d.features.effects.Has(Effect::GlossyReflection));
    EXPECT_TRUE(d.features.effects.Has(Effect::GlossyTransmission));
    EXPECT_NE(Reason(d, Effect::GlossyTransmission).find("material \"glass\" at "),
              std::string::npos)
        << Reason(d, Effect::GlossyTransmission);
    EXPECT_NE(Reason(d, Effect::GlossyTransmission).find("rough.pbrt:5"), std::string::npos);
}

TEST(Effects, PolishedMetalIsSpecularAndMatteIsNothing) {
    std::string path = Write("plain.pbrt", Header +
                                               "WorldBegin\n"
                                               "LightSource \"spot\"\n"
                                               "Material \"metal\" \"float roughness\" [ 0 ] "
                                               "\"bool remaproughness\" \"false\"\n"
                                               "Shape \"sphere\"\n"
                                               "Material \"matte\"\nShape \"sphere\"\nWorldEnd\n");
    RenderScene s = Build(path, "distribution");
    EXPECT_TRUE(s.features.effects.Has(Effect::SpecularReflection));
    EXPECT_FALSE(s.features.effects.Has(Effect::GlossyReflection));
    EXPECT_FALSE(s.features.effects.Has(Effect::Textures));

    std::string matte = Write("matte.pbrt", Header + "WorldBegin\nShape \"sphere\"\nWorldEnd\n");
    RenderScene m = Build(matte);
    EXPECT_EQ(m.features.effects.mask, 0u);  // no light: no shadows either
    EXPECT_TRUE(m.features.effects.lights.empty());
    EXPECT_EQ(m.features.effects.maxUsefulDepth, 1);
}

TEST(Effects, AreaLightsLensAndCsgHaveTheirLocations) {
    std::string path =
        Write("misc.pbrt",
              "LookAt 0 1 -5  0 0.5 0  0 1 0\n"
              "Camera \"perspective\" \"float lensradius\" [ 0.1 ] \"float focaldistance\" [ 5 ]\n"
              "WorldBegin\n"
              "AttributeBegin\nAreaLightSource \"diffuse\" \"integer nsamples\" [ 9 ]\n"
              "Shape \"sphere\"\nAttributeEnd\n"
              "CSGBegin \"union\"\nShape \"sphere\"\nShape \"sphere\" \"float radius\" 2\nCSGEnd\n"
              "WorldEnd\n");
    RenderScene s = Build(path);
    const EffectSet &e = s.features.effects;
    EXPECT_NE(Reason(s, Effect::DepthOfField).find("\"lensradius\" at "), std::string::npos)
        << Reason(s, Effect::DepthOfField);
    EXPECT_NE(Reason(s, Effect::DepthOfField).find("misc.pbrt:2"), std::string::npos);
    EXPECT_NE(Reason(s, Effect::SoftShadows).find("AreaLightSource \"diffuse\" at "),
              std::string::npos);
    EXPECT_NE(Reason(s, Effect::SoftShadows).find("misc.pbrt:5"), std::string::npos);
    ASSERT_EQ(e.lights.size(), 1u);
    EXPECT_EQ(e.lights[0].shadowRays, 9);
    EXPECT_NE(Reason(s, Effect::Csg).find("CSGBegin \"union\" at "), std::string::npos);
    EXPECT_NE(Reason(s, Effect::Csg).find("misc.pbrt:8"), std::string::npos)
        << Reason(s, Effect::Csg);
}

}  // namespace
}  // namespace prism
