// The ../shared helper of tests/support/shared.h: a skip on a developer's machine, a failure in CI.

#include "support/shared.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <optional>
#include <string>

#include "support/temp_dir.h"

namespace prism::test {
namespace {

// Sets CI for one scope and restores the previous value.
class ScopedCI {
  public:
    explicit ScopedCI(const char *value) {
        if (const char *old = std::getenv("CI")) old_ = old;
        if (value)
            setenv("CI", value, 1);
        else
            unsetenv("CI");
    }
    ~ScopedCI() {
        if (old_)
            setenv("CI", old_->c_str(), 1);
        else
            unsetenv("CI");
    }

  private:
    std::optional<std::string> old_;
};

const char *Missing = "/nonexistent/prism-shared-for-test";

TEST(SharedDir, MissingIsAFailureInCI) {
    ScopedCI ci("true");
    EXPECT_TRUE(InCI());
    EXPECT_NONFATAL_FAILURE(EXPECT_FALSE(SharedPathPresent(Missing)), "CI=true");
}

TEST(SharedDir, MissingIsOnlyASkipOutsideCI) {
    for (const char *value : {static_cast<const char *>(nullptr), "false", ""}) {
        ScopedCI ci(value);
        EXPECT_FALSE(InCI());
        EXPECT_FALSE(SharedPathPresent(Missing));  // no failure recorded: the caller skips
    }
}

TEST(SharedDir, PresentPathPassesEverywhere) {
    for (const char *value : {static_cast<const char *>(nullptr), "true"}) {
        ScopedCI ci(value);
        EXPECT_TRUE(SharedPathPresent(PRISM_TEST_DATA_DIR));
    }
}

}  // namespace
}  // namespace prism::test
