// The realistic camera's lens (render/lens_system.h): a thick lens's focal length against the
// lensmaker's equation, the double-Gauss design's against its published 50 mm, focusing (an
// in-focus point images to a small spot), and the exit pupil's bounds.
#include "render/lens_system.h"

#include <gtest/gtest.h>

#include <cmath>

#include "assembly/lens_file.h"

namespace prism {
namespace {

// The double-Gauss 50 mm f/2 of scenes/pbrt3-reference/dgauss.50mm.dat.
const char *DoubleGauss =
    "# radius thickness eta aperture\n"
    "29.475 3.76 1.67 25.2\n84.83 0.12 1 25.2\n19.275 4.025 1.67 23\n40.77 3.275 1.699 23\n"
    "12.75 5.705 1 18\n0 4.5 0 17.1\n-14.495 1.18 1.603 17\n40.77 6.065 1.658 20\n"
    "-20.385 0.19 1 20\n437.065 3.22 1.717 20\n-39.73 0 1 20\n";

std::vector<LensInterface> WithStop(std::vector<LensInterface> l, double diameterMm) {
    for (LensInterface &e : l)
        if (e.radius == 0) e.apertureRadius = diameterMm * 0.5e-3;
    return l;
}

// The largest distance from the camera-space point P of the rays the lens makes from film
// point pFilm over a grid of pupil samples (those that pass), and how many passed.
double Spot(const LensSystem &lens, Vec2d pFilm, const Vec3d &P, int *passed) {
    double worst = 0;
    *passed = 0;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            double w;
            const LensRay r = lens.GenerateRay(pFilm, Vec2d((i + 0.5) / 16, (j + 0.5) / 16), &w);
            if (w == 0) continue;
            ++*passed;
            const Vec3d v = P - r.o, d = Normalize(r.d);
            worst = std::max(worst, Length(v - d * Dot(v, d)));
        }
    return worst;
}

// A biconvex lens (R1 = 50, R2 = -50, 5 thick, n = 1.5): the lensmaker's equation gives
// 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) d / (n R1 R2)).
TEST(LensSystem, AThickLensHasTheLensmakersFocalLength) {
    const std::vector<LensInterface> l = ParseLensFile("50 5 1.5 20\n-50 0 1 20\n", "thick.dat");
    const LensSystem lens(l, 10, 0.035, true);
    double f, pRear, pFront;
    lens.CardinalPoints(&f, &pRear, &pFront);
    const double R1 = 50, R2 = -50, d = 5, n = 1.5;
    const double want = 1 / ((n - 1) * (1 / R1 - 1 / R2 + (n - 1) * d / (n * R1 * R2)));
    EXPECT_NEAR(f * 1000, want, 1e-3 * want);
    // Symmetric: the principal planes lie symmetrically about the lens's middle.
    const double middle = lens.RearZ() + 0.0025;
    EXPECT_NEAR(pRear - middle, middle - pFront, 1e-7);
    // Focused at 10 m: the film sits at the thick-lens image distance behind the rear
    // principal plane, 1/si = 1/f - 1/so.
    const double so = 10 - pFront, si = 1 / (1 / f - 1 / so);
    EXPECT_NEAR(pRear, si, 1e-9);
}

TEST(LensSystem, TheDoubleGaussIsA50mmLens) {
    const LensSystem lens(WithStop(ParseLensFile(DoubleGauss, "dgauss.dat"), 17.1), 1e3, 0.035,
                          true);
    double f, pRear, pFront;
    lens.CardinalPoints(&f, &pRear, &pFront);
    EXPECT_NEAR(f * 1000, 50, 1.5);
    // Focused at 1 km the film is about a focal length behind the rear principal plane.
    EXPECT_NEAR(pRear, f, 1e-5);
}

// A point on the plane of focus images to a small spot on the film, on axis and off it (the
// image inverted through the lens); focused elsewhere, the same point spreads far wider.
TEST(LensSystem, AnInFocusPointImagesToASmallSpot) {
    const std::vector<LensInterface> l = WithStop(ParseLensFile(DoubleGauss, "dgauss.dat"), 8);
    const LensSystem sharp(l, 5, 0.035, true), blurred(l, 2, 0.035, true);
    int passed;
    const double onAxis = Spot(sharp, Vec2d(0, 0), Vec3d(0, 0, 5), &passed);
    EXPECT_GT(passed, 128);
    EXPECT_LT(onAxis, 2e-3);  // 2 mm at 5 m: about a pixel of a 35 mm film 1000 pixels wide
    EXPECT_GT(Spot(blurred, Vec2d(0, 0), Vec3d(0, 0, 5), &passed), 10 * onAxis);
    // Off axis: the chief ray through the stop's centre finds the conjugate point.
    const Vec2d pFilm(-4e-3, 3e-3);
    double w;
    const LensRay chief = sharp.GenerateRay(pFilm, Vec2d(0.5, 0.5), &w);
    ASSERT_GT(w, 0);
    const Vec3d d = Normalize(chief.d);
    const Vec3d P = chief.o + d * ((5 - chief.o.z) / d.z);
    EXPECT_GT(P.x, 0);  // inverted
    EXPECT_LT(P.y, 0);
    EXPECT_NEAR(P.x / P.y, -4.0 / 3, 0.01);
    EXPECT_LT(Spot(sharp, pFilm, P, &passed), 5e-3);
    EXPECT_GT(passed, 64);
}

// The exit pupil's bounds hold every rear-plane point through which a ray from the film point
// passes the lens (sampled far more finely than the tables were), and the weight is pbrt-v3's
// cos^4 times the pupil's area over the centre's.
TEST(LensSystem, TheExitPupilBoundsHoldEveryRayThatPasses) {
    const LensSystem lens(WithStop(ParseLensFile(DoubleGauss, "dgauss.dat"), 12), 5, 0.035, true);
    const double rear = 10e-3 * 1.6;  // beyond the rear element's radius
    for (double r : {0.0, 5e-3, 11e-3, 17e-3}) {
        const LensSystem::Box &b = lens.PupilBounds(r);
        const int n = 200;
        int passed = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec3d pRear(-rear + 2 * rear * (i + 0.5) / n,
                                  -rear + 2 * rear * (j + 0.5) / n, lens.RearZ());
                const Vec3d pFilm(r, 0, 0);
                LensRay out;
                if (!lens.TraceFromFilm({pFilm, pRear - pFilm}, &out)) continue;
                ++passed;
                EXPECT_TRUE(pRear.x >= b.x0 && pRear.x <= b.x1 && pRear.y >= b.y0 &&
                            pRear.y <= b.y1)
                    << r << " " << pRear.x << " " << pRear.y;
            }
        if (r < 12e-3) EXPECT_GT(passed, 0) << r;
    }
    double w;
    const LensRay ray = lens.GenerateRay(Vec2d(0, 0), Vec2d(0.5, 0.5), &w);
    EXPECT_NEAR(w, 1, 1e-12);  // straight down the axis, the centre's own pupil
    EXPECT_GT(ray.d.z, 0);
    // Physical weighting: the pupil's area over the rear distance squared, times the shutter
    // time (pbrt-v3's renders halve with a shutter open half as long).
    const std::vector<LensInterface> l = WithStop(ParseLensFile(DoubleGauss, "dgauss.dat"), 12);
    const LensSystem full(l, 5, 0.035, false, 1), half(l, 5, 0.035, false, 0.5);
    double wFull, wHalf;
    full.GenerateRay(Vec2d(3e-3, 0), Vec2d(0.4, 0.6), &wFull);
    half.GenerateRay(Vec2d(3e-3, 0), Vec2d(0.4, 0.6), &wHalf);
    ASSERT_GT(wFull, 0);
    EXPECT_NEAR(wHalf, 0.5 * wFull, 1e-12 * wFull);
    const LensSystem::Box &b = full.PupilBounds(3e-3);
    EXPECT_LT(wFull, b.Area() / (full.RearZ() * full.RearZ()));  // cos^4 < 1 off the axis
}

}  // namespace
}  // namespace prism
