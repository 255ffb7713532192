#pragma once
// The rigid transform (rotation and translation, no scale) that best puts 2-D points on
// others in the least-squares sense: Eigen::umeyama, in one place.
#include <Eigen/Core>

namespace mrloc::common {

/** T (3x3, homogeneous) minimising sum |T from_k - to_k|^2; from and to hold at least two
 *  points, column k of each paired. */
Eigen::Matrix3d rigidFit2D(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to);

}  // namespace mrloc::common
