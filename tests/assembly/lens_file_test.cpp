// pbrt-v3 lens description files (assembly/lens_file.h): rows in millimetres become interfaces
// in metres, and every malformed row is an error at its line and column.
#include "assembly/lens_file.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace prism {
namespace {

TEST(LensFile, RowsBecomeInterfacesInMetres) {
    const std::vector<LensInterface> l = ParseLensFile(
        "# a comment\n\n  29.475\t3.76 1.67 25.2  # trailing\n0 4.5 0 17.1\n-39.73 0 1 20",
        "a.dat");
    ASSERT_EQ(l.size(), 3u);
    EXPECT_DOUBLE_EQ(l[0].radius, 29.475e-3);
    EXPECT_DOUBLE_EQ(l[0].thickness, 3.76e-3);
    EXPECT_DOUBLE_EQ(l[0].eta, 1.67);
    EXPECT_DOUBLE_EQ(l[0].apertureRadius, 12.6e-3);
    EXPECT_EQ(l[1].radius, 0);  // the stop
    EXPECT_EQ(l[1].eta, 0);
    EXPECT_DOUBLE_EQ(l[2].radius, -39.73e-3);
}

TEST(LensFile, MalformedRowsAreErrorsAtTheirLineAndColumn) {
    struct Case {
        const char *text;
        int line, column;
        const char *fragment;
    } cases[] = {
        {"10 2 1.5 4\n5 6 x 8\n", 2, 5, "expected a number"},
        {"1 2 1.5\n", 1, 8, "expected four numbers"},
        {"10 2 1.5 4 5\n", 1, 12, "more than four numbers"},
        {"10 -2 1.5 4\n", 1, 1, "negative thickness"},
        {"10 2 0.5 4\n", 1, 1, "index of refraction"},
        {"10 2 1.5 0\n", 1, 1, "aperture diameter must be positive"},
        {"1 2 1.5 4\n", 1, 1, "smaller than the aperture"},
        {"10 2 1.5 1e9\n", 1, 10, "out of range"},
        {"10 2 nan 4\n", 1, 6, "out of range"},
        {"# only a comment\n", 0, 0, "no interfaces"},
    };
    for (const Case &c : cases) {
        try {
            ParseLensFile(c.text, "bad.dat");
            ADD_FAILURE() << "no error for " << c.text;
        } catch (const SceneError &e) {
            EXPECT_EQ(e.Loc().file, "bad.dat");
            EXPECT_EQ(e.Loc().line, c.line) << c.text;
            EXPECT_EQ(e.Loc().column, c.column) << c.text;
            EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
        }
    }
    std::string many;
    for (int i = 0; i <= MaxLensInterfaces; ++i) many += "10 1 1.5 4\n";
    EXPECT_THROW(ParseLensFile(many, "many.dat"), SceneError);
}

}  // namespace
}  // namespace prism
