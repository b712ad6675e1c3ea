// pbrt-v4's ColorSpace and Attribute directives (scene/scene_builder_attributes.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/pbrt_parser.h"
#include "support/errors.h"

namespace prism {
namespace {

using namespace test;

TEST(PbrtAttribute, ShapeDefaultsAreScopedAndLoseToTheShapesOwn) {
    SceneDescription s = ParsePbrtText(R"(WorldBegin
        AttributeBegin
          Attribute "shape" "float radius" 2 "float zmax" 0.5
          Shape "sphere"
          Shape "sphere" "float radius" 3
          Attribute "shape" "float radius" 4
          Shape "sphere"
        AttributeEnd
        Shape "sphere")");
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_FLOAT_EQ(s.shapes[0].params.GetFloat("radius", 1), 2.f);
    EXPECT_FLOAT_EQ(s.shapes[0].params.GetFloat("zmax", 1), 0.5f);
    EXPECT_FLOAT_EQ(s.shapes[1].params.GetFloat("radius", 1), 3.f);
    // A later Attribute replaces the earlier one's parameter of the same name, keeps the rest.
    EXPECT_FLOAT_EQ(s.shapes[2].params.GetFloat("radius", 1), 4.f);
    EXPECT_FLOAT_EQ(s.shapes[2].params.GetFloat("zmax", 1), 0.5f);
    // AttributeEnd restores the defaults of before.
    EXPECT_FALSE(s.shapes[3].params.Has("radius"));
    // The attribute's location is the Attribute line's.
    EXPECT_EQ(s.shapes[0].params.Find("radius")->loc.ToString(), "s.pbrt:3:29");
    EXPECT_EQ(s.pbrtVersion.version, 4);
}

TEST(PbrtAttribute, EachTargetReachesItsOwnDirectives) {
    SceneDescription s = ParsePbrtText(R"(WorldBegin
        Attribute "light" "float scale" 5
        Attribute "material" "rgb reflectance" [0.1 0.2 0.3]
        Attribute "medium" "rgb sigma_a" [1 2 3]
        Attribute "texture" "float scale" 7
        Attribute "shape" "float radius" 9
        LightSource "point"
        AreaLightSource "diffuse"
        Material "diffuse"
        MakeNamedMaterial "m" "string type" "conductor"
        MakeNamedMedium "fog" "string type" "homogeneous"
        Texture "t" "float" "checkerboard"
        Shape "sphere")");
    EXPECT_FLOAT_EQ(s.lights.at(0).params.GetFloat("scale", 1), 5.f);
    EXPECT_FLOAT_EQ(s.areaLights.at(0).params.GetFloat("scale", 1), 5.f);
    for (const MaterialDesc &m : s.materials) {
        EXPECT_FLOAT_EQ(m.params.GetRGB("reflectance", RGB(0)).g, 0.2f);
        EXPECT_FALSE(m.params.Has("scale"));
        EXPECT_FALSE(m.params.Has("radius"));
    }
    EXPECT_FLOAT_EQ(s.media.at(0).params.GetRGB("sigma_a", RGB(0)).b, 3.f);
    EXPECT_FLOAT_EQ(s.textures.at(0).params.GetFloat("scale", 1), 7.f);
    EXPECT_FALSE(s.textures.at(0).params.Has("reflectance"));
    EXPECT_FLOAT_EQ(s.shapes.at(0).params.GetFloat("radius", 1), 9.f);
    EXPECT_FALSE(s.shapes.at(0).params.Has("scale"));
}

TEST(PbrtAttribute, DefaultsAreNeverReportedUnused) {
    SceneDescription s = ParsePbrtText(R"(WorldBegin
        Attribute "shape" "float radius" 2
        Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
                             "float bogus" 1)");
    Diagnostics diag;
    s.shapes.at(0).params.GetPoint3s("P");
    s.shapes.at(0).params.GetInts("indices");
    s.shapes.at(0).params.ReportUnused(diag, "shape");
    ASSERT_EQ(diag.Count(), 1u);  // "bogus" only
    EXPECT_NE(diag.Warnings()[0].message.find("bogus"), std::string::npos);
}

TEST(PbrtAttribute, InstancesAndNamedMediumTypesUseThem) {
    SceneDescription s = ParsePbrtText(R"(WorldBegin
        Attribute "medium" "string type" "homogeneous"
        MakeNamedMedium "fog"
        ObjectBegin "o"
          Attribute "shape" "float radius" 0.25
          Shape "sphere"
        ObjectEnd
        Shape "sphere")");
    EXPECT_EQ(s.media.at(0).type, "homogeneous");
    EXPECT_FLOAT_EQ(s.objects.at(0).shapes.at(0).params.GetFloat("radius", 1), 0.25f);
    EXPECT_FALSE(s.shapes.at(0).params.Has("radius"));  // ObjectEnd closed the scope
}

TEST(PbrtAttribute, UnknownTargetIsAnErrorAtTheDirective) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin\n  Attribute \"camera\" \"float fov\" 30"),
              "s.pbrt:2:3: error: unknown Attribute target \"camera\" (expected \"shape\", "
              "\"light\", \"material\", \"medium\" or \"texture\")");
}

TEST(PbrtColorSpace, IsScopedAndTagsWhatIsWrittenInIt) {
    SceneDescription s = ParsePbrtText(R"(ColorSpace "rec2020"
        Film "rgb"
        WorldBegin
        AttributeBegin
          ColorSpace "aces2065-1"
          LightSource "point" "rgb I" [1 1 1]
          Attribute "material" "rgb reflectance" [0.5 0.5 0.5]
          ColorSpace "srgb"
          Material "diffuse"
          Material "diffuse" "rgb reflectance" [0.2 0.4 0.6]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [0.2 0.4 0.6])");
    EXPECT_EQ(s.film.colorSpace, ColorSpaceId::Rec2020);
    const LightDesc &l = s.lights.at(0);
    EXPECT_EQ(l.colorSpace, ColorSpaceId::ACES2065_1);
    const Param *I = l.params.Find("I");
    EXPECT_EQ(I->colorSpace, ColorSpaceId::ACES2065_1);
    EXPECT_EQ(I->written, (std::vector<double>{1, 1, 1}));
    // As a reflectance a grey stays grey; as an emission ACES's white is warm in sRGB.
    EXPECT_NEAR(l.params.GetRGB("I", RGB(0)).r, 1, 1e-4);
    EXPECT_GT(EmissionRGB(*I).r, 1.02f);
    // An attribute keeps the space it was written in.
    EXPECT_EQ(s.materials.at(0).params.Find("reflectance")->colorSpace, ColorSpaceId::ACES2065_1);
    EXPECT_EQ(s.materials.at(1).params.Find("reflectance")->colorSpace, ColorSpaceId::SRGB);
    // Rec. 2020 again after AttributeEnd: (0.2, 0.4, 0.6) is another colour in sRGB.
    const Param *r = s.materials.at(2).params.Find("reflectance");
    EXPECT_EQ(r->colorSpace, ColorSpaceId::Rec2020);
    EXPECT_GT(std::abs(r->numbers[0] - 0.2), 0.02);
}

TEST(PbrtColorSpace, UnknownNameIsAnErrorAtTheDirective) {
    EXPECT_EQ(PbrtErrorOf("Film \"rgb\"\nColorSpace \"adobergb\""),
              "s.pbrt:2:1: error: unknown color space \"adobergb\" (expected \"srgb\", "
              "\"rec2020\", \"dci-p3\" or \"aces2065-1\")");
}

}  // namespace
}  // namespace prism
