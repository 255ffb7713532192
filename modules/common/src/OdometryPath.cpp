#include <mrloc/common/OdometryPath.h>
#include <cmath>

namespace mrloc::common {

void OdometryPath::add(double t, const mrpt::poses::CPose2D& odometry) {
    if (last_) {
        lastStep_ = std::hypot(odometry.x() - last_->x(), odometry.y() - last_->y());
        length_ += lastStep_;
        if (t > lastTime_) {
            speed_ = lastStep_ / (t - lastTime_);
            forwardSpeed_ = (odometry - *last_).x() / (t - lastTime_);  // in the robot's frame
            lastIncrement_ = {odometry - *last_, t - lastTime_};
        }
    }
    last_ = odometry;
    lastTime_ = t;
}

std::optional<mrpt::poses::CPose2D> OdometryPath::extrapolate(double t) const {
    if (!last_ || !lastIncrement_) return std::nullopt;
    const auto& [increment, duration] = *lastIncrement_;
    const double ahead = t - lastTime_;
    if (ahead < 0 || ahead > 1.5 * duration) return std::nullopt;
    // the last increment in proportion: a chord of the arc the robot is on, which is 0.04 mm
    // from the arc 30 ms after a reading at 0.5 m/s on a 2 m circle
    const double f = ahead / duration;
    return *last_ + mrpt::poses::CPose2D(f * increment.x(), f * increment.y(), f * increment.phi());
}

}  // namespace mrloc::common
