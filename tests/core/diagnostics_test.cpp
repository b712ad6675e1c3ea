// Diagnostics (core/error.h): identical warnings kept once, and of one kind of warning the
// first kMaxPerKind kept and the rest summed up in one line (issue 25: 40,000 unused-parameter
// warnings took 66 s, each new warning compared with every earlier one).
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

}  // namespace
}  // namespace prism
