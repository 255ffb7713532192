// RangeWindow: ranges read one at a time, while the robot moves, given back as one epoch read
// at the newest time: closed form on a robot driving a known arc among four beacons.
#include <gtest/gtest.h>
#include <mrloc/beacons/RangeWindow.h>

namespace {

using mrloc::beacons::BeaconMap;
using mrloc::beacons::RangeWindow;
using mrpt::poses::CPose2D;

mrpt::obs::CObservationBeaconRanges oneRange(int id, double r) {
    mrpt::obs::CObservationBeaconRanges obs;
    mrpt::obs::CObservationBeaconRanges::TMeasurement m;
    m.beaconID = id;
    m.sensedDistance = float(r);
    m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0.05, 0.02, 0);  // off the centre
    obs.sensedData.push_back(m);
    return obs;
}

TEST(RangeWindow, RangesReadOneAtATimeAreMovedToTheNewestPose) {
    const BeaconMap map{{1, {0, 0, 0}}, {2, {4, 0, 0}}, {3, {4, 3, 0}}, {4, {0, 3, 0}}};
    // world pose = start (+) odometry; the odometry frame is turned and moved from the world's
    const CPose2D start(1.5, 1.0, 0.7);
    RangeWindow window;
    std::optional<mrpt::obs::CObservationBeaconRanges> epoch;
    const CPose2D odo0(10, -3, 2.0);  // the odometry's reading where the robot was at `start`
    CPose2D odo = odo0, world;
    for (int k = 0; k < 4; ++k) {
        if (k) odo = odo + CPose2D(0.2, 0.0, 0.15);  // 0.2 m and 8.6 deg per reading
        world = start + (odo - odo0);
        const auto sensor = world.composePoint(mrpt::math::TPoint2D(0.05, 0.02));
        const auto& b = map.at(k + 1);
        const double r = std::hypot(sensor.x - b.x, sensor.y - b.y);
        window.add(k * 0.1, oneRange(k + 1, r), odo, map);
        epoch = window.epoch(k * 0.1, odo, map, 4, 1.0);
        if (k < 3) {
            EXPECT_FALSE(epoch) << "only " << k + 1 << " beacons in";
        }
    }
    ASSERT_TRUE(epoch);
    ASSERT_EQ(epoch->sensedData.size(), 4u);
    // every range as the receiver reads it at the newest pose (it moved 0.6 m meanwhile)
    const auto sensor = world.composePoint(mrpt::math::TPoint2D(0.05, 0.02));
    for (const auto& m : epoch->sensedData) {
        const auto& b = map.at(m.beaconID);
        EXPECT_NEAR(m.sensedDistance, std::hypot(sensor.x - b.x, sensor.y - b.y), 1e-5)
            << "beacon " << m.beaconID;
    }
    // a range older than the span is not used
    EXPECT_FALSE(window.epoch(0.35, odo, map, 4, 0.3));
    EXPECT_EQ(window.added(), 4u);
}

}  // namespace
