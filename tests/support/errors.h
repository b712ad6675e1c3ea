// Catching the error a piece of code throws, to compare its message.
#pragma once

#include <string>

#include "scene/pbrt_parser.h"

namespace prism::test {

// What ErrorOf returns when nothing was thrown.
inline constexpr const char *kNoError = "no error";

// The what() of the E that `f()` throws, or kNoError. Exceptions of other types go on up, so
// the test fails with them.
template <class E, class F>
std::string ErrorOf(F &&f) {
    try {
        f();
    } catch (const E &e) {
        return e.what();
    }
    return kNoError;
}

// The error of parsing pbrt text `text` as the file `filename` (kNoError if it parses).
std::string PbrtErrorOf(const std::string &text, const PbrtParseOptions &opts = {},
                        const std::string &filename = "s.pbrt");

// The scene of pbrt text `text` as the file "s.pbrt", its warnings dropped.
SceneDescription ParsePbrtText(const std::string &text);

}  // namespace prism::test
