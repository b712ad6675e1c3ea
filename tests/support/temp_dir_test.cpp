// The scratch folders and error catchers of the test-support library: each test gets a folder
// of its own, empty when handed out, and ErrorOf reports what is thrown.

#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "support/errors.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

TEST(TempDir, IsEmptyNamedAfterTheTestAndInsideTheScratchDirectory) {
    fs::path a = TempDir("a");
    WriteTestFile(a / "sub" / "f.txt", "x");
    EXPECT_EQ(ReadFile(a / "sub" / "f.txt"), "x");
    fs::path again = TempDir("a");
    EXPECT_EQ(again, a);
    EXPECT_TRUE(fs::is_empty(again)) << "a second TempDir(\"a\") must start empty";
    EXPECT_NE(TempDir("b"), a);
    EXPECT_NE(a.filename().string().find("TempDir.IsEmptyNamedAfterTheTest"), std::string::npos)
        << a;
    EXPECT_EQ(a.parent_path(), fs::path(::testing::TempDir()).parent_path());
}

TEST(TempDir, ASlashInANameMakesOneFolderNotANest) {
    // A value-parameterised test's name has a '/', and so may a caller's name.
    fs::path d = TempDir("p/q");
    EXPECT_TRUE(fs::is_directory(d));
    EXPECT_EQ(d.parent_path(), fs::path(::testing::TempDir()).parent_path());
}

TEST(ErrorOf, ReturnsWhatOfTheCaughtTypeOrNoError) {
    EXPECT_EQ(ErrorOf<SceneError>([] { throw SceneError("bad"); }), "bad");
    EXPECT_EQ(ErrorOf<SceneError>([] {}), kNoError);
    EXPECT_THROW(ErrorOf<SceneError>([] { throw std::logic_error("other"); }), std::logic_error);
    EXPECT_EQ(PbrtErrorOf("WorldBegin WorldBegin"),
              "s.pbrt:1:12: error: WorldBegin inside the world block");
}

}  // namespace
}  // namespace prism::test
