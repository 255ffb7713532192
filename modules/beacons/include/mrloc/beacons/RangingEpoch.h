#pragma once
// The seam between an active beacon system's decisions and the simulated hardware.
//
// A ranging epoch is one slot of the shared ultrasonic channel: one robot, the beacons of
// one section firing one after another at it. Who gets the slot, which beacons fire and
// where each head points is decided by a RangingController (the RF beacon's logic, seed 001
// section 2.1, implemented by the beacons module); the simulator slews the heads, fires,
// propagates the ultrasound and writes what the receiver heard to the rawlog.
#include <mrpt/math/TPoint3D.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::beacons {

/** What a robot tells the RF beacon over the radio before each slot. */
struct RobotReport {
    std::string robot;
    mrpt::math::TPoint3D receiver;  ///< its receiver's position, from its own estimate (m)
    double speed = 0;               ///< from its odometry (m/s)
};

struct RangingEpoch {
    std::string robot;
    std::string section;
    std::vector<int> beacons;                     ///< firing order (RF beacon first)
    std::vector<mrpt::math::TPoint3D> aimPoints;  ///< where each beacon's head points
    double shotInterval = 0.03;  ///< s between two shots: flight time + echoes dying out
};

class RangingController {
 public:
    virtual ~RangingController() = default;
    /** Called when the channel is free at time t (s since the start) with the robots that
     *  ask for a fix; returns the next slot, or nothing to leave the channel idle. */
    virtual std::optional<RangingEpoch> nextEpoch(double t,
                                                  const std::vector<RobotReport>& requests) = 0;
};

}  // namespace mrloc::beacons
