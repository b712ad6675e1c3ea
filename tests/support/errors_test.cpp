// The error catchers of the test-support library: ErrorOf reports what is thrown, of the type
// asked for, and lets other exceptions through.

#include "support/errors.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "core/error.h"

namespace prism::test {
namespace {

TEST(ErrorOf, ReturnsWhatOfTheCaughtTypeOrNoError) {
    EXPECT_EQ(ErrorOf<SceneError>([] { throw SceneError("bad"); }), "bad");
    EXPECT_EQ(ErrorOf<SceneError>([] {}), kNoError);
    EXPECT_THROW(ErrorOf<SceneError>([] { throw std::logic_error("other"); }), std::logic_error);
    EXPECT_EQ(PbrtErrorOf("WorldBegin WorldBegin"),
              "s.pbrt:1:12: error: WorldBegin inside the world block");
}

}  // namespace
}  // namespace prism::test
