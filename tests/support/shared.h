// What every test may need to know of its surroundings: the source tree, ../shared, and
// whether it runs under continuous integration.
#pragma once

#include <filesystem>
#include <string>

namespace prism::test {

// The checkout's top folder (scenes/, tests/bad/ and the docs are read from it).
inline const std::string Source = PRISM_SOURCE_DIR_FOR_TESTS;

// True under continuous integration (the environment variable CI is "true", as GitHub Actions,
// GitLab CI, most others and .ci/run set it).
bool InCI();

// Whether `path` (a file or folder of ../shared, the external scenes and references) exists.
// When it does not, a developer's checkout may simply lack ../shared and the caller skips; in
// CI a missing ../shared means the suite would silently test less, so this records a failure.
bool SharedPathPresent(const std::filesystem::path &path);

}  // namespace prism::test

// In a test body: skips the test when `path` under ../shared is missing, and fails it instead in
// CI (CI=true).
#define PRISM_REQUIRE_SHARED(where)               \
    if (!::prism::test::SharedPathPresent(where)) \
    GTEST_SKIP() << std::filesystem::path(where).string() << " not present"
