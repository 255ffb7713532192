#pragma once
// The beacon system in the simulator (seed 001), as the method's payload: the pan-tilt
// heads, the ultrasonic link and the TOF noise (BeaconRanging), the robots' on-board
// estimator and the RF beacon that schedules and aims from what they report. Beacon
// ranging is closed-loop: when the ultrasonic channel is free, the robots that want a fix
// report their position (from the on-board estimate) and speed (from odometry) to the RF
// beacon, which picks the next epoch; the heads slew and fire. Every shot goes to the shot
// log (`<stem>.shots.txt`), written beside the rawlog at the end.
#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/sim/Payload.h>

#include <limits>
#include <memory>

namespace mrloc::beacons {

/** A robot's beacon keys in [robot.<name>] (the simulator's robot options accept them). */
struct BeaconRobotOptions {
    mrpt::math::TPoint3D receiver{0, 0, 0.3};  ///< receiver = x y z on the robot (m)
    double beaconRate = 5;   ///< beacon_rate: most ranging epochs it asks for (Hz)
    long rangingEpochs = 0;  ///< ranging_epochs: stops asking after this many (0: never)
    /** ranging_pause = t0 t1 (s from the start): asks for no epoch in [t0, t1) (out of the
     *  beacons' reach: a gap in the ranges); none if t1 <= t0 */
    double pauseStart = 0, pauseEnd = 0;

    /** The beacon method's keys of [robot.<name>] (doc/ini.md shows them with the
     *  simulator's). */
    static const common::KeyTable<BeaconRobotOptions>& keys();
    /** Their names, which the simulator accepts in [robot.<name>]. */
    static std::vector<std::string> keyNames();
    void load(const mrpt::config::CConfigFileBase& ini, const std::string& robot);
    void save(mrpt::config::CConfigFileBase& target, const std::string& robot) const;
};

class BeaconPayload : public sim::Payload {
 public:
    /** The on-board part is configured from the INI's [beacons]; `world` must outlive the
     *  payload. */
    /** `robots` in the scenario's robot order. */
    BeaconPayload(const mrpt::config::CConfigFileBase& ini, const BeaconMap& beacons,
                  SensorOptions sensors, UltrasonicOptions ultrasonic,
                  std::vector<BeaconRobotOptions> robots);
    /** Another controller instead of the RF beacon (tests: every beacon at the truth). */
    void replaceController(std::unique_ptr<RangingController> controller) {
        controller_ = std::move(controller);
    }
    void sense(sim::Step& step) override;
    void onObservation(const mrpt::obs::CObservation::Ptr& obs) override;
    std::vector<std::string> finish(const std::string& rawlogPath) override;

    const ShotLog& shots() const { return shots_; }
    const OnboardBeacons& onboard() const { return onboard_; }

 private:
    struct RobotState {
        double lastEpoch = -std::numeric_limits<double>::infinity();
        long epochs = 0;
    };
    void fireDue(sim::Step& step);
    RobotReport report(const sim::Step& step, size_t robot) const;

    OnboardBeacons onboard_;
    std::unique_ptr<RangingController> controller_;  ///< null: the RF beacon
    BeaconMap beacons_;
    SensorOptions sensors_;
    UltrasonicOptions ultrasonic_;
    std::unique_ptr<BeaconRanging> ranging_;  ///< made at the first step, with the world
    std::vector<BeaconRobotOptions> robots_;
    std::vector<RobotState> state_;
    size_t epochRobot_ = 0;  ///< the robot the current epoch serves
    double channelFree_ = 0;
    ShotLog shots_;
};

}  // namespace mrloc::beacons
