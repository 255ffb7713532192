#pragma once
// Who gets the next slot of the ultrasonic channel (seed 001 section 2.1).
//
// Priority: the RF beacon knows each robot's speed and gives faster robots fixes more often,
// so that the distance travelled between two fixes is about the same for all. It serves
// the robot with the largest estimated distance since its last slot,
//     score = (t - last slot) * max(speed, min_speed),
// which makes slot rates proportional to speed (min_speed keeps standing robots served).
// Round robin: the robots take turns, whatever their speed (the existing systems).
#include <mrloc/beacons/RangingEpoch.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::beacons {

enum class Scheduling { Priority, RoundRobin };

class ShotScheduler {
 public:
    ShotScheduler(Scheduling policy, double minSpeed);
    /** Index in `candidates` of the robot to serve at time t (candidates not empty). */
    size_t pick(double t, const std::vector<RobotReport>& candidates);
    /** Records that `robot` got the slot at time t. */
    void served(const std::string& robot, double t);

 private:
    Scheduling policy_;
    double minSpeed_;
    std::map<std::string, double> lastServed_;
    std::vector<std::string> turnOrder_;  ///< robots in order of first appearance
    std::string lastRobot_;
};

}  // namespace mrloc::beacons
