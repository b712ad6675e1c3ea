// The scratch folders of the test-support library: each test gets a folder of its own, empty
// when handed out.

#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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

}  // namespace
}  // namespace prism::test
