#include "scene/pbrt_parser.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "support/errors.h"
#include "support/shared.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

namespace fs = std::filesystem;

SceneDescription Parse(const std::string &text, Diagnostics *diagOut = nullptr) {
    Diagnostics diag;
    SceneDescription s = ParsePbrtString(text, "s.pbrt", diagOut ? *diagOut : diag);
    return s;
}

Vec3d Origin(const Transform &t) { return t.Point(Vec3d(0, 0, 0)); }

TEST(PbrtParser, DefaultsAndFormat) {
    SceneDescription s = Parse("WorldBegin WorldEnd");
    EXPECT_EQ(s.format, "pbrt");
    EXPECT_EQ(s.sourceFile, "s.pbrt");
    EXPECT_EQ(s.baseDir, "");
    EXPECT_FALSE(s.camera.specified);
    EXPECT_EQ(s.integrator.type, "path");
    EXPECT_TRUE(s.shapes.empty());
}

TEST(PbrtParser, OptionsBlock) {
    SceneDescription s = Parse(R"(
        LookAt 0 0 -5  0 0 0  0 1 0
        Camera "perspective" "float fov" 45
        Film "image" "integer xresolution" 64 "integer yresolution" 32 "string filename" "o.exr"
        Sampler "halton" "integer pixelsamples" 4
        PixelFilter "gaussian"
        Integrator "whitted" "integer maxdepth" 7
        Accelerator "kdtree"
        WorldBegin WorldEnd)");
    EXPECT_TRUE(s.camera.specified);
    EXPECT_EQ(s.camera.type, "perspective");
    EXPECT_FLOAT_EQ(s.camera.params.GetFloat("fov", 0), 45.f);
    EXPECT_EQ(s.camera.loc.ToString(), "s.pbrt:3:9");
    // cameraFromWorld maps the eye to the camera-space origin.
    Vec3d eye = s.camera.cameraFromWorld.Point(Vec3d(0, 0, -5));
    EXPECT_NEAR(Length(eye), 0.0, 1e-12);
    Vec3d ahead = s.camera.cameraFromWorld.Point(Vec3d(0, 0, 0));
    EXPECT_NEAR(ahead.z, 5.0, 1e-12);
    EXPECT_EQ(s.film.params.GetInt("xresolution", 0), 64);
    EXPECT_EQ(s.sampler.params.GetInt("pixelsamples", 0), 4);
    EXPECT_EQ(s.filter.type, "gaussian");
    EXPECT_EQ(s.integrator.type, "whitted");
    EXPECT_EQ(s.integrator.params.GetInt("maxdepth", 0), 7);
}

TEST(PbrtParser, ScaleBeforeLookAtEntersCameraTransform) {
    SceneDescription s = Parse(R"(Scale -1 1 1 LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" WorldBegin)");
    EXPECT_TRUE(s.camera.cameraFromWorld.SwapsHandedness());
    Vec3d p = s.camera.cameraFromWorld.Point(Vec3d(1, 2, 3));
    EXPECT_NEAR(p.x, -1, 1e-12);
    EXPECT_NEAR(p.y, 2, 1e-12);
    EXPECT_NEAR(p.z, 3, 1e-12);
}

TEST(PbrtParser, WorldBeginResetsTransform) {
    SceneDescription s = Parse(R"(Translate 5 5 5 Camera "perspective"
        WorldBegin Shape "sphere")");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_TRUE(s.shapes[0].worldFromObject.IsIdentity());
}

