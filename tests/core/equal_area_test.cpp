// The equal-area square-sphere mapping (core/equal_area.h): unit directions, the inverse, the
// layout pbrt-v4's maps use, and equal area — the Jacobian is 4π everywhere.
#include "core/equal_area.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"

namespace prism {
namespace {

TEST(EqualArea, LayoutCentreIsUpCornersAreDownEdgesAreTheEquator) {
    const Vec3d c = EqualAreaSquareToSphere({0.5, 0.5});
    EXPECT_NEAR(c.z, 1, 1e-12);
    for (Vec2d corner : {Vec2d(0, 0), Vec2d(1, 0), Vec2d(0, 1), Vec2d(1, 1)})
        EXPECT_NEAR(EqualAreaSquareToSphere(corner).z, -1, 1e-12);
    // The edge midpoints' diamond is the equator; its vertices are ±x and ±y.
    const Vec3d px = EqualAreaSquareToSphere({1, 0.5}), py = EqualAreaSquareToSphere({0.5, 1});
    EXPECT_NEAR(px.x, 1, 1e-12);
    EXPECT_NEAR(py.y, 1, 1e-12);
    EXPECT_NEAR(EqualAreaSquareToSphere({0.75, 0.75}).z, 0, 1e-12);
    // Halfway from the centre to the left edge: r = 1/2, so z = 1 - r² = 3/4, on the -x side.
    const Vec3d half = EqualAreaSquareToSphere({0.25, 0.5});
    EXPECT_NEAR(half.z, 0.75, 1e-12);
    EXPECT_NEAR(half.x, -std::sqrt(1 - 0.75 * 0.75), 1e-12);
    EXPECT_NEAR(half.y, 0, 1e-12);
}

TEST(EqualArea, DirectionsAreUnitAndTheInverseRoundTrips) {
    PCG32 rng(4, 2);
    for (int i = 0; i < 20000; ++i) {
        const Vec2d p(rng.Uniform(), rng.Uniform());
        const Vec3d w = EqualAreaSquareToSphere(p);
        ASSERT_NEAR(Length(w), 1, 1e-12) << p.x << " " << p.y;
        const Vec2d q = EqualAreaSphereToSquare(w);
        ASSERT_NEAR(q.x, p.x, 1e-9) << p.x << " " << p.y;
        ASSERT_NEAR(q.y, p.y, 1e-9) << p.x << " " << p.y;
    }
    // Poles and axes, where the octant is ambiguous, still land on the right points.
    const Vec2d up = EqualAreaSphereToSquare({0, 0, 1});
    EXPECT_NEAR(up.x, 0.5, 1e-12);
    EXPECT_NEAR(up.y, 0.5, 1e-12);
    const Vec3d down = EqualAreaSquareToSphere(EqualAreaSphereToSquare({0, 0, -1}));
    EXPECT_NEAR(down.z, -1, 1e-12);
    const Vec3d minusY = EqualAreaSquareToSphere(EqualAreaSphereToSquare({0, -1, 0}));
    EXPECT_NEAR(minusY.y, -1, 1e-9);
}

// |∂w/∂x × ∂w/∂y| by central differences: 4π wherever the map is smooth (away from the
// diamond's edges and the axes, where it folds).
TEST(EqualArea, EveryPatchOfTheSquareIsTheSameSolidAngle) {
    PCG32 rng(9, 1);
    const double h = 1e-6;
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec2d p(0.01 + 0.98 * rng.Uniform(), 0.01 + 0.98 * rng.Uniform());
        const double u = std::abs(2 * p.x - 1), v = std::abs(2 * p.y - 1);
        if (std::abs(u + v - 1) < 1e-3 || u < 1e-3 || v < 1e-3) continue;
        const Vec3d dx =
            (EqualAreaSquareToSphere({p.x + h, p.y}) - EqualAreaSquareToSphere({p.x - h, p.y})) /
            (2 * h);
        const Vec3d dy =
            (EqualAreaSquareToSphere({p.x, p.y + h}) - EqualAreaSquareToSphere({p.x, p.y - h})) /
            (2 * h);
        ASSERT_NEAR(Length(Cross(dx, dy)), 4 * Pi, 1e-4) << p.x << " " << p.y;
        ++checked;
    }
    EXPECT_GT(checked, 3900);
}

}  // namespace
}  // namespace prism
