// The split between syntax and graphics state: the parser drives any PbrtTarget (here one
// that records the calls) and SceneBuilder turns the same calls into a SceneDescription.
#include "scene/scene_builder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/load_scene.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

// Records "Directive:argument@line" for the directives the test uses.
class RecordingTarget : public PbrtTarget {
  public:
    std::vector<std::string> calls;
    void Add(const std::string &s, const FileLoc &loc) {
        calls.push_back(s + "@" + fs::path(loc.file).filename().string() + ":" +
                        std::to_string(loc.line));
    }
    void AttributeBegin(const FileLoc &loc) override { Add("AttributeBegin", loc); }
    void AttributeEnd(const FileLoc &loc) override { Add("AttributeEnd", loc); }
    void TransformBegin(const FileLoc &loc) override { Add("TransformBegin", loc); }
    void TransformEnd(const FileLoc &loc) override { Add("TransformEnd", loc); }
    void Translate(double dx, double, double, const FileLoc &loc) override {
        Add("Translate:" + std::to_string(int(dx)), loc);
    }
    void Scale(double, double, double, const FileLoc &loc) override { Add("Scale", loc); }
    void Rotate(double, double, double, double, const FileLoc &loc) override { Add("Rotate", loc); }
    void LookAt(double, double, double, double, double, double, double, double, double,
                const FileLoc &loc) override {
        Add("LookAt", loc);
    }
    void Transform(const double m[16], const FileLoc &loc) override {
        Add("Transform:" + std::to_string(int(m[15])), loc);
    }
    void ConcatTransform(const double[16], const FileLoc &loc) override {
        Add("ConcatTransform", loc);
    }
    void Identity(const FileLoc &loc) override { Add("Identity", loc); }
    void CoordinateSystem(const std::string &n, const FileLoc &loc) override {
        Add("CoordinateSystem:" + n, loc);
    }
    void CoordSysTransform(const std::string &n, const FileLoc &loc) override {
        Add("CoordSysTransform:" + n, loc);
    }
    void ActiveTransform(ActiveTransformKind k, const FileLoc &loc) override {
        Add("ActiveTransform:" + std::to_string(int(k)), loc);
    }
    void TransformTimes(double, double, const FileLoc &loc) override { Add("TransformTimes", loc); }
    void ReverseOrientation(const FileLoc &loc) override { Add("ReverseOrientation", loc); }
    void Camera(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Camera:" + t, loc);
    }
    void Film(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Film:" + t, loc);
    }
    void Sampler(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Sampler:" + t, loc);
    }
    void PixelFilter(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("PixelFilter:" + t, loc);
    }
    void Integrator(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Integrator:" + t, loc);
    }
    void Accelerator(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Accelerator:" + t, loc);
    }
    void Option(ParsedParameterVector, const FileLoc &loc) override { Add("Option", loc); }
    void ColorSpace(const std::string &n, const FileLoc &loc) override {
        Add("ColorSpace:" + n, loc);
    }
    void WorldBegin(const FileLoc &loc) override { Add("WorldBegin", loc); }
    void WorldEnd(const FileLoc &loc) override { Add("WorldEnd", loc); }
    void Material(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Material:" + t, loc);
    }
    void MakeNamedMaterial(const std::string &n, ParsedParameterVector,
                           const FileLoc &loc) override {
        Add("MakeNamedMaterial:" + n, loc);
    }
    void NamedMaterial(const std::string &n, const FileLoc &loc) override {
        Add("NamedMaterial:" + n, loc);
    }
    void Texture(const std::string &n, const std::string &k, const std::string &t,
                 ParsedParameterVector, const FileLoc &loc) override {
        Add("Texture:" + n + "," + k + "," + t, loc);
    }
    void LightSource(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("LightSource:" + t, loc);
    }
    void AreaLightSource(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("AreaLightSource:" + t, loc);
    }
    void Shape(const std::string &t, ParsedParameterVector params, const FileLoc &loc) override {
        std::string s = "Shape:" + t;
        for (const ParsedParameter &p : params)
            s += "," + p.type + " " + p.name + "=" + std::to_string(p.numbers.size()) + "n" +
                 std::to_string(p.strings.size()) + "s";
        Add(s, loc);
    }
    void ObjectBegin(const std::string &n, const FileLoc &loc) override {
        Add("ObjectBegin:" + n, loc);
    }
    void ObjectEnd(const FileLoc &loc) override { Add("ObjectEnd", loc); }
    void ObjectInstance(const std::string &n, const FileLoc &loc) override {
        Add("ObjectInstance:" + n, loc);
    }
    void MakeNamedMedium(const std::string &n, ParsedParameterVector, const FileLoc &loc) override {
        Add("MakeNamedMedium:" + n, loc);
    }
    void MediumInterface(const std::string &in, const std::string &out,
                         const FileLoc &loc) override {
        Add("MediumInterface:" + in + "," + out, loc);
    }
    void Attribute(const std::string &t, ParsedParameterVector, const FileLoc &loc) override {
        Add("Attribute:" + t, loc);
    }
    void EndOfFiles() override { calls.push_back("EndOfFiles"); }
};

