#pragma once
// One degree in radians, for tests that write angles in degrees (one definition, so that a
// test folder's files can be compiled together).
#include <cmath>

namespace mrloc::testing_angles {
inline constexpr double kDeg = M_PI / 180;
}  // namespace mrloc::testing_angles
