#pragma once
// Odometry from velocities: datasets that log wheel speeds or velocity commands (libRSF's
// odom2diff, MRCLAM's odometry) give no pose; the importer integrates one.
#include <mrpt/poses/CPose2D.h>

namespace mrloc::logimport {

/** The pose after moving at constant forward speed v (m/s), lateral speed vy and turn rate w
 *  (rad/s) for dt seconds from `from`: the exact arc (a constant twist), not Euler's step,
 *  so that the integrated path does not depend on the log's rate. */
mrpt::poses::CPose2D moveArc(const mrpt::poses::CPose2D& from, double v, double vy, double w,
                             double dt);

}  // namespace mrloc::logimport
