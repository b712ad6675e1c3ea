#include "support/shared.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace prism::test {

bool InCI() {
    const char *ci = std::getenv("CI");
    return ci && std::strcmp(ci, "true") == 0;
}

bool SharedPathPresent(const std::filesystem::path &path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) return true;
    if (InCI()) ADD_FAILURE() << path << " is missing and CI=true: ../shared must be present in CI";
    return false;
}

}  // namespace prism::test
