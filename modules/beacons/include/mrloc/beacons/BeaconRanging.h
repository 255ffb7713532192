#pragma once
// The beacons' hardware in the simulator: pan-tilt heads that slew to where the RF beacon
// tells them, transmitters that fire one after another on the shared ultrasonic channel,
// and the link (Ultrasonic.h) plus the TOF noise and failure model ([sensors]) between a
// transmitter and a receiver. One RangingEpoch in, one CObservationBeaconRanges out.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/PanTilt.h>
#include <mrloc/beacons/RangingEpoch.h>
#include <mrloc/beacons/ShotLog.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/sim/World.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/random/RandomGenerators.h>

#include <functional>
#include <map>

namespace mrloc::beacons {

/** Section [sensors]: TOF noise and failures on top of the ultrasonic link. */
struct SensorOptions : public mrpt::config::CLoadableOptions {
    double rangeSigma = 0.01;          ///< Gaussian TOF range noise (m)
    double rangeMax = 10;              ///< no reading beyond (m)
    double dropout = 0.02;             ///< probability a line-of-sight range is missed
    double outlierProbability = 0.01;  ///< probability a range reads long (late trigger)
    double outlierMin = 0.1;           ///< such a range is long by U(outlierMin, outlierMax) m
    double outlierMax = 1.0;
    double biasSigma = 0;     ///< each beacon's own range offset, drawn once (m)
    double biasDrift = 0;     ///< its random walk (m/sqrt(s)): a UWB antenna delay
    bool nlosReflect = true;  ///< blocked path: a long reflected range (else none)

    /** Every key of [sensors], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<SensorOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

/** One burst from a transmitter whose head is at `angles` to a receiver at `rx`: the link's
 *  level (distance, off-axis angle, fading), the decoder's trigger or a miss, the TOF noise,
 *  dropouts and late echoes of [sensors]. `lineOfSight` is asked once, after the draws;
 *  `beaconBias` (the beacon's own range offset) is asked only when [sensors] gives one. The
 *  draws are made in one fixed order whatever the branch, so one shot's fate never shifts
 *  the random stream of the others. Used by the simulator and by the coverage study
 *  (BeaconStudy.h), so both fire the same physics. */
ShotRecord simulateShot(const UltrasonicLink& link, const SensorOptions& sensors,
                        const PanTiltHead& head, const PanTiltAngles& angles, int beacon,
                        const mrpt::math::TPoint3D& rx, const std::function<bool()>& lineOfSight,
                        const std::function<double()>& beaconBias,
                        mrpt::random::CRandomGenerator& rng);

class BeaconRanging {
 public:
    BeaconRanging(const sim::World& world, const BeaconMap& beacons, SensorOptions sensors,
                  UltrasonicOptions ultrasonic);

    /** Starts an epoch at time t: each head slews to its aim point (eq. 3 inverse
     *  kinematics), then the beacons fire in order, one per shot interval. Returns the time
     *  the channel is free again. Throws mrloc::Error for a beacon that is not in the map. */
    double begin(double t, const RangingEpoch& epoch);
    bool inEpoch() const { return inEpoch_; }
    const RangingEpoch& epoch() const { return epoch_; }

    /** Fires the current epoch's shots that are due by time t at the receiver, which is at
     *  `receiverAt(time)` in the world (`onRobot` in the robot's frame), and logs them.
     *  After the last shot it returns the epoch's observation (ranges of the shots
     *  received), stamped by the caller, and ends the epoch; lastShotTime() tells when. */
    mrpt::obs::CObservationBeaconRanges::Ptr fireDue(
        double t, const std::function<mrpt::math::TPoint3D(double)>& receiverAt,
        const mrpt::math::TPoint3D& onRobot, mrpt::random::CRandomGenerator& rng, ShotLog& log);
    double lastShotTime() const { return lastShot_; }

    const PanTiltHead& head(int beacon) const { return heads_.at(beacon).head; }
    beacons::PanTiltAngles angles(int beacon) const { return heads_.at(beacon).angles; }
    const UltrasonicLink& link() const { return link_; }

 private:
    struct Head {
        PanTiltHead head;
        beacons::PanTiltAngles angles;  ///< current joint angles; 0, 0 = straight down
    };
    ShotRecord shoot(int beacon, const mrpt::math::TPoint3D& rx, double t,
                     mrpt::random::CRandomGenerator& rng);
    double beaconBias(int beacon, double t, mrpt::random::CRandomGenerator& rng);

    const sim::World& world_;
    const BeaconMap& beacons_;
    SensorOptions sensors_;
    UltrasonicLink link_;
    std::map<int, Head> heads_;
    std::map<int, std::pair<double, double>> bias_;  ///< beacon -> its offset, and when (s)

    bool inEpoch_ = false;
    RangingEpoch epoch_;
    double firstShot_ = 0;
    size_t fired_ = 0;
    double lastShot_ = 0;
    mrpt::obs::CObservationBeaconRanges::Ptr obs_;
};

}  // namespace mrloc::beacons
