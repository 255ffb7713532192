#include <mrloc/common/OdometryPath.h>
#include <mrpt/poses/Lie/SE.h>

#include <Eigen/Dense>
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
    using SE2 = mrpt::poses::Lie::SE<2>;
    SE2::tangent_vector twist = SE2::log(increment);
    twist *= ahead / duration;
    return *last_ + SE2::exp(twist);
}

}  // namespace mrloc::common
