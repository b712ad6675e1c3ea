// The pbrt reader's files: Include and Import resolved against the top-level scene's folder,
// include cycles, depth and --confine, missing and non-regular files.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/pbrt_parser.h"
#include "support/errors.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

namespace fs = std::filesystem;

Vec3d Origin(const Transform &t) { return t.Point(Vec3d(0, 0, 0)); }

TEST(PbrtParser, IncludeResolvesAgainstTopLevelDirectory) {
    const fs::path dir = TempDir("include");
    WriteTestFile(dir / "geom/a.pbrt", "Include \"geom/b.pbrt\"\nShape \"a\"\n");
    WriteTestFile(dir / "geom/b.pbrt", "Translate 1 0 0\n\n  Shape \"b\"\n");
    WriteTestFile(dir / "sub/abs.pbrt", "Shape \"abs\"\n");
    std::string top = WriteTestFile(
        dir / "scene.pbrt", "WorldBegin\nInclude \"geom/a.pbrt\"\nImport \"" +
                                (dir / "sub" / "abs.pbrt").string() + "\"\nShape \"top\"\n");
    Diagnostics diag;
    SceneDescription s = ParsePbrtFile(top, diag);
    EXPECT_EQ(s.baseDir, dir.string());
    EXPECT_EQ(s.sourceFile, top);
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].type, "b");
    EXPECT_EQ(s.shapes[0].loc.ToString(), (dir / "geom/b.pbrt").string() + ":3:3");
    EXPECT_EQ(s.shapes[1].type, "a");
    EXPECT_EQ(Origin(s.shapes[1].worldFromObject), Vec3d(1, 0, 0));  // includes share state
    EXPECT_EQ(s.shapes[2].type, "abs");
    EXPECT_EQ(s.shapes[3].type, "top");
    EXPECT_EQ(s.shapes[3].loc.ToString(), top + ":4:1");
    EXPECT_EQ(s.shapes[3].directiveIndex, 3);
}

TEST(PbrtParser, IncludeCycle) {
    const fs::path dir = TempDir("cycle");
    WriteTestFile(dir / "a.pbrt", "WorldBegin\nInclude \"b.pbrt\"\n");
    WriteTestFile(dir / "b.pbrt", "\n Include \"a.pbrt\"\n");
    WriteTestFile(dir / "self.pbrt", "Include \"self.pbrt\"\n");
    std::string a = (dir / "a.pbrt").string(), b = (dir / "b.pbrt").string();
    Diagnostics diag;
    try {
        ParsePbrtFile(a, diag);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Message(), "include cycle: " + a + " -> " + b + " -> " + a);
        EXPECT_EQ(e.Loc().ToString(), b + ":2:2");
    }
    try {
        ParsePbrtFile((dir / "self.pbrt").string(), diag);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find("include cycle: "), std::string::npos);
    }
}

TEST(PbrtParser, IncludeDepthAndConfinement) {
    const fs::path dir = TempDir("depth");
    for (int i = 0; i < 5; ++i) {
        std::string name = std::string("d").append(std::to_string(i)).append(".pbrt");
        std::string next = std::string("d").append(std::to_string(i + 1)).append(".pbrt");
        WriteTestFile(dir / name, std::string("Include \"").append(next).append("\"\n"));
    }
    WriteTestFile(dir / "d5.pbrt", "WorldBegin Shape \"deep\"\n");
    WriteTestFile(dir / "../prism_parser_outside.pbrt", "Shape \"x\"\n");
    Diagnostics diag;
    std::string top = (dir / "d0.pbrt").string();
    EXPECT_EQ(ParsePbrtFile(top, diag).shapes.size(), 1u);
    PbrtParseOptions opts;
    opts.maxIncludeDepth = 3;
    try {
        ParsePbrtFile(top, diag, opts);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Message(), "includes nested deeper than 3 levels");
    }
    std::string esc =
        WriteTestFile(dir / "escape.pbrt", "Include \"../prism_parser_outside.pbrt\"\n");
    EXPECT_NO_THROW(ParsePbrtFile(esc, diag));
    opts = {};
    opts.confineIncludes = true;
    try {
        ParsePbrtFile(esc, diag, opts);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Message(),
                  "included file \"../prism_parser_outside.pbrt\" is outside the scene directory");
    }
}

TEST(PbrtParser, MissingFiles) {
    Diagnostics diag;
    try {
        ParsePbrtFile("/nonexistent/x.pbrt", diag);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/x.pbrt: error: cannot open file "
                  "\"/nonexistent/x.pbrt\": No such file or directory");
    }
    EXPECT_EQ(PbrtErrorOf("Include \"/nonexistent/y.pbrt\""),
              "s.pbrt:1:1: error: cannot open file \"/nonexistent/y.pbrt\": "
              "No such file or directory");
    const fs::path dir = TempDir("missing");
    try {
        ParsePbrtFile(dir.string(), diag);
        FAIL() << "no error";
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find("Is a directory"), std::string::npos);
    }
}

TEST(PbrtParser, RefusesNonRegularFiles) {
    // Reading a device would never end; it must fail promptly instead.
    EXPECT_EQ(PbrtErrorOf("Include \"/dev/zero\""),
              "s.pbrt:1:1: error: cannot open file \"/dev/zero\": not a regular file");
    Diagnostics diag;
    SceneDescription s =
        ParsePbrtString("WorldBegin Shape \"t\" \"spectrum eta\" \"/dev/zero\"", "s.pbrt", diag);
    EXPECT_EQ(s.shapes[0].params.GetRGB("eta", {}), RGB(1.f));
    EXPECT_EQ(diag.Count(), 1u);
}

}  // namespace
}  // namespace prism