TEST(PbrtParser, AttributeScopesTransformAndState) {
    SceneDescription s = Parse(R"(WorldBegin
        Material "plastic"
        AttributeBegin
          Translate 1 0 0
          Material "glass"
          ReverseOrientation
          AreaLightSource "diffuse" "rgb L" [1 1 1]
          Shape "sphere"
          AttributeBegin
            Translate 0 2 0
            Shape "disk"
          AttributeEnd
          Shape "cylinder"
        AttributeEnd
        Shape "cone")");
    ASSERT_EQ(s.shapes.size(), 4u);
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].type, "plastic");
    EXPECT_EQ(s.materials[1].type, "glass");
    const ShapeDesc &sphere = s.shapes[0], &disk = s.shapes[1], &cyl = s.shapes[2],
                    &cone = s.shapes[3];
    EXPECT_EQ(Origin(sphere.worldFromObject), Vec3d(1, 0, 0));
    EXPECT_EQ(Origin(disk.worldFromObject), Vec3d(1, 2, 0));
    EXPECT_EQ(Origin(cyl.worldFromObject), Vec3d(1, 0, 0));
    EXPECT_TRUE(cone.worldFromObject.IsIdentity());
    EXPECT_EQ(sphere.material, 1);
    EXPECT_EQ(disk.material, 1);
    EXPECT_EQ(cone.material, 0);
    EXPECT_TRUE(sphere.reverseOrientation);
    EXPECT_TRUE(cyl.reverseOrientation);
    EXPECT_FALSE(cone.reverseOrientation);
    EXPECT_EQ(sphere.areaLight, 0);
    EXPECT_EQ(disk.areaLight, 0);
    EXPECT_EQ(cone.areaLight, -1);
    ASSERT_EQ(s.areaLights.size(), 1u);
    EXPECT_EQ(s.areaLights[0].type, "diffuse");
    EXPECT_EQ(s.areaLights[0].params.GetRGB("L", {}), RGB(1.f));
}

TEST(PbrtParser, DefaultMaterialIsMinusOne) {
    SceneDescription s = Parse(R"(WorldBegin Shape "sphere")");
    EXPECT_EQ(s.shapes[0].material, -1);
    EXPECT_EQ(s.shapes[0].areaLight, -1);
    EXPECT_EQ(s.shapes[0].type, "sphere");
    EXPECT_EQ(s.shapes[0].loc.ToString(), "s.pbrt:1:12");
}

TEST(PbrtParser, TransformBeginScopesOnlyTheTransform) {
    SceneDescription s = Parse(R"(WorldBegin
        TransformBegin
          Translate 0 0 3
          Material "mirror"
          ReverseOrientation
          Shape "sphere"
        TransformEnd
        Shape "disk")");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(Origin(s.shapes[0].worldFromObject), Vec3d(0, 0, 3));
    EXPECT_TRUE(s.shapes[1].worldFromObject.IsIdentity());
    EXPECT_EQ(s.shapes[1].material, 0);  // the material is not scoped by TransformBegin
    EXPECT_TRUE(s.shapes[1].reverseOrientation);
}

TEST(PbrtParser, TransformDirectives) {
    SceneDescription s = Parse(R"(WorldBegin
        Translate 1 2 3 Scale 2 2 2 Shape "a"
        Identity Rotate 90 0 0 1 Shape "b"
        Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1] Shape "c"
        ConcatTransform [2 0 0 0  0 2 0 0  0 0 2 0  1 0 0 1] Shape "d"
        Transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1 Shape "e")");
    ASSERT_EQ(s.shapes.size(), 5u);
    Vec3d a = s.shapes[0].worldFromObject.Point(Vec3d(1, 0, 0));
    EXPECT_EQ(a, Vec3d(3, 2, 3));  // translate ∘ scale: post-multiplied
    Vec3d b = s.shapes[1].worldFromObject.Point(Vec3d(1, 0, 0));
    EXPECT_NEAR(b.x, 0, 1e-12);
    EXPECT_NEAR(b.y, 1, 1e-12);
    EXPECT_EQ(Origin(s.shapes[2].worldFromObject), Vec3d(5, 6, 7));
    EXPECT_EQ(s.shapes[3].worldFromObject.Point(Vec3d(1, 0, 0)), Vec3d(8, 6, 7));
    EXPECT_EQ(Origin(s.shapes[4].worldFromObject), Vec3d(-1, 0, 0));
}

