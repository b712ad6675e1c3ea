// Helpers shared by the test binaries (tests/ is on every test binary's include path).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace prism::test {

// True under continuous integration (the environment variable CI is "true", as GitHub Actions,
// GitLab CI and most others set it).
inline bool InCI() {
    const char *ci = std::getenv("CI");
    return ci && std::strcmp(ci, "true") == 0;
}

// Whether `path` (a file or folder of ../shared, the external scenes and references) exists.
// When it does not, a developer's checkout may simply lack ../shared and the caller skips; in
// CI a missing ../shared means the suite would silently test less, so this records a failure.
inline bool SharedPathPresent(const std::filesystem::path &path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) return true;
    if (InCI()) ADD_FAILURE() << path << " is missing and CI=true: ../shared must be present in CI";
    return false;
}

// A folder `name` under the test scratch directory (::testing::TempDir()), created if needed.
inline std::filesystem::path ScratchDir(const std::string &name) {
    std::filesystem::path d = std::filesystem::path(::testing::TempDir()) / name;
    std::filesystem::create_directories(d);
    return d;
}

// Writes `contents` (bytes as given) to `path` and returns the path as a string.
inline std::string WriteTestFile(const std::filesystem::path &path, const std::string &contents) {
    std::ofstream(path, std::ios::binary) << contents;
    return path.string();
}

// A fixture with a fresh, empty directory per test (under the test scratch directory, named
// after the suite, the test and the process), removed afterwards.
class FreshDirTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::path(::testing::TempDir()) /
               (std::string(info->test_suite_name()) + "_" + std::to_string(::getpid()) + "_" +
                info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string Path(const std::string &name) const { return (dir_ / name).string(); }
    std::set<std::string> ListDir() const {
        std::set<std::string> names;
        for (const auto &e : std::filesystem::directory_iterator(dir_))
            names.insert(e.path().filename());
        return names;
    }

    std::filesystem::path dir_;
};

}  // namespace prism::test

// In a test body: skips the test when `path` under ../shared is missing, and fails it instead in
// CI (CI=true).
#define PRISM_REQUIRE_SHARED(where)               \
    if (!::prism::test::SharedPathPresent(where)) \
    GTEST_SKIP() << std::filesystem::path(where).string() << " not present"
