#include <mrloc/beacons/ShotScheduler.h>

#include <algorithm>
#include <limits>

namespace mrloc::beacons {

ShotScheduler::ShotScheduler(Scheduling policy, double minSpeed)
    : policy_(policy), minSpeed_(minSpeed) {}

size_t ShotScheduler::pick(double t, const std::vector<RobotReport>& candidates) {
    for (const auto& c : candidates)
        if (std::find(turnOrder_.begin(), turnOrder_.end(), c.robot) == turnOrder_.end())
            turnOrder_.push_back(c.robot);
    if (policy_ == Scheduling::Priority) {
        size_t best = 0;
        double bestScore = -1;
        for (size_t i = 0; i < candidates.size(); ++i) {
            const auto it = lastServed_.find(candidates[i].robot);
            const double score = it == lastServed_.end()
                                     ? std::numeric_limits<double>::infinity()
                                     : (t - it->second) * std::max(candidates[i].speed, minSpeed_);
            if (score > bestScore) {
                bestScore = score;
                best = i;
            }
        }
        return best;
    }
    // Round robin: the first candidate after the last robot served, in turn order.
    const auto last = std::find(turnOrder_.begin(), turnOrder_.end(), lastRobot_);
    const size_t start = last == turnOrder_.end() ? 0 : size_t(last - turnOrder_.begin()) + 1;
    for (size_t k = 0; k < turnOrder_.size(); ++k) {
        const std::string& name = turnOrder_[(start + k) % turnOrder_.size()];
        for (size_t i = 0; i < candidates.size(); ++i)
            if (candidates[i].robot == name) return i;
    }
    return 0;  // unreachable: every candidate is in turnOrder_
}

void ShotScheduler::served(const std::string& robot, double t) {
    lastServed_[robot] = t;
    lastRobot_ = robot;
}

}  // namespace mrloc::beacons
