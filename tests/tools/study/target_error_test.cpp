// `prism render --target-error` (tools/study/target_error.h): the fits, the spp they choose, and an
// end-to-end pilot, render and verification of a small scene.
#include "tools/study/target_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "scene/load_scene.h"
#include "support/shared.h"

namespace prism {
namespace {

using namespace test;

TEST(TargetError, PowerLawFitRecoversAAndB) {
    std::vector<double> x, y;
    for (int n : {1, 2, 3, 4, 6, 8, 12, 16}) {
        x.push_back(n);
        y.push_back(0.3 * std::pow(n, -0.75));
    }
    PowerLaw p = FitPowerLaw(x, y);
    EXPECT_NEAR(p.a, 0.3, 1e-9);
    EXPECT_NEAR(p.b, 0.75, 1e-9);
    EXPECT_NEAR(p(64), 0.3 * std::pow(64, -0.75), 1e-12);
    EXPECT_THROW(FitPowerLaw({2, 2}, {1, 1}), std::invalid_argument);
}

TEST(TargetError, ErrorCurveFitRecoversNoiseAndFloor) {
    std::vector<int> spp{1, 2, 3, 4, 6, 8, 12, 16};
    for (double floor : {0.0, 0.02}) {
        std::vector<double> err2;
        for (int n : spp) err2.push_back(floor * floor + std::pow(0.2 * std::pow(n, -0.6), 2));
        ErrorCurve c = FitErrorCurve(spp, err2);
        EXPECT_NEAR(std::sqrt(c.floor2), floor, 2e-4) << floor;
        EXPECT_NEAR(c.noise.a, 0.2, 0.01) << floor;
        EXPECT_NEAR(c.noise.b, 0.6, 0.02) << floor;
    }
}

TEST(TargetError, ChosenSppIsTheFewestReachingTheTargetAndMonotone) {
    ErrorCurve c{0.003 * 0.003, {0.25, 0.7}};
    int last = 0;
    for (double target = 0.2; target > 0.0035; target *= 0.93) {
        std::optional<int> n = c.SppFor(target);
        ASSERT_TRUE(n) << target;
        EXPECT_GE(*n, last) << target;  // a smaller target never takes fewer samples
        EXPECT_LE(c.Error(*n), target);
        EXPECT_TRUE(IsWellStratifiedSampleCount(*n)) << *n;
        int previous = *n - 1;
        while (previous > 0 && !IsWellStratifiedSampleCount(previous)) --previous;
        if (previous > 0) EXPECT_GT(c.Error(previous), target);
        last = *n;
    }
    EXPECT_FALSE(c.SppFor(0.003));  // at the floor: unreachable
    EXPECT_FALSE(c.SppFor(0.001));
}

TEST(TargetError, WellStratifiedSampleCounts) {
    std::vector<int> counts;
    for (int n = 0; n <= 42; ++n)
        if (IsWellStratifiedSampleCount(n)) counts.push_back(n);
    EXPECT_EQ(counts, (std::vector<int>{1,  2,  3,  4,  5,  6,  7,  8,  9,  12, 15, 16,
                                        18, 20, 24, 25, 28, 30, 32, 35, 36, 40, 42}));
    EXPECT_EQ(NextWellStratifiedSampleCount(21), 24);
    EXPECT_EQ(NextWellStratifiedSampleCount(25), 25);
    EXPECT_EQ(NextWellStratifiedSampleCount(0), 1);
    EXPECT_TRUE(IsWellStratifiedSampleCount(256));
    EXPECT_TRUE(IsWellStratifiedSampleCount(1 << 16));
}

TEST(TargetError, RelativeRmseAndPilotResolution) {
    Image a(2, 1), b(2, 1);
    b.SetRGB(0, 0, RGB(1, 1, 1));
    b.SetRGB(1, 0, RGB(1, 1, 1));
    a.SetRGB(0, 0, RGB(1, 1, 1));
    a.SetRGB(1, 0, RGB(0.5f, 1, 1));
    EXPECT_DOUBLE_EQ(RelativeRmse(a, b), std::sqrt(0.25 / 6));
    EXPECT_EQ(PilotResolution({640, 480}), Vec2i(320, 240));
    EXPECT_EQ(PilotResolution({200, 100}), Vec2i(100, 50));
    EXPECT_EQ(PilotResolution({100, 50}), Vec2i(64, 32));
    EXPECT_EQ(PilotResolution({48, 36}), Vec2i(48, 36));
}

// The whole path on a small Whitted scene (mirror, glass, texture, an environment light):
// the render with the chosen settings lands near the target against the study's reference.
TEST(TargetError, SmallSceneLandsNearTheTarget) {
    Diagnostics diag(false);
    SceneDescription desc = LoadScene(Source + "/scenes/whitted.pbrt", diag);
    BuildSettings base;
    base.resolution = {64, 48};
    TargetOptions o;
    o.target = 0.05;
    TargetChoice choice = ChooseTargetSettings(desc, base, o, diag);
    EXPECT_GE(choice.spp, 1);
    EXPECT_LE(choice.predictedError, o.target);
    EXPECT_EQ(choice.pilotResolution, Vec2i(64, 48));
    EXPECT_FALSE(choice.candidates.empty());
    BuildSettings s = ApplyTargetChoice(base, choice);
    EXPECT_EQ(s.spp, choice.spp);
    RenderScene scene = BuildRenderScene(desc, s, diag);
    Image img = Render(scene, nullptr);
    TargetVerification v = VerifyTarget(desc, base, choice, img, diag);
    EXPECT_GT(v.refSpp, choice.spp);
    EXPECT_NEAR(v.reached, o.target, 0.5 * o.target) << DescribeVerification(choice, v);
    EXPECT_NE(DescribeChoice(choice).find("target-error: chose spp"), std::string::npos);
    // A floor above the target: a clear error, no render.
    o.target = 1e-6;
    EXPECT_THROW(ChooseTargetSettings(desc, base, o, diag), SceneError);
}

}  // namespace
}  // namespace prism
