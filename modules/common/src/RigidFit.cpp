#include <mrloc/common/RigidFit.h>

#include <Eigen/Geometry>

namespace mrloc::common {

// Compiled without GCC 12's -Wstringop-overread (modules/common/CMakeLists.txt): a false
// positive inside Eigen::umeyama's vectorized copy of a 2-vector into its 3x3 result.
Eigen::Matrix3d rigidFit2D(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to) {
    return Eigen::umeyama(from, to, false);
}

}  // namespace mrloc::common
