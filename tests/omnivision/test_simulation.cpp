// The simulator's omni-camera run (snapshots, stops, the LiDAR) and the localizer's input
// checks.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/omnivision/OmniCamera.h>
#include <mrloc/omnivision/OmniLocalizer.h>
#include <mrloc/omnivision/OmniMethod.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationRange.h>

#include <algorithm>
#include <filesystem>

using namespace mrloc;

namespace {

const char* kIni = R"(
[scenario]
name = omni_sim
method = omnivision
robots = A B C
duration = 3
dt = 0.01
[world]
size = 10 10 3
[robot.A]
start = 1 1 0
waypoints = 9 1
[robot.B]
start = 1 5 0
waypoints = 9 5
[robot.C]
start = 5 9 -90
waypoints = 5 1
)";

}  // namespace

TEST(OmniSimulation, SnapshotsStopsAndLidarGoToTheRawlog) {
    mrpt::config::CConfigFileMemory ini(kIni);
    const auto cfg = sim::ScenarioConfig::load(ini);
    omnivision::OmniSetup setup;
    setup.camera.render = false;
    setup.snapshotTimes = {1, 2};
    setup.stops = {{"A", 1, 2}};
    setup.lidar = omnivision::OmniSetup::Lidar{"A", "B", 0.0};
    omnivision::OmniPayload payload(setup, cfg.world);
    const std::string dir = testing::TempDir() + "/omni_sim";
    const auto path = sim::simulateToFiles(cfg, dir, common::silentLog(), &payload).rawlog;
    common::RawlogReader reader(path);
    int bearings = 0, lidar = 0;
    std::vector<mrpt::obs::CObservation::Ptr> all;
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) all.push_back(obs);
    for (const auto& obs : all) {
        if (common::sensorOfLabel(obs->sensorLabel) == "omni_bearings") {
            const auto b = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(obs);
            ASSERT_TRUE(b);
            EXPECT_EQ(b->sensedData.size(), 2u);  // the two others
            for (const auto& m : b->sensedData) EXPECT_EQ(m.landmarkID, -1);
            ++bearings;
        }
        if (obs->sensorLabel == "A.lidar.B") {
            const auto r = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(obs);
            ASSERT_TRUE(r);
            const double t = mrpt::Clock::toDouble(obs->timestamp);
            const auto a =
                common::interpolate(common::loadTum(common::groundTruthPath(path, "A")), t);
            const auto b =
                common::interpolate(common::loadTum(common::groundTruthPath(path, "B")), t);
            EXPECT_NEAR(r->sensedData.front().sensedDistance,
                        std::hypot(a->x() - b->x(), a->y() - b->y()),
                        1e-5);  // sigma 0: the true distance (float)
            ++lidar;
        }
    }
    EXPECT_EQ(bearings, 6);  // 3 robots x 2 snapshots
    EXPECT_EQ(lidar, 2);
    // A stood still during [1, 2] s: same position at both snapshots.
    const auto gt = common::loadTum(common::groundTruthPath(path, "A"));
    const auto p1 = common::interpolate(gt, 1.7e9 + 1), p2 = common::interpolate(gt, 1.7e9 + 2);
    ASSERT_TRUE(p1 && p2);
    EXPECT_NEAR(p1->x(), p2->x(), 1e-9);
    const auto c1 =
        common::interpolate(common::loadTum(common::groundTruthPath(path, "C")), 1.7e9 + 1);
    const auto c2 =
        common::interpolate(common::loadTum(common::groundTruthPath(path, "C")), 1.7e9 + 2);
    EXPECT_GT(std::abs(c1->y() - c2->y()), 0.2);  // C drove on
}

// Bearings mode: an obstacle between two cameras hides each from the other (as a rendered
// panorama would), through the world's own line of sight; a robot's band hides those behind
// it; out of range is out of sight.
TEST(OmniSimulation, ObstaclesBandsAndRangeHideRobotsInBearingsMode) {
    sim::WorldOptions w;
    w.sizeX = 10, w.sizeY = 10, w.height = 3;
    w.obstacles = {{"wall", {4.9, 0.2, 0}, {5.1, 3, 1}}};
    const sim::World world(w);
    const omnivision::LineOfSight clear = [&](const auto& a, const auto& b) {
        return world.lineOfSight(a, b);
    };
    // A and B on either side of the wall; C seen by both; D behind C's band from A.
    const std::vector<mrpt::poses::CPose2D> poses{
        {2, 1, 0}, {8, 1, 0}, {5, 6, 0}, {6.8, 9, 0}};  // D = A + 1.6 (C - A)
    omnivision::OmniCameraOptions o;
    o.render = false;
    o.markerRadius = 0.15;
    const auto robotsSeen = [&](size_t observer, const omnivision::LineOfSight& los) {
        auto r = omnivision::sightingsOf(poses, observer, o, los).robots;
        std::sort(r.begin(), r.end());
        return r;
    };
    EXPECT_EQ(robotsSeen(0, {}), (std::vector<int>{1, 2}));     // open space: B and C
    EXPECT_EQ(robotsSeen(0, clear), (std::vector<int>{2}));     // the wall hides B
    EXPECT_EQ(robotsSeen(1, clear), (std::vector<int>{2, 3}));  // and A from B
    o.maxRange = 5;
    EXPECT_EQ(robotsSeen(1, clear), (std::vector<int>{}));  // C is 5.8 m away, D 8 m
}

TEST(OmniLocalizerInput, WrongClassUnderAnOmniLabelIsAnError) {
    mrpt::config::CConfigFileMemory ini("[omnivision]\ncamera = bearings\n");
    omnivision::OmniLocalizer loc;
    loc.configure(ini);
    auto wrong = mrpt::obs::CObservationBearingRange::Create();
    wrong->sensorLabel = "A.omni";
    try {
        loc.process(wrong);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'A.omni' is a mrpt::obs::CObservationBearingRange, "
                                             "expected CObservationImage"),
                  std::string::npos)
            << e.what();
    }
    auto nan = mrpt::obs::CObservationBearingRange::Create();
    nan->sensorLabel = "A.omni_bearings";
    mrpt::obs::CObservationBearingRange::TMeasurement m;
    m.yaw = std::numeric_limits<float>::quiet_NaN();
    nan->sensedData.push_back(m);
    EXPECT_THROW(loc.process(nan), Error);
    EXPECT_THROW(loc.estimates(), Error);  // no snapshot at all
}
