#pragma once
// Ground truth from a file named in the INI, in the formats MRPT's datasets use besides TUM:
//   tum                    "t x y z qx qy qz qw" (mrloc's own)
//   index_x_y_phi          "i x y phi": pose of the i-th step (MRPT's *_GT.txt of
//                          range-only demos), phi in rad
//   x_y_z_yaw_pitch_roll   one row per step, "x y z yaw pitch roll" in m and rad (MRPT's
//                          *_ground_truth_robot_path.txt)
// Rows of a step-indexed format take the time of the robot's step-th odometry reading (an
// actions + sensory-frames rawlog has one per step): that is the time base. A frame offset
// `x y phi_deg` puts the file's frame in the estimates' frame: pose = offset (+) row.
#include <mrloc/common/Trajectory.h>
#include <mrpt/poses/CPose3D.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

struct GroundTruthSource {
    std::string path;  ///< empty: none (then <rawlog stem>.<robot>.gt.txt, as before)
    std::string format = "tum";
    std::string robot = "robot";
    mrpt::poses::CPose3D offset;

    static const std::vector<std::string>& formats();
};

/** Reads the file; `stepTimes` are the robot's odometry reading times, the time base of
 *  the step-indexed formats. Rows past the last step are left out. Throws mrloc::Error
 *  naming the file and line. */
Trajectory loadGroundTruth(const GroundTruthSource& source, const std::vector<double>& stepTimes);

/** The step-indexed or TUM format of a truth file, by the columns of its first row:
 *  4 "i x y phi", 6 "x y z yaw pitch roll", 8 TUM. nullopt for anything else. */
std::optional<std::string> groundTruthFormatOf(const std::string& path);

}  // namespace mrloc::common
