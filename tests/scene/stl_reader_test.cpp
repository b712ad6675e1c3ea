// STL reader: ASCII and binary, welding, solids, and hostile files (located errors, budget).
#include "scene/stl_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/memory.h"
#include "scene/load_scene.h"
#include "support/errors.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

using namespace test;

// A binary STL of `triangles` (9 floats each), with the header text `header`.
std::string BinaryStl(const std::vector<std::array<float, 9>> &triangles,
                      const std::string &header = "binary test") {
    std::string s(80, ' ');
    s.replace(0, std::min<size_t>(header.size(), 80), header.substr(0, 80));
    const uint32_t n = uint32_t(triangles.size());
    s.append(reinterpret_cast<const char *>(&n), 4);
    for (const auto &t : triangles) {
        const float normal[3] = {0, 0, 1};
        s.append(reinterpret_cast<const char *>(normal), 12);
        s.append(reinterpret_cast<const char *>(t.data()), 36);
        s.append(2, '\0');  // attribute byte count
    }
    return s;
}

const char *kTetrahedron =
    "solid tet\n"
    "  facet normal 0 0 -1\n    outer loop\n      vertex 0 0 0\n      vertex 0 1 0\n"
    "      vertex 1 0 0\n    endloop\n  endfacet\n"
    "  facet normal 0 -1 0\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
    "      vertex 0 0 1\n    endloop\n  endfacet\n"
    "  facet normal -1 0 0\n    outer loop\n      vertex 0 0 0\n      vertex 0 0 1\n"
    "      vertex 0 1 0\n    endloop\n  endfacet\n"
    "  facet normal 0.577 0.577 0.577\n    outer loop\n      vertex 1 0 0\n      vertex 0 1 0\n"
    "      vertex 0 0 1\n    endloop\n  endfacet\n"
    "endsolid tet\n";

std::string StlError(const std::string &name, const std::string &contents,
                     MemoryBudget *budget = nullptr) {
    const std::string path = WriteScratchFile("stl_" + name, contents);
    Diagnostics diag;
    return ErrorOf<SceneError>([&] { ReadStlFile(path, diag, budget); });
}

TEST(StlReader, AsciiTetrahedronIsWeldedIntoFourVertices) {
    const std::string path = WriteScratchFile("stl_tet.stl", kTetrahedron);
    Diagnostics diag;
    SceneDescription d = ReadStlFile(path, diag);
    EXPECT_EQ(d.format, "stl");
    EXPECT_EQ(d.integrator.type, "distribution") << "as OBJ, glTF and PLY";
    ASSERT_EQ(d.shapes.size(), 1u);
    const ShapeDesc &s = d.shapes[0];
    EXPECT_EQ(s.type, "trianglemesh");
    EXPECT_EQ(s.name, "tet");
    EXPECT_EQ(s.params.GetPoint3s("P").size(), 4u);
    const std::vector<int> idx = s.params.GetInts("indices");
    ASSERT_EQ(idx.size(), 12u);
    EXPECT_EQ((std::vector<int>(idx.begin(), idx.begin() + 3)), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(s.params.Find("N"), nullptr) << "facet normals are not read";
    EXPECT_EQ(s.loc.line, 1);
}

TEST(StlReader, BinaryMatchesAscii) {
    // The same tetrahedron, with -0 for one zero: it welds with +0.
    const std::string bin = BinaryStl({{0, 0, 0, 0, 1, 0, 1, 0, 0},
                                       {-0.f, 0, 0, 1, 0, 0, 0, 0, 1},
                                       {0, 0, 0, 0, 0, 1, 0, 1, 0},
                                       {1, 0, 0, 0, 1, 0, 0, 0, 1}});
    const std::string path = WriteScratchFile("stl_tet_bin.stl", bin);
    Diagnostics diag;
    SceneDescription d = ReadStlFile(path, diag);
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].name, "stl_tet_bin");
    EXPECT_EQ(d.shapes[0].params.GetPoint3s("P").size(), 4u);
    const std::string asciiPath = WriteScratchFile("stl_tet_ascii.stl", kTetrahedron);
    SceneDescription a = ReadStlFile(asciiPath, diag);
    EXPECT_EQ(d.shapes[0].params.GetInts("indices"), a.shapes[0].params.GetInts("indices"));
    EXPECT_EQ(d.shapes[0].params.GetPoint3s("P"), a.shapes[0].params.GetPoint3s("P"));
}

TEST(StlReader, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
    // Many exporters write "solid" into the binary header; the exact size decides.
    const std::string path =
        WriteScratchFile("stl_solid_header.stl",
                         BinaryStl({{0, 0, 0, 1, 0, 0, 0, 1, 0}}, "solid exported by a CAD tool"));
    Diagnostics diag;
    SceneDescription d = ReadStlFile(path, diag);
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].params.GetInts("indices").size(), 3u);
}

