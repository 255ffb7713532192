// Simulator: kinematics, steering, line of sight in the OctoMap.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/sim/Sensors.h>
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

TEST(Odometry, SystematicErrorsScaleDistancesAndDriftTheHeading) {
    auto cfg = config();
    auto& o = cfg.robots[0];
    o.start = mrpt::poses::CPose2D(0, 0, 0);
    o.odometrySigmaXY = o.odometrySigmaPhi = o.odometrySigmaPhiPerMetre = 0;
    o.odometryScaleError = 0.01;          // wheels 1 % larger than believed
    o.odometryHeadingDrift = M_PI / 180;  // 1 deg per metre
    mrpt::random::CRandomGenerator rng(1), untouched(1);
    sim::OdometrySensor odometer(o, rng);
    EXPECT_EQ(rng.drawUniform32bit(), untouched.drawUniform32bit());  // no sigma: no draw
    // 2 m straight in 1 cm steps: 2.02 m read, the heading 2 deg off
    for (int k = 0; k < 200; ++k) odometer.accumulate(mrpt::poses::CPose2D(0.01, 0, 0), rng);
    const auto read = odometer.read("r.odom", mrpt::Clock::now())->odometry;
    EXPECT_NEAR(read.phi(), 2 * M_PI / 180, 1e-12);
    // the path bends by the drift: its length is 2.02 m, its chord a little less
    EXPECT_NEAR(std::hypot(read.x(), read.y()), 2.02 * (1 - std::pow(M_PI / 90, 2) / 24), 1e-5);
    // with sigmas the errors are drawn once, in order: scale, then drift
    o.odometryScaleErrorSigma = 0.005;
    o.odometryHeadingDriftSigma = 0.001;
    mrpt::random::CRandomGenerator g(9), h(9);
    sim::OdometrySensor drawn(o, g);
    const double scale = 0.01 + h.drawGaussian1D(0, 0.005);
    const double drift = M_PI / 180 + h.drawGaussian1D(0, 0.001);
    EXPECT_DOUBLE_EQ(drawn.scaleError(), scale);
    EXPECT_DOUBLE_EQ(drawn.headingDrift(), drift);
}

TEST(World, PillarsFillTheirCircleOnly) {
    auto cfg = config();
    cfg.world.pillars.push_back({"p", 1.0, 3.0, 0.2, 1.0});
    const sim::World world(cfg.world);
    const auto occupied = [&](double x, double y, double z) {
        const auto* n = world.octree().search(x, y, z);
        return n && world.octree().isNodeOccupied(n);
    };
    EXPECT_TRUE(occupied(1.0, 3.0, 0.5));
    EXPECT_TRUE(occupied(1.12, 3.0, 0.9));
    EXPECT_FALSE(occupied(1.3, 3.0, 0.5));    // beyond the radius
    EXPECT_FALSE(occupied(1.16, 3.16, 0.5));  // the square's corner, outside the circle
    EXPECT_FALSE(occupied(1.0, 3.0, 1.2));    // above it
    EXPECT_FALSE(world.lineOfSight({0.5, 3.0, 0.5}, {1.5, 3.0, 0.5}));
}

TEST(Simulator, AnObservationSinkSeesWhatTheRawlogGets) {
    const auto cfg = config();
    sim::Simulator a(cfg), b(cfg, std::make_shared<const sim::World>(cfg.world));
    const std::string path = testing::TempDir() + "/sink.rawlog";
    {
        common::RawlogWriter w(path);
        a.run(w);
        w.commit();
    }
    std::vector<double> sunk;
    b.run([&](const mrpt::obs::CObservation& o) {
        sunk.push_back(mrpt::Clock::toDouble(o.timestamp));
    });
    common::RawlogReader r(path);
    size_t n = 0;
    for (mrpt::obs::CObservation::Ptr obs; r.next(obs); ++n)
        ASSERT_EQ(mrpt::Clock::toDouble(obs->timestamp), sunk.at(n));
    EXPECT_EQ(n, sunk.size());
    EXPECT_GT(n, 10u);
}

// effective.ini writes a robot's start, waypoints and the world's obstacles with every digit
// their reals hold (they were "%g": 6 digits, so a run from effective.ini started 1e-6 m off)
TEST(Robot, EffectiveIniGivesBackTheStartAndWaypointsToTheDigit) {
    mrpt::config::CConfigFileMemory ini(
        "[robot.r1]\nstart = 1.23456789012345 -2.000000000001 33.3\n"
        "waypoints = 0.1000000001 2.718281828459045, 3 4\n");
    mrloc::sim::RobotOptions r;
    r.loadFromConfigFile(ini, "robot.r1");
    mrpt::config::CConfigFileMemory saved;
    r.saveToConfigFile(saved, "robot.r1");
    EXPECT_EQ(saved.read_string("robot.r1", "start", ""), "1.23456789012345 -2.000000000001 33.3");
    mrloc::sim::RobotOptions back;
    back.loadFromConfigFile(saved, "robot.r1");
    EXPECT_EQ(back.start.x(), r.start.x());
    EXPECT_EQ(back.start.y(), r.start.y());
    EXPECT_EQ(back.start.phi(), r.start.phi());  // "33.3" gives the pose "33.3" gave
    ASSERT_EQ(back.waypoints.size(), 2u);
    EXPECT_EQ(back.waypoints[0].x, 0.1000000001);
    EXPECT_EQ(back.waypoints[0].y, 2.718281828459045);
}

// A batch job's trials share one world (issue 56): sharedWorld builds it once while the
// [world] keys stay the same (whatever the seed), and anew when one changes; the shared world
// is the one World(options) builds (the same voxels).
TEST(World, SharedWorldIsBuiltOnceWhileItsKeysStayTheSame) {
    auto cfg = config();
    const auto a = sim::sharedWorld(cfg.world);
    EXPECT_EQ(sim::sharedWorld(cfg.world), a);
    const sim::World fresh(cfg.world);
    EXPECT_EQ(a->octree().size(), fresh.octree().size());
    EXPECT_EQ(a->octree().getNumLeafNodes(), fresh.octree().getNumLeafNodes());
    cfg.world.pillars.push_back({"p", 1.0, 3.0, 0.2, 1.0});
    const auto b = sim::sharedWorld(cfg.world);
    EXPECT_NE(b, a);
    EXPECT_FALSE(b->lineOfSight({0.5, 3.0, 0.5}, {1.5, 3.0, 0.5}));  // the pillar is there
    EXPECT_TRUE(a->lineOfSight({0.5, 3.0, 0.5}, {1.5, 3.0, 0.5}));   // a, still held, is not
    EXPECT_EQ(sim::sharedWorld(cfg.world), b);
}
