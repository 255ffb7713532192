// Seed 004 eqs. (1)-(6), re-derived: the wall normal's two roots, the no-wall case, and the
// ERPs, against geometry computed by hand.
#include <gtest/gtest.h>
#include <mrloc/framesync/Erp.h>
#include <mrpt/core/bits_math.h>

#include <algorithm>
#include <cmath>

using namespace mrloc::framesync;
using mrpt::DEG2RAD;

namespace {
std::vector<double> sorted(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v;
}
}  // namespace

TEST(Erp, AWallParallelToTheMotionGivesBothPerpendicularRoots) {
    // P1 = (0, 0), P2 = (1, 0), the wall y = 1: r1 = r2 = 1, cos = 0, phi = 0 +- 90 deg
    const auto roots = sorted(wallNormalDirections({0, 0}, 1, {1, 0}, 1));
    ASSERT_EQ(roots.size(), 2u);
    EXPECT_NEAR(roots[0], -M_PI / 2, 1e-12);
    EXPECT_NEAR(roots[1], M_PI / 2, 1e-12);
}

TEST(Erp, ASlantedWallGivesItsNormalAndTheMirrorRoot) {
    // The wall n.X = 2 with n at 60 deg: r1 = 2 at (0, 0), r2 = 2 - n.(1, 0) = 1.5 at (1, 0).
    // cos = -(1.5 - 2) / 1 = 0.5, arccos = 60 deg: the roots are +60 (the wall) and -60.
    const auto roots = sorted(wallNormalDirections({0, 0}, 2, {1, 0}, 1.5));
    ASSERT_EQ(roots.size(), 2u);
    EXPECT_NEAR(roots[0], DEG2RAD(-60.0), 1e-12);
    EXPECT_NEAR(roots[1], DEG2RAD(60.0), 1e-12);
    // the same pair moved along (2, 3) and turned by 30 deg: alpha = 30 deg, roots 30 +- 60
    const double a = DEG2RAD(30.0);
    const TPoint2D p1(2, 3), p2(2 + std::cos(a), 3 + std::sin(a));
    const auto turned = sorted(wallNormalDirections(p1, 2, p2, 1.5));
    ASSERT_EQ(turned.size(), 2u);
    EXPECT_NEAR(turned[0], DEG2RAD(-30.0), 1e-12);
    EXPECT_NEAR(turned[1], DEG2RAD(90.0), 1e-12);
}

TEST(Erp, RangesChangingMoreThanTheSensorMovedAreNoWall) {
    // |r2 - r1| = 1.5 > |P1 P2| = 1: no plane gives both ranges (a pillar, a corner)
    EXPECT_TRUE(wallNormalDirections({0, 0}, 1, {1, 0}, 2.5).empty());
    EXPECT_TRUE(wallNormalDirections({0, 0}, 2.5, {0, 1}, 1).empty());
    // the sensor did not move: nothing to tell
    EXPECT_TRUE(wallNormalDirections({1, 1}, 1, {1, 1}, 1).empty());
}

TEST(Erp, MovingStraightAtTheWallGivesOneRoot) {
    // towards the wall x = 3 along x: r1 = 3, r2 = 2, cos = 1, the roots coincide at 0
    const auto roots = wallNormalDirections({0, 0}, 3, {1, 0}, 2);
    ASSERT_EQ(roots.size(), 1u);
    EXPECT_NEAR(roots[0], 0, 1e-12);
}

TEST(Erp, TheReflectionPointLiesOnTheWallAtTheRangeAlongTheNormal) {
    // eqs. (2)-(3): R = P + r (cos phi, sin phi); with the 60-degree wall, R2 is on n.X = 2
    const double phi = DEG2RAD(60.0);
    const Erp e = makeErp({1, 0}, 1.5, phi);
    EXPECT_NEAR(e.point.x, 1 + 1.5 * 0.5, 1e-12);
    EXPECT_NEAR(e.point.y, 1.5 * std::sqrt(3.0) / 2, 1e-12);
    EXPECT_NEAR(std::cos(phi) * e.point.x + std::sin(phi) * e.point.y, 2, 1e-12);
    // eq. (1): P1R1 . R1R2 = 0 for the two ERPs of the pair
    const Erp e1 = makeErp({0, 0}, 2, phi);
    const TPoint2D p1r1 = e1.point - e1.sensor, r1r2 = e.point - e1.point;
    EXPECT_NEAR(p1r1.x * r1r2.x + p1r1.y * r1r2.y, 0, 1e-12);
}
