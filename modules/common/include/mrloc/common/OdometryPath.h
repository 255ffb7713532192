#pragma once
// A robot's odometry readings turned into what several parts need: the path length
// travelled (seed 000's l_C, seed 001's distance between fixes) and the speed over the
// last two readings (the RF beacon's priority, the motion compensation of ranges).
// One place computes them, from the readings' world-frame positions.
#include <mrpt/poses/CPose2D.h>

#include <optional>

namespace mrloc::common {

class OdometryPath {
 public:
    /** Adds a reading at time t (s). */
    void add(double t, const mrpt::poses::CPose2D& odometry);
    /** Path length from the first reading to the last (m). */
    double length() const { return length_; }
    /** Length of the last step, between the last two readings (m); 0 before two. */
    double lastStep() const { return lastStep_; }
    /** Speed over the last step (m/s), and its forward component in the robot's frame at
     *  the earlier reading; nothing before two readings or when they share a time. */
    std::optional<double> speed() const { return speed_; }
    std::optional<double> forwardSpeed() const { return forwardSpeed_; }
    std::optional<mrpt::poses::CPose2D> last() const { return last_; }
    /** The odometry at time t after the last reading, the last step's increment taken in
     *  proportion; nothing before two readings, before the last reading, or later than one
     *  and a half steps after it (a reading is missing: the robot may have stopped). */
    std::optional<mrpt::poses::CPose2D> extrapolate(double t) const;

 private:
    std::optional<mrpt::poses::CPose2D> last_;
    double lastTime_ = 0, length_ = 0, lastStep_ = 0;
    std::optional<std::pair<mrpt::poses::CPose2D, double>> lastIncrement_;  // and its duration
    std::optional<double> speed_, forwardSpeed_;
};

}  // namespace mrloc::common