TEST(PbrtParser, NamedMaterialsAreScoped) {
    SceneDescription s = Parse(R"(WorldBegin
        MakeNamedMaterial "red" "string type" "matte" "rgb Kd" [1 0 0]
        AttributeBegin
          MakeNamedMaterial "red" "string type" "plastic"
          NamedMaterial "red"
          Shape "sphere"
          MakeNamedMaterial "inner" "string type" "glass"
        AttributeEnd
        NamedMaterial "red"
        Shape "disk")");
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[0].name, "red");
    EXPECT_EQ(s.materials[0].type, "matte");
    EXPECT_EQ(s.materials[1].type, "plastic");
    EXPECT_EQ(s.shapes[0].material, 1);
    EXPECT_EQ(s.shapes[1].material, 0);  // the inner redefinition did not leak out
    // "type" is consumed by the parser, so it never shows up as an unused parameter.
    Diagnostics diag;
    s.materials[0].params.GetRGB("Kd", {});
    s.materials[0].params.ReportUnused(diag, "");
    EXPECT_EQ(diag.Count(), 0u);
    EXPECT_EQ(
        PbrtErrorOf(R"(WorldBegin AttributeBegin MakeNamedMaterial "inner" "string type" "glass"
        AttributeEnd NamedMaterial "inner")"),
        "s.pbrt:2:22: error: unknown named material \"inner\"");
}

TEST(PbrtParser, NamedMaterialErrors) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin NamedMaterial \"nope\""),
              "s.pbrt:1:12: error: unknown named material \"nope\"");
    EXPECT_EQ(PbrtErrorOf("WorldBegin MakeNamedMaterial \"m\" \"rgb Kd\" [1 1 1]"),
              "s.pbrt:1:12: error: MakeNamedMaterial \"m\" needs a \"string type\" parameter");
}

TEST(PbrtParser, Textures) {
    SceneDescription s = Parse(R"(WorldBegin
        Translate 1 0 0
        Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "rgb tex1" [1 0 0]
        Texture "bump" "float" "imagemap" "string filename" "b.png"
        Texture "c" "color" "constant"
        Material "matte" "texture Kd" "checks")");
    ASSERT_EQ(s.textures.size(), 3u);
    EXPECT_EQ(s.textures[0].name, "checks");
    EXPECT_EQ(s.textures[0].type, "checkerboard");
    EXPECT_FALSE(s.textures[0].isFloat);
    EXPECT_TRUE(s.textures[1].isFloat);
    EXPECT_EQ(Origin(s.textures[0].worldFromTexture), Vec3d(1, 0, 0));
    EXPECT_EQ(s.materials[0].params.GetTexture("Kd"), "checks");
    EXPECT_EQ(PbrtErrorOf(R"(WorldBegin Texture "t" "vector" "constant")"),
              "s.pbrt:1:12: error: texture \"t\": unknown texture type \"vector\" "
              "(expected \"float\" or \"spectrum\")");
}

TEST(PbrtParser, Lights) {
    SceneDescription s = Parse(R"(WorldBegin
        AttributeBegin Rotate -90 1 0 0
          LightSource "infinite" "rgb L" [0.5 0.5 0.5]
        AttributeEnd
        LightSource "point" "point from" [0 4 0] "blackbody I" [5500 1])");
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, "infinite");
    EXPECT_TRUE(s.lights[0].worldFromLight.Vector(Vec3d(0, 0, 1)).y > 0.99);
    EXPECT_TRUE(s.lights[1].worldFromLight.IsIdentity());
    EXPECT_EQ(s.lights[1].params.GetPoint3("from", {}), Vec3f(0, 4, 0));
}

