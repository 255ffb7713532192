// The odometry path: its length, speed and the pose it holds between readings.
#include <gtest/gtest.h>
#include <mrloc/common/OdometryPath.h>

#include <cmath>

using mrloc::common::OdometryPath;
using mrpt::poses::CPose2D;

// A robot on a 2 m circle at 0.5 m/s, odometry at 20 Hz: the pose 30 ms after a reading is
// the last increment in proportion, a chord: measured 0.037 mm from the arc (bound 0.1 mm),
// where holding the last reading would be 15 mm behind.
TEST(OdometryPath, ExtrapolatesAlongTheLastStepsArc) {
    const double radius = 2.0, speed = 0.5, dt = 0.05;
    const auto onCircle = [&](double t) {
        const double a = speed * t / radius;
        return CPose2D(radius * std::sin(a), radius * (1 - std::cos(a)), a);
    };
    OdometryPath path;
    EXPECT_FALSE(path.extrapolate(0.0));
    path.add(0.0, onCircle(0.0));
    EXPECT_FALSE(path.extrapolate(0.01));  // one reading: no twist yet
    for (int k = 1; k <= 10; ++k) path.add(k * dt, onCircle(k * dt));
    const double t = 10 * dt + 0.03;
    const auto p = path.extrapolate(t);
    ASSERT_TRUE(p);
    const CPose2D truth = onCircle(t);
    EXPECT_LT(std::hypot(p->x() - truth.x(), p->y() - truth.y()), 1e-4);
    EXPECT_NEAR(p->phi(), truth.phi(), 1e-9);
    EXPECT_TRUE(path.extrapolate(10 * dt));  // at the reading: the reading
    EXPECT_NEAR(path.extrapolate(10 * dt)->x(), onCircle(10 * dt).x(), 1e-12);
    EXPECT_FALSE(path.extrapolate(10 * dt - 0.001));     // before the last reading
    EXPECT_TRUE(path.extrapolate(10 * dt + 1.5 * dt));   // a reading late
    EXPECT_FALSE(path.extrapolate(10 * dt + 1.6 * dt));  // missing: the robot may have stopped
    EXPECT_NEAR(path.length(), speed * 10 * dt, 1e-4);   // chords of the arc
    ASSERT_TRUE(path.forwardSpeed());
    EXPECT_NEAR(*path.forwardSpeed(), speed, 1e-3);
}
