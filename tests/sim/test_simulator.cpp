// Simulator: kinematics, steering, line of sight in the OctoMap.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>

#include "WalledRoomIni.h"

using namespace mrloc;

namespace {

using testing_room::kWalledRoomIni;

sim::ScenarioConfig config() {
    mrpt::config::CConfigFileMemory ini(kWalledRoomIni);
    return sim::ScenarioConfig::load(ini);
}

}  // namespace

TEST(World, LineOfSightIsBlockedByObstacleOnly) {
    const sim::World world(config().world);
    EXPECT_TRUE(world.lineOfSight({0.5, 0.5, 0.5}, {0.2, 0.2, 2.5}));
    EXPECT_TRUE(world.lineOfSight({0.5, 0.5, 0.5}, {1.5, 3.8, 2.5}));
    EXPECT_FALSE(world.lineOfSight({0.5, 0.5, 0.5}, {3.8, 2.0, 2.5}));  // through the wall at x=2
    EXPECT_TRUE(world.lineOfSight({2.5, 0.5, 0.5}, {3.8, 2.0, 2.5}));
    // Beacons mounted in the corners of the room, on the wall surface.
    EXPECT_TRUE(world.lineOfSight({0.5, 0.5, 0.5}, {0.0, 4.0, 2.5}));
    EXPECT_TRUE(world.lineOfSight({3.0, 1.0, 0.5}, {4.0, 4.0, 2.5}));
    EXPECT_TRUE(world.lineOfSight({3.0, 1.0, 0.5}, {4.0, 0.0, 2.5}));
    EXPECT_FALSE(world.lineOfSight({3.0, 1.0, 0.5}, {0.0, 0.0, 2.5}));
}

TEST(Robot, UnicycleReachesWaypointAtConfiguredSpeed) {
    auto cfg = config();
    sim::Robot robot(cfg.robots[0]);
    mrpt::random::CRandomGenerator rng(1);
    double travelled = 0;
    for (int k = 0; k < 400; ++k) {
        const auto d = robot.step(0.01, rng);
        travelled += std::hypot(d.x(), d.y());
    }
    // 4 s at 0.5 m/s straight north from (0.5, 0.5): heading already 90 degrees.
    EXPECT_NEAR(robot.pose().y(), 2.5, 1e-6);
    EXPECT_NEAR(robot.pose().x(), 0.5, 1e-9);
    EXPECT_NEAR(travelled, 2.0, 1e-6);
}

TEST(Robot, StopGoDriveAndTurnAsCommanded) {
    auto cfg = config();
    sim::Robot robot(cfg.robots[0]);
    mrpt::random::CRandomGenerator rng(1);
    robot.drive(0.2, 0);  // 0.2 m/s straight on, heading 90 degrees
    for (int k = 0; k < 100; ++k) robot.step(0.01, rng);
    EXPECT_NEAR(robot.pose().y(), 0.5 + 0.2, 1e-9);
    robot.turn(0.5);  // on the spot: 0.5 rad in 1 s
    for (int k = 0; k < 100; ++k) robot.step(0.01, rng);
    EXPECT_NEAR(robot.pose().y(), 0.7, 1e-9);
    EXPECT_NEAR(robot.pose().phi(), M_PI / 2 + 0.5, 1e-9);
    robot.drive(10, 100);  // capped at speed 0.5 m/s and max_turn_rate 1.5 rad/s
    const auto d = robot.step(0.1, rng);
    EXPECT_NEAR(d.phi(), 0.15, 1e-12);
    EXPECT_NEAR(std::hypot(d.x(), d.y()), 2 * 0.5 / 1.5 * std::sin(0.075), 1e-12);  // chord
    robot.stop();
    EXPECT_TRUE(robot.halted());
    robot.go();
    robot.setWaypoints({{0.7, 3.0}}, false);  // back to following waypoints
    for (int k = 0; k < 2000; ++k) robot.step(0.01, rng);
    EXPECT_NEAR(robot.pose().x(), 0.7, 0.03);
    EXPECT_NEAR(robot.pose().y(), 3.0, 0.03);
}

TEST(Robot, ActuationNoiseIsDrawnOnlyWhenAskedFor) {
    auto cfg = config();
    sim::Robot exact(cfg.robots[0]);
    mrpt::random::CRandomGenerator a(3), b(3);
    exact.step(0.01, a);
    EXPECT_EQ(a.drawUniform32bit(), b.drawUniform32bit());  // no draw without noise
    cfg.robots[0].actuationSigmaV = 0.1;
    sim::Robot noisy(cfg.robots[0]);
    double sum = 0, sum2 = 0;
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
        sim::Robot r(cfg.robots[0]);
        const double v = std::hypot(r.step(0.01, a).x(), 0.0) / (0.5 * 0.01);  // relative speed
        sum += v, sum2 += v * v;
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 1.0, 0.01);  // 4.5 standard errors of 0.1 / sqrt(2000)
    EXPECT_NEAR(sd, 0.1, 0.01);
}