TEST(PbrtParser, CoordinateSystems) {
    SceneDescription s = Parse(R"(
        LookAt 0 0 -10  0 0 0  0 1 0
        Camera "perspective"
        WorldBegin
        Translate 3 0 0
        CoordinateSystem "mine"
        Identity
        CoordSysTransform "camera"
        Shape "a"
        CoordSysTransform "mine"
        Shape "b"
        CoordSysTransform "world"
        Shape "c")");
    ASSERT_EQ(s.shapes.size(), 3u);
    // "camera" is the camera-to-world frame: its origin is the eye.
    Vec3d eye = Origin(s.shapes[0].worldFromObject);
    EXPECT_NEAR(eye.x, 0, 1e-12);
    EXPECT_NEAR(eye.z, -10, 1e-12);
    EXPECT_EQ(Origin(s.shapes[1].worldFromObject), Vec3d(3, 0, 0));
    EXPECT_TRUE(s.shapes[2].worldFromObject.IsIdentity());
    EXPECT_EQ(PbrtErrorOf("WorldBegin CoordSysTransform \"nope\""),
              "s.pbrt:1:12: error: unknown coordinate system \"nope\"");
}

TEST(PbrtParser, ObjectsAndInstances) {
    SceneDescription s = Parse(R"(WorldBegin
        Shape "before"
        ObjectBegin "tree"
          Material "matte"
          Translate 0 1 0
          Shape "sphere"
          Shape "cylinder"
        ObjectEnd
        Shape "after"
        Translate 5 0 0
        ObjectInstance "tree"
        Translate 5 0 0
        ObjectInstance "tree")");
    ASSERT_EQ(s.shapes.size(), 2u);  // object shapes are not top-level shapes
    EXPECT_EQ(s.shapes[0].directiveIndex, 0);
    EXPECT_EQ(s.shapes[1].directiveIndex, 1);
    EXPECT_EQ(s.shapes[1].material, -1);  // ObjectBegin scopes attributes as in pbrt-v3
    EXPECT_TRUE(s.shapes[1].worldFromObject.IsIdentity());
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "tree");
    ASSERT_EQ(s.objects[0].shapes.size(), 2u);
    EXPECT_EQ(s.objects[0].shapes[1].type, "cylinder");
    EXPECT_EQ(s.objects[0].shapes[0].material, 0);
    EXPECT_EQ(Origin(s.objects[0].shapes[0].worldFromObject), Vec3d(0, 1, 0));
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[1].object, "tree");
    EXPECT_EQ(Origin(s.instances[1].worldFromInstance), Vec3d(10, 0, 0));
    EXPECT_EQ(s.instances[0].loc.ToString(), "s.pbrt:11:9");
}

TEST(PbrtParser, ObjectErrors) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectBegin \"a\" ObjectBegin \"b\""),
              "s.pbrt:1:28: error: ObjectBegin inside ObjectBegin \"a\" (started at s.pbrt:1:12)");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectInstance \"x\""),
              "s.pbrt:1:12: error: unknown object \"x\"");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectBegin \"a\" ObjectEnd "
                          "ObjectBegin \"b\" ObjectInstance \"a\""),
              "s.pbrt:1:54: error: ObjectInstance inside ObjectBegin \"b\"");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectEnd"),
              "s.pbrt:1:12: error: ObjectEnd without matching ObjectBegin");
    EXPECT_EQ(PbrtErrorOf("WorldBegin ObjectBegin \"a\" AttributeEnd"),
              "s.pbrt:1:28: error: AttributeEnd does not match ObjectBegin at s.pbrt:1:12");
}

TEST(PbrtParser, DirectiveIndexCountsTopLevelShapesInOrder) {
    SceneDescription s = Parse(R"(WorldBegin Shape "a"
        AttributeBegin Shape "b" AttributeEnd
        ObjectBegin "o" Shape "x" Shape "y" ObjectEnd
        Shape "c")");
    ASSERT_EQ(s.shapes.size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.shapes[i].directiveIndex, i);
    EXPECT_EQ(s.shapes[2].type, "c");
    EXPECT_EQ(s.objects[0].shapes[1].directiveIndex, 1);
}

