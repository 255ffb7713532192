#pragma once
// Ranges a robot at a known pose would hear: one per beacon of the map, to a receiver 0.5 m
// above the robot's centre, each plus the error the caller draws (noise, a bias, a late
// echo). Shared by the tracker's tests and its benchmark.
#include <mrloc/beacons/BeaconMap.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <functional>

namespace mrloc::testing_beacons {

/** error(beacon id, true distance) is added to each range, beacons in the map's order. */
inline mrpt::obs::CObservationBeaconRanges rangesAt(
    const beacons::BeaconMap& map, const mrpt::poses::CPose2D& robot,
    const std::function<double(int, double)>& error) {
    constexpr double kReceiverHeight = 0.5;
    mrpt::obs::CObservationBeaconRanges obs;
    for (const auto& [id, b] : map) {
        mrpt::obs::CObservationBeaconRanges::TMeasurement m;
        m.beaconID = id;
        m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0, 0, kReceiverHeight);
        const double d = std::sqrt(std::pow(b.x - robot.x(), 2) + std::pow(b.y - robot.y(), 2) +
                                   std::pow(b.z - kReceiverHeight, 2));
        m.sensedDistance = float(d + error(id, d));
        obs.sensedData.push_back(m);
    }
    return obs;
}

}  // namespace mrloc::testing_beacons
