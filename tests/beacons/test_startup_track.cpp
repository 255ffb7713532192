// The tracker's start-up: fixes that fit the odometry's path, found by consensus.
#include <gtest/gtest.h>
#include <mrloc/beacons/StartupTrack.h>

#include <cmath>

using mrloc::beacons::StartupTrack;
using mrpt::poses::CPose2D;

namespace {

// The odometry frame is the world turned by 0.7 rad and shifted by (1, 2): a robot driving
// 0.1 m per fix along the odometry's x axis.
const double kTurn = 0.7;
const Eigen::Vector2d kShift(1, 2);

Eigen::Vector2d world(double odometryX) {
    return kShift + Eigen::Vector2d(std::cos(kTurn), std::sin(kTurn)) * odometryX;
}

}  // namespace

TEST(StartupTrack, AWrongFixDoesNotTurnTheStart) {
    StartupTrack track;
    for (int k = 0; k < 7; ++k) {
        Eigen::Vector2d fix = world(0.1 * k);
        if (k == 5) fix += Eigen::Vector2d(0.25, -0.3);  // two long echoes that agree
        track.add({fix, CPose2D(0.1 * k, 0, 0), 0.05});
        // four fixes must agree over the 0.3 m baseline before anything starts
        if (k < 3) {
            EXPECT_FALSE(track.align(0.3)) << k;
        }
    }
    const auto T = track.align(0.3);
    ASSERT_TRUE(T);
    EXPECT_NEAR(std::atan2((*T)(1, 0), (*T)(0, 0)), kTurn, 1e-9);
    EXPECT_NEAR((*T)(0, 2), kShift.x(), 1e-9);
    EXPECT_NEAR((*T)(1, 2), kShift.y(), 1e-9);
    EXPECT_EQ(track.size(), 6u);  // the wrong fix is dropped
}

TEST(StartupTrack, NoStartWhileMostFixesDisagree) {
    StartupTrack track;
    // four good fixes and five wrong ones, each wrong a different way: no majority
    for (int k = 0; k < 9; ++k) {
        Eigen::Vector2d fix = world(0.1 * k);
        if (k % 2 == 1 || k == 8) fix += Eigen::Vector2d(0.2 * k, -0.1 * k);
        track.add({fix, CPose2D(0.1 * k, 0, 0), 0.05});
    }
    EXPECT_FALSE(track.align(0.3));
}

TEST(StartupTrack, ANewFixMustAgreeOnTheDistanceTravelled) {
    StartupTrack track;
    track.add({world(0), CPose2D(0, 0, 0), 0.02});
    EXPECT_FALSE(track.newestAgrees());  // a lone fix waits for a second
    track.add({world(0.2), CPose2D(0.2, 0, 0), 0.02});
    EXPECT_TRUE(track.newestAgrees());
    // 0.4 m from the first fix where the odometry moved 0.3 m: more than 0.02 + 0.02 +
    // 5 % of 0.3 m apart
    track.add({world(0) + Eigen::Vector2d(0.4, 0), CPose2D(0.3, 0, 0), 0.02});
    EXPECT_FALSE(track.newestAgrees());
    // the spread of the odometry positions 0, 0.2, 0.3 m about their mean
    EXPECT_NEAR(track.odometrySpread(), 0.0466667, 1e-6);
}