TEST(PbrtParser, UnknownDirectiveLocation) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin\n  Shape \"sphere\"\n\n    Foo 1 2"),
              "s.pbrt:4:5: error: unknown directive \"Foo\"");
}

TEST(PbrtParser, PositionalArgumentErrors) {
    EXPECT_EQ(PbrtErrorOf("Translate 1 2\nWorldBegin"),
              "s.pbrt:1:1: error: Translate expects 3 numbers, got 2");
    EXPECT_EQ(PbrtErrorOf("Translate 1 2 3 4"),
              "s.pbrt:1:1: error: Translate expects 3 numbers, got 4");
    EXPECT_EQ(PbrtErrorOf("Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0]"),
              "s.pbrt:1:1: error: Transform expects 16 numbers, got 15");
    EXPECT_EQ(PbrtErrorOf("WorldBegin Shape \"sphere\" ]"),
              "s.pbrt:1:27: error: unexpected token \"]\"");
    EXPECT_EQ(PbrtErrorOf("WorldBegin Shape 1"),
              "s.pbrt:1:12: error: Shape expects a quoted shape type, got 1");
    EXPECT_EQ(PbrtErrorOf("WorldBegin Shape"),
              "s.pbrt:1:12: error: Shape expects a quoted shape type, got end of file");
    EXPECT_EQ(PbrtErrorOf("LookAt 0 0 0 0 0 0 0 1 0"),
              "s.pbrt:1:1: error: LookAt: LookAt: eye and look point are the same");
    EXPECT_EQ(PbrtErrorOf("Scale 1 0 1"),
              "s.pbrt:1:1: error: Scale: singular transformation matrix");
    EXPECT_EQ(PbrtErrorOf("Rotate 30 0 0 0"), "s.pbrt:1:1: error: Rotate axis must not be zero");
    EXPECT_EQ(PbrtErrorOf("WorldBegin \"float x\" 1"),
              "s.pbrt:1:12: error: unexpected string \"float x\"");
    EXPECT_EQ(PbrtErrorOf("WorldBegin WorldBegin"),
              "s.pbrt:1:12: error: WorldBegin inside the world block");
    EXPECT_EQ(PbrtErrorOf("WorldBegin WorldEnd Shape \"sphere\""),
              "s.pbrt:1:21: error: Shape after WorldEnd");
}

TEST(PbrtParser, WrongParameterTypeError) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin\nShape \"sphere\" \"float radius\" \"one\""),
              "s.pbrt:2:16: error: parameter \"radius\": expected numbers, got strings");
    EXPECT_EQ(PbrtErrorOf("WorldBegin\nShape \"sphere\" \"spline radius\" 1"),
              "s.pbrt:2:16: error: unknown parameter type \"spline\"");
}

TEST(PbrtParser, AllParameterTypesParse) {
    SceneDescription s = Parse(R"(WorldBegin Shape "t"
        "float a" 1 "integer b" [1 2] "bool c" "true" "bool c2" [false] "string d" "x"
        "point e" [1 2 3] "point3 e3" [1 2 3] "point2 f" [1 2] "vector g" [1 2 3]
        "vector3 g3" [1 2 3] "vector2 h" [1 2] "normal i" [0 0 1] "normal3 i3" [0 0 1]
        "rgb j" [1 2 3] "color k" [1 2 3] "xyz l" [1 1 1] "blackbody m" [3000 1]
        "spectrum n" [400 1 700 1] "texture o" "tex")");
    const ParamSet &ps = s.shapes[0].params;
    EXPECT_EQ(ps.Params().size(), 19u);
    const std::pair<const char *, ParamType> expect[] = {
        {"a", ParamType::Float},    {"b", ParamType::Integer}, {"c", ParamType::Bool},
        {"c2", ParamType::Bool},    {"d", ParamType::String},  {"e", ParamType::Point3},
        {"e3", ParamType::Point3},  {"f", ParamType::Point2},  {"g", ParamType::Vector3},
        {"g3", ParamType::Vector3}, {"h", ParamType::Vector2}, {"i", ParamType::Normal},
        {"i3", ParamType::Normal},  {"j", ParamType::RGB},     {"k", ParamType::RGB},
        {"l", ParamType::RGB},      {"m", ParamType::RGB},     {"n", ParamType::RGB},
        {"o", ParamType::Texture}};
    for (const auto &[name, type] : expect) {
        ASSERT_NE(ps.Find(name), nullptr) << name;
        EXPECT_EQ(ps.Find(name)->type, type) << name;
    }
    EXPECT_FALSE(ps.GetBool("c2", true));
    EXPECT_EQ(ps.Find("a")->loc.ToString(), "s.pbrt:2:9");
}

