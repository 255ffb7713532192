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
        }
    }
    last_ = odometry;
    lastTime_ = t;
}

}  // namespace mrloc::common
