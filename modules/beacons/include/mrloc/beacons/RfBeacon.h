#pragma once
// The RF beacon's logic (seed 001 section 2.1), as the simulator's RangingController: it
// receives each robot's position and speed, hands the next slot of the ultrasonic channel
// to one robot (ShotScheduler), picks the beacons of the robot's section and tells each
// head where to point: at the robot's reported receiver position (active beacons, inverse
// kinematics of eq. 3 done by the head) or at the section's fixed aim point.
//
// Sections and handover: a robot can only be ranged by a section whose beacon table it
// holds. It holds its start section's from the beginning; any other takes
// registration_time to arrive after it is asked for. Without handover it is asked for when
// the robot's estimate enters the section, so fixes stop meanwhile; with handover the
// neighbouring RF beacon sends it as soon as the robot comes within handover_margin of the
// boundary, and the fixes keep flowing across it.
#include <mrloc/beacons/RangingEpoch.h>
#include <mrloc/beacons/Sections.h>
#include <mrloc/beacons/ShotScheduler.h>

#include <map>
#include <set>

namespace mrloc::beacons {

struct RfBeaconOptions {
    bool activeAiming = true;  ///< aiming = active | fixed
    Scheduling scheduling = Scheduling::Priority;
    double minSpeed = 0.05;         ///< m/s, floor of the priority's speed
    double handoverMargin = 0.5;    ///< m; 0 turns handover off
    double registrationTime = 0.5;  ///< s to receive a section's beacon table
    double shotInterval = 0.03;     ///< s between two beacons' shots in an epoch
    /** shots_per_beacon: rounds of the section's beacons in one epoch (each beacon fires
     *  this many times; a fix takes each beacon's mean range) */
    int shotsPerBeacon = 1;
    /** beacons_per_epoch: the section's beacons fired per epoch, in turn from where the
     *  robot's last epoch stopped (a radio beacon ranged one at a time: 1); 0: all */
    int beaconsPerEpoch = 0;
    SectionMap sections;

    /** How long before the end of its epoch beacon `id` fired, on average over its rounds
     *  (its section's firing order times shot_interval); 0 for a beacon in no section. */
    double shotAge(int id) const;
};

struct RfBeaconStats {
    size_t epochs = 0;
    size_t registrations = 0;  ///< section tables sent
    size_t waits = 0;          ///< requests turned down: section table not there yet
};

class RfBeacon : public beacons::RangingController {
 public:
    explicit RfBeacon(RfBeaconOptions options);
    std::optional<RangingEpoch> nextEpoch(double t,
                                          const std::vector<RobotReport>& requests) override;
    const RfBeaconStats& stats() const { return stats_; }

 private:
    /** Updates the robot's section tables; returns its section if its table is there. */
    std::optional<size_t> servingSection(double t, const RobotReport& r);

    RfBeaconOptions o_;
    ShotScheduler scheduler_;
    std::map<std::string, std::map<size_t, double>> tableReadyAt_;  ///< robot -> section -> t
    std::map<std::string, size_t> nextBeacon_;  ///< robot -> its next beacon (beacons_per_epoch)
    RfBeaconStats stats_;
};

}  // namespace mrloc::beacons
