// Which pbrt version's rules a file is read by (scene/pbrt_version.h).
#include "scene/pbrt_version.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "scene/pbrt_parser.h"
#include "support/temp_dir.h"

namespace prism {
namespace {

PbrtVersionChoice VersionOf(const std::string &text, int forced = 0) {
    Diagnostics diag(false);
    PbrtParseOptions opts;
    opts.pbrtVersion = forced;
    return ParsePbrtString(text, "v.pbrt", diag, opts).pbrtVersion;
}

TEST(PbrtVersion, AFileWithNothingVersionSpecificIsReadAsPbrtV3) {
    const PbrtVersionChoice v = VersionOf("WorldBegin\nShape \"sphere\"\n");
    EXPECT_EQ(v.version, 3);
    EXPECT_FALSE(v.loc.Valid());
    EXPECT_NE(v.why.find("nothing in the file"), std::string::npos) << v.why;
}

TEST(PbrtVersion, TheFirstVersionSpecificConstructDecides) {
    struct Case {
        const char *text;
        int version;
        const char *why;
        int line;
    };
    const Case cases[] = {
        {"Film \"rgb\"\nWorldBegin\n", 4, "Film \"rgb\"", 1},
        {"Film \"image\"\nWorldBegin\n", 3, "Film \"image\"", 1},
        {"WorldBegin\nMaterial \"matte\"\n", 3, "Material \"matte\"", 2},
        {"WorldBegin\nMaterial \"coateddiffuse\"\n", 4, "Material \"coateddiffuse\"", 2},
        {"WorldBegin\nMakeNamedMaterial \"m\" \"string type\" \"conductor\"\n", 4,
         "MakeNamedMaterial \"conductor\"", 2},
        {"Option \"bool disablepixeljitter\" true\nWorldBegin\n", 4, "Option", 1},
        {"Integrator \"whitted\"\nWorldBegin\n", 3, "Integrator \"whitted\"", 1},
        {"Sampler \"zsobol\"\nWorldBegin\n", 4, "Sampler \"zsobol\"", 1},
        {"WorldBegin\nShape \"hyperboloid\"\n", 3, "Shape \"hyperboloid\"", 2},
        {"WorldBegin\nLightSource \"point\" \"float power\" 10\n", 4, "parameter \"power\"", 2},
        {"WorldBegin\nLightSource \"point\" \"blackbody I\" 3000\n", 4, "one value", 2},
        {"WorldBegin\nLightSource \"point\" \"blackbody I\" [3000 1]\n", 3, "two values", 2},
        {"WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"metal-Au-eta\"\n", 4,
         "Material \"conductor\"", 2},
        {"WorldBegin\nMakeNamedMedium \"m\" \"string type\" \"uniformgrid\"\n", 4,
         "MakeNamedMedium \"uniformgrid\"", 2},
        {"WorldBegin\nTexture \"t\" \"float\" \"imagemap\" \"string encoding\" \"linear\" "
         "\"string filename\" \"x.png\"\n",
         4, "parameter \"encoding\"", 2},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.text);
        const PbrtVersionChoice v = VersionOf(c.text);
        EXPECT_EQ(v.version, c.version);
        EXPECT_NE(v.why.find(c.why), std::string::npos) << v.why;
        EXPECT_NE(v.why.find(c.version == 4 ? "(pbrt-v4 only)" : "(pbrt-v3 only)"),
                  std::string::npos)
            << v.why;
        EXPECT_EQ(v.loc.line, c.line);
        EXPECT_TRUE(v.conflict.empty()) << v.conflict;
    }
}

TEST(PbrtVersion, ANamedSpectrumIsPbrtV4Evidence) {
    const PbrtVersionChoice v = VersionOf(
        "WorldBegin\nMaterial \"interface\"\nLightSource \"point\" \"spectrum I\" "
        "\"stdillum-D65\"\n");
    EXPECT_EQ(v.version, 4);
    EXPECT_NE(v.why.find("named spectrum \"stdillum-D65\""), std::string::npos) << v.why;
}

TEST(PbrtVersion, AMixedFileKeepsTheFirstAndNamesTheOther) {
    const PbrtVersionChoice v =
        VersionOf("Film \"rgb\"\nWorldBegin\nMaterial \"plastic\"\nShape \"sphere\"\n");
    EXPECT_EQ(v.version, 4);
    EXPECT_NE(v.conflict.find("Material \"plastic\" (pbrt-v3 only)"), std::string::npos)
        << v.conflict;
    EXPECT_EQ(v.conflictLoc.line, 3);
}

TEST(PbrtVersion, TheFlagWins) {
    const PbrtVersionChoice v = VersionOf("Film \"rgb\"\nWorldBegin\n", 3);
    EXPECT_EQ(v.version, 3);
    EXPECT_EQ(v.why, "--pbrt-version 3");
    EXPECT_EQ(VersionOf("WorldBegin\nMaterial \"matte\"\n", 4).version, 4);
}

TEST(PbrtVersion, ImportIsPbrtV4) {
    const std::filesystem::path dir = test::ScratchDir("pbrt_version");
    test::WriteTestFile(dir / "part.pbrt", "Shape \"sphere\"\n");
    const std::string top =
        test::WriteTestFile(dir / "top.pbrt", "WorldBegin\nImport \"part.pbrt\"\n");
    Diagnostics diag(false);
    const SceneDescription d = ParsePbrtFile(top, diag);
    EXPECT_EQ(d.pbrtVersion.version, 4);
    EXPECT_NE(d.pbrtVersion.why.find("Import"), std::string::npos) << d.pbrtVersion.why;
    EXPECT_EQ(d.shapes.size(), 1u);
}

// pbrt-v4's defaults where the file names no Sampler or Integrator; pbrt-v3's otherwise.
TEST(PbrtVersion, EachVersionHasItsDefaults) {
    Diagnostics diag(false);
    const SceneDescription v4 = ParsePbrtString("Film \"rgb\"\nWorldBegin\n", "a.pbrt", diag);
    EXPECT_EQ(v4.integrator.type, "volpath");
    EXPECT_EQ(v4.sampler.type, "zsobol");
    const SceneDescription v3 = ParsePbrtString("WorldBegin\n", "b.pbrt", diag);
    EXPECT_EQ(v3.integrator.type, "path");
    EXPECT_EQ(v3.sampler.type, "halton");
    const SceneDescription named = ParsePbrtString(
        "Film \"rgb\"\nIntegrator \"path\"\nSampler \"halton\"\nWorldBegin\n", "c.pbrt", diag);
    EXPECT_EQ(named.integrator.type, "path");
    EXPECT_EQ(named.sampler.type, "halton");
}

}  // namespace
}  // namespace prism
