#include "support/errors.h"

#include "core/error.h"

namespace prism::test {

std::string PbrtErrorOf(const std::string &text, const PbrtParseOptions &opts,
                        const std::string &filename) {
    Diagnostics diag;
    return ErrorOf<SceneError>([&] { ParsePbrtString(text, filename, diag, opts); });
}

SceneDescription ParsePbrtText(const std::string &text) {
    Diagnostics diag;
    return ParsePbrtString(text, "s.pbrt", diag);
}

}  // namespace prism::test