TEST(PbrtParser, UnbalancedScopes) {
    EXPECT_EQ(PbrtErrorOf("WorldBegin AttributeEnd"),
              "s.pbrt:1:12: error: AttributeEnd without matching AttributeBegin");
    EXPECT_EQ(PbrtErrorOf("WorldBegin TransformEnd"),
              "s.pbrt:1:12: error: TransformEnd without matching TransformBegin");
    EXPECT_EQ(PbrtErrorOf("WorldBegin TransformBegin AttributeEnd"),
              "s.pbrt:1:27: error: AttributeEnd does not match TransformBegin at s.pbrt:1:12");
    Diagnostics diag;
    Parse("WorldBegin\nAttributeBegin\nShape \"sphere\"\nWorldEnd", &diag);
    auto w = diag.Warnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].ToString(), "s.pbrt:2:1: warning: AttributeBegin without matching AttributeEnd");
    Diagnostics diag2;
    Parse("WorldBegin\nAttributeBegin\n", &diag2);  // v4 style: no WorldEnd
    EXPECT_EQ(diag2.Count(), 1u);
}

TEST(PbrtParser, UnsupportedFeaturesWarn) {
    Diagnostics diag;
    SceneDescription s = Parse(R"(
        ActiveTransform EndTime Translate 9 9 9 ActiveTransform All
        TransformTimes 0 1
        Camera "perspective"
        WorldBegin
        MakeNamedMedium "fog" "string type" "homogeneous"
        MediumInterface "fog" ""
        Option "bool disablepixeljitter" true
        ColorSpace "aces2065-1"
        Attribute "shape" "float radius" 2
        Shape "sphere")",
                               &diag);
    // Motion blur is supported now (issue 12): the EndTime translate moves only the camera's
    // end-time transform.
    EXPECT_TRUE(s.camera.cameraFromWorld.IsIdentity());
    ASSERT_TRUE(s.camera.motion.has_value());
    EXPECT_EQ(s.camera.motion->end.Point(Vec3d(0, 0, 0)), Vec3d(9, 9, 9));
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_FALSE(s.shapes[0].motion.has_value());  // WorldBegin resets both transforms
    bool media = false, option = false;
    for (const Warning &w : diag.Warnings()) {
        EXPECT_EQ(w.message.find("motion"), std::string::npos) << w.message;
        media |= w.message == "participating media are not supported";
        option |= w.message.find("Option") != std::string::npos;
    }
    // Participating media are supported now (issue 14): no warning.
    EXPECT_FALSE(media);
    // Options are kept for the assembly (assembly/scene_options.h), which reads or warns.
    EXPECT_FALSE(option);
    ASSERT_NE(s.options.Find("disablepixeljitter"), nullptr);
}