TEST(PbrtParser, SendsDirectivesToTheTargetWithoutInterpretingThem) {
    fs::path dir = fs::path(::testing::TempDir()) / "scene_builder_test";
    fs::create_directories(dir);
    std::ofstream(dir / "inc.pbrt") << "Translate 7 0 0\n";
    RecordingTarget t;
    // No WorldBegin, an unknown parameter type, an unknown named material, a ReverseOrientation
    // outside any scope: none of that is the parser's business.
    ParsePbrt(
        "Texture \"t\" \"float\" \"checkerboard\"\n"
        "Include \"inc.pbrt\"\n"
        "Shape \"sphere\" \"quaternion q\" [1 2 3 4] \"string s\" \"x\"\n"
        "NamedMaterial \"nope\"\n"
        "ActiveTransform EndTime\n"
        "MediumInterface \"a\"\n"
        "Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 5]\n",
        (dir / "main.pbrt").string(), t);
    std::vector<std::string> want = {
        "Texture:t,float,checkerboard@main.pbrt:1",
        "Translate:7@inc.pbrt:1",
        "Shape:sphere,quaternion q=4n0s,string s=0n1s@main.pbrt:3",
        "NamedMaterial:nope@main.pbrt:4",
        "ActiveTransform:1@main.pbrt:5",
        // One name is both media, as pbrt-v3's parser reads it (issue 14; it was "a,").
        "MediumInterface:a,a@main.pbrt:6",
        "Transform:5@main.pbrt:7",
        "EndOfFiles",
    };
    EXPECT_EQ(t.calls, want);
}

TEST(SceneBuilder, BuildsTheDescriptionFromTargetCalls) {
    Diagnostics diag;
    SceneBuilder b("dir/x.pbrt", diag);
    FileLoc loc{"dir/x.pbrt", 1, 1};
    b.WorldBegin(loc);
    b.AttributeBegin(loc);
    b.Translate(1, 2, 3, loc);
    b.ReverseOrientation(loc);
    ParsedParameter radius{"float", "radius", loc, {2.5}, {}};
    b.Shape("sphere", {radius}, loc);
    b.AttributeEnd(loc);
    b.Shape("sphere", {}, loc);
    b.EndOfFiles();
    SceneDescription d = b.Result();
    EXPECT_EQ(d.baseDir, "dir");
    EXPECT_EQ(d.format, "pbrt");
    ASSERT_EQ(d.shapes.size(), 2u);
    EXPECT_TRUE(d.shapes[0].reverseOrientation);
    EXPECT_FALSE(d.shapes[1].reverseOrientation);
    EXPECT_EQ(d.shapes[0].params.GetFloat("radius", 1), 2.5f);
    EXPECT_EQ(d.shapes[0].worldFromObject.Point(Vec3d(0, 0, 0)).z, 3.0);
    EXPECT_EQ(d.shapes[1].worldFromObject.Point(Vec3d(0, 0, 0)).z, 0.0);
    EXPECT_EQ(d.shapes[1].directiveIndex, 1);
}

TEST(SceneBuilder, GraphicsStateErrorsAreLocated) {
    Diagnostics diag;
    SceneBuilder b("x.pbrt", diag);
    EXPECT_THROW(b.AttributeEnd(FileLoc{"x.pbrt", 4, 2}), SceneError);
    try {
        b.NamedMaterial("nope", FileLoc{"x.pbrt", 5, 1});
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_STREQ(e.what(), "x.pbrt:5:1: error: unknown named material \"nope\"");
    }
}

TEST(LoadScene, OneListOfSceneExtensions) {
    for (const char *e :
         {".pbrt", ".obj", ".gltf", ".glb", ".ply", ".PLY", ".Pbrt", ".stl", ".STL"})
        EXPECT_TRUE(IsSceneExtension(e)) << e;
    for (const char *e : {"", ".xyz", ".png", ".pbr", ".pbrtx", "pbrt"})
        EXPECT_FALSE(IsSceneExtension(e)) << e;
    EXPECT_EQ(SceneExtensionList(), ".pbrt, .obj, .gltf, .glb, .ply or .stl");
}

TEST(ParamSet, MarkAllUsed) {
    ParamSet ps;
    Param a, b;
    a.name = "a";
    b.name = "b";
    ps.Add(a);
    ps.Add(b);
    ps.MarkAllUsed();
    Diagnostics diag;
    ps.ReportUnused(diag, "test");
    EXPECT_EQ(diag.Count(), 0u);
}

TEST(SceneDescription, FindObjectReturnsTheLastDefinition) {
    SceneDescription d;
    d.objects.push_back(ObjectDesc{"a", {}, {}});
    d.objects.push_back(ObjectDesc{"b", {}, {}});
    d.objects.push_back(ObjectDesc{"a", {}, {}});
    EXPECT_EQ(FindObject(d, "a"), &d.objects[2]);
    EXPECT_EQ(FindObject(d, "b"), &d.objects[1]);
    EXPECT_EQ(FindObject(d, "c"), nullptr);
}

}  // namespace
}  // namespace prism
