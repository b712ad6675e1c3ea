// Diagnostics (core/error.h): identical warnings kept once, and of one kind of warning the
// first kMaxPerKind kept and the rest summed up in one line (issue 25: 40,000 unused-parameter
// warnings took 66 s, each new warning compared with every earlier one); and the escaping of
// control characters in messages.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace prism {
namespace {

TEST(Diagnostics, WarningsOfOneKindAreCappedWithOneSummaryLine) {
    Diagnostics diag;
    for (int i = 0; i < 40000; ++i)
        diag.Warn(FileLoc{"s.pbrt", 6 + i, 16},
                  "unused parameter \"bogus" + std::to_string(i) + "\" (shape \"sphere\")");
    // Another kind has its own cap; an identical warning is kept once.
    for (int i = 0; i < 3; ++i) diag.Warn(FileLoc{"s.pbrt", 1, 1}, "Attribute is not supported");
    std::vector<Warning> w = diag.Warnings();
    ASSERT_EQ(w.size(), size_t(Diagnostics::kMaxPerKind) + 2);
    EXPECT_EQ(w[0].ToString(),
              "s.pbrt:6:16: warning: unused parameter \"bogus0\" (shape \"sphere\")");
    EXPECT_EQ(w[9].message, "unused parameter \"bogus9\" (shape \"sphere\")");
    EXPECT_EQ(w[10].message, "Attribute is not supported");
    EXPECT_EQ(w[11].ToString(),
              "warning: and 39,990 more warnings like: unused parameter \"bogus10\" (shape "
              "\"sphere\")");
    EXPECT_EQ(diag.Count(), w.size());
    EXPECT_EQ(diag.Suppressed(), 39990u);
}

TEST(Diagnostics, NumbersAndQuotedNamesDoNotMakeANewKind) {
    Diagnostics diag;
    for (int i = 0; i < 20; ++i)
        diag.Warn("accessor " + std::to_string(i) + " of mesh \"m" + std::to_string(i) +
                  "\" has no min/max");
    for (int i = 0; i < 20; ++i) diag.Warn("texture \"t" + std::to_string(i) + "\" redefined");
    std::vector<Warning> w = diag.Warnings();
    ASSERT_EQ(w.size(), 2u * Diagnostics::kMaxPerKind + 2);
    EXPECT_EQ(w[20].message,
              "and 10 more warnings like: accessor 10 of mesh \"m10\" has no min/max");
    EXPECT_EQ(w[21].message, "and 10 more warnings like: texture \"t10\" redefined");
}

TEST(Diagnostics, ControlCharactersInNamesAndMessagesAreEscaped) {
    using namespace std::string_literals;
    EXPECT_EQ(Quote("a\0b.pbrt"s), "\"a\\x00b.pbrt\"");
    EXPECT_EQ(Quote("x\x1b[2J\n\x7f"), "\"x\\x1b[2J\\x0a\\x7f\"");
    EXPECT_EQ(EscapeControlChars(EscapeControlChars("a\tb")), "a\\x09b");  // once is enough
    EXPECT_EQ(EscapeControlChars("caf\xc3\xa9 \\ \"q\""), "caf\xc3\xa9 \\ \"q\"");  // kept
    // what() is a C string: a NUL must not end the message there.
    SceneError e(FileLoc{"s.pbrt", 3, 9}, "cannot open file \"a"s + '\0' + "b\": gone");
    EXPECT_STREQ(e.what(), "s.pbrt:3:9: error: cannot open file \"a\\x00b\": gone");
    Warning w{FileLoc{"s.pbrt", 1, 1}, "shape \"sph\x1b[31mere\""};
    EXPECT_EQ(w.ToString(), "s.pbrt:1:1: warning: shape \"sph\\x1b[31mere\"");
}

}  // namespace
}  // namespace prism