// 400,000 numbers in two arrays, each read (the parser's speed is measured by benchmarks, not
// asserted here: the machine is shared).
TEST(PbrtParser, LargeMeshReadsEveryNumber) {
    std::string text = "WorldBegin Shape \"trianglemesh\" \"point P\" [";
    const int n = 200000;
    text.reserve(size_t(n) * 30);
    for (int i = 0; i < n; ++i) text += " 0.125 -1.5e-2 3";
    text += "] \"integer indices\" [";
    for (int i = 0; i < n; ++i) text.append(" ").append(std::to_string(i % 1000));
    text += "]";
    SceneDescription s = Parse(text);
    EXPECT_EQ(s.shapes[0].params.GetPoint3s("P").size(), size_t(n));
    EXPECT_EQ(s.shapes[0].params.GetInts("indices").size(), size_t(n));
    EXPECT_EQ(s.shapes[0].params.GetPoint3s("P")[size_t(n) - 1], Vec3f(0.125f, -1.5e-2f, 3));
    EXPECT_EQ(s.shapes[0].params.GetInts("indices")[size_t(n) - 1], (n - 1) % 1000);
}

TEST(PbrtParser, MutatedInputNeverCrashes) {
    // Byte-level mutations of a scene using most directives: every outcome must be either a
    // parsed scene or a SceneError (no other exception, crash or hang).
    const std::string base = R"(LookAt 0 0 -5 0 0 0 0 1 0 Camera "perspective" "float fov" [45]
        Film "image" "integer xresolution" 8 WorldBegin
        AttributeBegin Translate 1 2 3 Material "matte" "rgb Kd" [.5 .5 .5]
        MakeNamedMaterial "m" "string type" "glass" NamedMaterial "m"
        Texture "t" "spectrum" "checkerboard" "blackbody tex1" [3000 1]
        AreaLightSource "diffuse" "spectrum L" [400 1 700 2] ReverseOrientation
        Shape "trianglemesh" "point P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
        AttributeEnd TransformBegin Rotate 30 0 1 0 CoordinateSystem "c" TransformEnd
        ObjectBegin "o" Shape "sphere" "float radius" 1 ObjectEnd ObjectInstance "o"
        CoordSysTransform "c" LightSource "point" "bool b" "true" WorldEnd)";
    Diagnostics diag;
    ASSERT_NO_THROW(ParsePbrtString(base, "s.pbrt", diag));
    PbrtParseOptions opts;
    opts.confineIncludes = true;
    std::mt19937 rng(12345);
    const char alphabet[] = " \n\"[]#.-+e0123456789AaZz\\";
    int errors = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        std::string text = base;
        int edits = 1 + int(rng() % 4);
        for (int k = 0; k < edits; ++k) {
            size_t pos = rng() % text.size();
            switch (rng() % 3) {
                case 0:
                    text[pos] = alphabet[rng() % (sizeof(alphabet) - 1)];
                    break;
                case 1:
                    text.erase(pos, 1 + rng() % 8);
                    break;
                default:
                    text.insert(pos, 1, alphabet[rng() % (sizeof(alphabet) - 1)]);
                    break;
            }
        }
        try {
            ParsePbrtString(text, "s.pbrt", diag, opts);
        } catch (const SceneError &e) {
            ++errors;
            EXPECT_FALSE(e.Message().empty());
        }
    }
    EXPECT_GT(errors, 100);  // the mutations do reach the error paths
}

TEST(PbrtParser, SharedScenesParse) {
    fs::path shared(PRISM_SHARED_DIR);
    PRISM_REQUIRE_SHARED(shared / "scenes");
    std::vector<fs::path> files;
    for (const auto &e : fs::recursive_directory_iterator(shared / "scenes"))
        if (e.path().extension() == ".pbrt") files.push_back(e.path());
    if (fs::exists(shared / "peers" / "whitted.pbrt"))
        files.push_back(shared / "peers" / "whitted.pbrt");
    ASSERT_FALSE(files.empty());
    for (const fs::path &f : files) {
        Diagnostics diag;
        SCOPED_TRACE(f.string());
        try {
            SceneDescription s = ParsePbrtFile(f.string(), diag);
            // Included geometry fragments have no world block; whole scenes have a camera.
            if (s.camera.specified) {
                EXPECT_FALSE(s.shapes.empty() && s.instances.empty());
            }
        } catch (const SceneError &e) {
            ADD_FAILURE() << e.what();
        }
    }
}

}  // namespace
}  // namespace prism
