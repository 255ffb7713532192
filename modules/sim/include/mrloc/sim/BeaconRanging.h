#pragma once
// The beacons' hardware in the simulator: pan-tilt heads that slew to where the RF beacon
// tells them, transmitters that fire one after another on the shared ultrasonic channel,
// and the link (Ultrasonic.h) plus the TOF noise and failure model ([sensors]) between a
// transmitter and a receiver. One RangingEpoch in, one CObservationBeaconRanges out.
#include <mrloc/common/BeaconMap.h>
#include <mrloc/common/PanTilt.h>
#include <mrloc/common/RangingController.h>
#include <mrloc/sim/Sensors.h>
#include <mrloc/sim/ShotLog.h>
#include <mrloc/sim/Ultrasonic.h>
#include <mrloc/sim/World.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/random/RandomGenerators.h>

#include <functional>
#include <map>

namespace mrloc::sim {

class BeaconRanging {
 public:
    BeaconRanging(const World& world, const common::BeaconMap& beacons, SensorOptions sensors,
                  UltrasonicOptions ultrasonic);

    /** Starts an epoch at time t: each head slews to its aim point (eq. 3 inverse
     *  kinematics), then the beacons fire in order, one per shot interval. Returns the time
     *  the channel is free again. Throws mrloc::Error for a beacon that is not in the map. */
    double begin(double t, const common::RangingEpoch& epoch);
    bool inEpoch() const { return inEpoch_; }
    const common::RangingEpoch& epoch() const { return epoch_; }

    /** Fires the current epoch's shots that are due by time t at the receiver, which is at
     *  `receiverAt(time)` in the world (`onRobot` in the robot's frame), and logs them.
     *  After the last shot it returns the epoch's observation (ranges of the shots
     *  received), stamped by the caller, and ends the epoch; lastShotTime() tells when. */
    mrpt::obs::CObservationBeaconRanges::Ptr fireDue(
        double t, const std::function<mrpt::math::TPoint3D(double)>& receiverAt,
        const mrpt::math::TPoint3D& onRobot, mrpt::random::CRandomGenerator& rng, ShotLog& log);
    double lastShotTime() const { return lastShot_; }

    const common::PanTiltHead& head(int beacon) const { return heads_.at(beacon).head; }
    common::PanTiltAngles angles(int beacon) const { return heads_.at(beacon).angles; }
    const UltrasonicLink& link() const { return link_; }

 private:
    struct Head {
        common::PanTiltHead head;
        common::PanTiltAngles angles;  ///< current joint angles; 0, 0 = straight down
    };
    ShotRecord shoot(int beacon, const mrpt::math::TPoint3D& rx,
                     mrpt::random::CRandomGenerator& rng) const;

    const World& world_;
    const common::BeaconMap& beacons_;
    SensorOptions sensors_;
    UltrasonicLink link_;
    std::map<int, Head> heads_;

    bool inEpoch_ = false;
    common::RangingEpoch epoch_;
    double firstShot_ = 0;
    size_t fired_ = 0;
    double lastShot_ = 0;
    mrpt::obs::CObservationBeaconRanges::Ptr obs_;
};

}  // namespace mrloc::sim
