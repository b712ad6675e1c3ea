// Scratch files of the tests. Every folder lies under the build tree's test scratch directory
// (::testing::TempDir(), TEST_TMPDIR), so the Release and sanitizer suites, or two checkouts,
// never share temporary files; ctest runs each test in a process of its own, in parallel.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>

namespace prism::test {

// A folder `name` under the scratch directory, created if needed and kept as it is (a folder
// per test file, shared by its tests).
std::filesystem::path ScratchDir(const std::string &name);

// An empty folder of the running test (named after its suite, its name and `name`; emptied
// first if it exists). Tests that need several call it with different names.
std::filesystem::path TempDir(const std::string &name);

// Writes `contents` (bytes as given) to `path`, creating its parent folders, and returns the
// path as a string. The file appears whole: it is written beside `path` under a name of this
// process and renamed over it, so another test process reading a shared scratch file (ctest
// runs the tests of one file in parallel, each rewriting it) never sees it cut short.
std::string WriteTestFile(const std::filesystem::path &path, const std::string &contents);

// WriteTestFile of `name` directly in the scratch directory (a name unique to the test file).
std::string WriteScratchFile(const std::string &name, const std::string &contents);

// The bytes of the file at `path` ("" if it cannot be read).
std::string ReadFile(const std::filesystem::path &path);

// The scratch folder `name` of one test file, named once at file scope
// (`const ScratchFiles kFiles("prism_limits");`) and created when first used.
class ScratchFiles {
  public:
    explicit ScratchFiles(std::string name) : name_(std::move(name)) {}
    std::filesystem::path Dir() const { return ScratchDir(name_); }
    // The path of `rel` in the folder, as a string.
    std::string Path(const std::string &rel) const { return (Dir() / rel).string(); }
    // WriteTestFile of `rel` in the folder.
    std::string Write(const std::string &rel, const std::string &contents) const {
        return WriteTestFile(Dir() / rel, contents);
    }

  private:
    std::string name_;
};

// A fixture with a fresh, empty directory per test (TempDir("")), removed afterwards.
class FreshDirTest : public ::testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;

    std::string Path(const std::string &name) const { return (dir_ / name).string(); }
    std::set<std::string> ListDir() const;

    std::filesystem::path dir_;
};

}  // namespace prism::test