TEST(StlReader, SolidsBecomeShapesAndPolygonsAreFanned) {
    const std::string text =
        "solid a\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 1 1 0 "
        "vertex 0 1 0 endloop endfacet\nendsolid a\n"
        "solid\nfacet normal 0 0 0 outer loop vertex 0 0 1 vertex 1 0 1 vertex 0 1 1 endloop "
        "endfacet\nendsolid\n";
    const std::string path = WriteScratchFile("stl_two.stl", text);
    Diagnostics diag;
    SceneDescription d = ReadStlFile(path, diag);
    ASSERT_EQ(d.shapes.size(), 2u);
    EXPECT_EQ(d.shapes[0].name, "a");
    EXPECT_EQ(d.shapes[0].params.GetInts("indices"), (std::vector<int>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(d.shapes[1].name, "stl_two") << "an unnamed solid is named by the file";
    EXPECT_EQ(d.shapes[1].loc.line, 4);
}

TEST(StlReader, AsciiErrorsAreLocated) {
    EXPECT_NE(StlError("kw.stl", "solid x\nfacet normal 0 0 1\n  outer lop\n")
                  .find("stl_kw.stl:3:9: error: expected \"loop\", found \"lop\""),
              std::string::npos)
        << "the column of the word";
    EXPECT_NE(StlError("num.stl", "solid x\nfacet normal 0 0 1 outer loop vertex 0 0 zero\n")
                  .find("stl_num.stl:2:42: error: expected a number, found \"zero\""),
              std::string::npos);
    EXPECT_NE(StlError("eof.stl", "solid x\nfacet normal 0 0 1 outer loop vertex 0 0 0\n")
                  .find(":3:1: error: unexpected end of file: expected \"vertex\" or \"endloop\""),
              std::string::npos);
    EXPECT_NE(StlError("two.stl",
                       "solid x\nfacet normal 0 0 1 outer loop vertex 0 0 0 "
                       "vertex 1 0 0 endloop endfacet endsolid\n")
                  .find(":2:57: error: a facet needs at least 3 vertices, found 2"),
              std::string::npos);
    EXPECT_NE(StlError("nan.stl", "solid x\nfacet normal 0 0 1 outer loop vertex nan 0 0\n")
                  .find(":2:38: error: a vertex coordinate is nan"),
              std::string::npos);
    EXPECT_NE(StlError("big.stl", "solid x\nfacet normal 0 0 1 outer loop vertex 1e39 0 0\n")
                  .find(":2:38: error: a vertex coordinate is inf"),
              std::string::npos)
        << "beyond float range";
    EXPECT_NE(StlError("junk.stl", "solid x\nendsolid x\nsolid y\nendsolid\ngarbage\n")
                  .find(":5:1: error: expected \"solid\", found \"garbage\""),
              std::string::npos);
}

TEST(StlReader, BinaryErrors) {
    std::string bin = BinaryStl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 0, 1}});
    EXPECT_NE(StlError("short.stl", bin.substr(0, bin.size() - 1))
                  .find("binary STL claims 2 triangles, which need 184 bytes; the file has 183"),
              std::string::npos);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(StlError("nanbin.stl",
                       BinaryStl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, nan, 0, 0, 0, 1}}))
                  .find("triangle 1 (byte 162): a vertex coordinate is nan"),
              std::string::npos);
    EXPECT_NE(StlError("tiny.stl", "abc").find("not an STL file: 3 bytes"), std::string::npos);
    EXPECT_NE(StlError("empty.stl", "").find("not an STL file: 0 bytes"), std::string::npos);
}

TEST(StlReader, HostileCountsAndPolygonsStayWithinTheBudget) {
    // A fanned polygon of 100k vertices is 99,998 triangles from 1.3 MB of text: the welder's
    // growth is checked, not the text's size.
    std::string text = "solid x\nfacet normal 0 0 1 outer loop\n";
    for (int i = 0; i < 100000; ++i) text += "vertex " + std::to_string(i) + " 0 0\n";
    text += "endloop endfacet endsolid\n";
    MemoryBudget budget(4 << 20);
    EXPECT_NE(StlError("fan.stl", text, &budget).find("STL welding buffers"), std::string::npos);
}

TEST(StlReader, LoadSceneFramesAndLightsAnStl) {
    const std::string path = WriteScratchFile("stl_scene.stl", kTetrahedron);
    Diagnostics diag;
    LoadOptions opts;
    SceneDescription d = LoadScene(path, diag, opts);
    EXPECT_TRUE(d.camera.specified) << "framed by the default camera";
    ASSERT_FALSE(d.shapes.empty());
    EXPECT_EQ(d.shapes[0].type, "trianglemesh");
}

}  // namespace
}  // namespace prism
