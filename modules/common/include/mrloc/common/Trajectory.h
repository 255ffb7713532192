#pragma once
// Time-stamped poses and their text form: the TUM format, one pose per line,
// "t x y z qx qy qz qw", '#' comments. Ground truth and estimates share it.
#include <mrpt/core/Clock.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/CQuaternion.h>
#include <mrpt/poses/CPose3D.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

/** Seconds since 1970 of an MRPT time stamp, negative before it. mrpt::Clock::toDouble
 *  computes in unsigned ticks: a stamp before 1970 (-5 s) comes out 1.8e12 s, and a check
 *  "before 1970" on it never fired (negative stamps reached a report as 1.8e12 s). */
double stampSeconds(mrpt::Clock::time_point stamp);

/** One time rule for import, localize and every output (doc/import.md#time): a stamp is
 *  seconds since 1970-01-01 00:00 UTC, MRPT's epoch. A log whose clock starts at 0 (most
 *  datasets: seconds from the start of the recording) keeps its numbers: in the rawlog it is
 *  that many seconds after 1970, and it is shown as relative time. Stamps before this limit
 *  (3 March 1973) are read as such a relative clock. */
constexpr double kRelativeClockLimit = 1e8;
inline bool isRelativeTime(double seconds) { return seconds >= 0 && seconds < kRelativeClockLimit; }
/** A time as a user reads it: a UTC date, "t = 12.500 s (relative clock)", or "before 1970". */
std::string timeInWords(double seconds);

struct StampedPose {
    double t = 0;  ///< seconds since 1970 (stampSeconds of the observation's stamp)
    mrpt::poses::CPose3D pose;
};

using Trajectory = std::vector<StampedPose>;

/** An estimate's covariance (MRPT's CPosePDFGaussian: x, y, phi; m, rad), at its time. */
struct StampedCovariance {
    double t = 0;
    mrpt::math::CMatrixDouble33 cov;
};
using CovarianceTrack = std::vector<StampedCovariance>;

/** covariance.<robot>.txt: "t xx xy xphi yy yphi phiphi" (the upper triangle, m^2, m rad,
 *  rad^2; "nan" where the method does not estimate a term), one line per estimate, at the
 *  estimates' times. Written atomically; read back exactly (17 digits). */
void saveCovariances(const std::string& path, const CovarianceTrack& track);
CovarianceTrack loadCovariances(const std::string& path);

/** Where a trajectory comes in (a TUM file, MRPT's ground truth formats, an importer's
 *  truth), its values are bounded here, in one place (doc/errors.md, "Trajectories"). */
struct TrajectoryLimits {
    static constexpr double kMaxCoordinate = 1e6;  ///< m: as an odometry pose (ObservationCheck)
    static constexpr double kMaxTime = 1e11;       ///< s from 1970, either way (year 5138)
    static constexpr size_t kMaxPoses = 2000000;   ///< a file's: 5.5 h at 100 Hz
    static constexpr size_t kMaxBytes = 256u << 20;  ///< a TUM file's (2 M lines of 128 bytes)
};

/** Throws mrloc::Error "<where>: ..." unless the time and position are finite and within
 *  TrajectoryLimits: a truth of 1e19 m would be an "RMSE" of 1e17 m. */
void checkTrajectoryPose(double t, double x, double y, double z, const std::string& where);

/** (w, x, y, z) of any scale, finite, as a unit quaternion: MRPT's CQuaternion refuses one off
 *  unit norm in its own words. Scaled by its largest component first, so that 1e300 does not
 *  overflow. nullopt when it is zero or its norm is under `minNorm`. */
std::optional<mrpt::math::CQuaternionDouble> unitQuaternion(double w, double x, double y,
                                                            double z, double minNorm);

/** Writes atomically; times with 9 decimals, positions with 6 (micrometres). */
void saveTum(const std::string& path, const Trajectory& traj);
/** Reads a TUM file; errors name the file and line. Times must not decrease; times,
 *  positions, the file's size and its poses are bounded (TrajectoryLimits). */
Trajectory loadTum(const std::string& path);

/** Pose at time t by linear interpolation of the position (and yaw); nullopt outside the
 *  covered span. Used to compare estimates with ground truth at the estimates' times. */
std::optional<mrpt::poses::CPose3D> interpolate(const Trajectory& traj, double t);
/** The pose at t between two stamped poses (a.t < t < b.t): the position linearly, the yaw
 *  along the shorter arc, pitch and roll a's. interpolate's rule, and common::evaluate's. */
mrpt::poses::CPose3D interpolateBetween(const StampedPose& a, const StampedPose& b, double t);
/** A pose known at one instant t0, carried on by a robot's odometry: `pose` at t0, then at
 *  each odometry reading after t0 (by more than 1 us) pose (+) odometry(t0)^-1 (+)
 *  odometry(t), the odometry at t0 interpolated. Only `pose` when the odometry does not
 *  reach t0 (or there is none). How a method that solves one instant (omnivision's layout,
 *  polymap's start) gives estimates over the rest of the log. */
Trajectory carriedByOdometry(const mrpt::poses::CPose3D& pose, double t0,
                             const Trajectory& odometry);

/** Where a baseline starts: the truth's pose at t. A truth of positions only (every
 *  orientation the identity while the path moves: libRSF's point2, TUM files written without
 *  a heading) gives no heading, so the direction of its first 0.3 m of motion after t stands
 *  in for it, as a user would set a start. nullopt outside the truth's span. */
std::optional<mrpt::poses::CPose3D> startPoseOf(const Trajectory& truth, double t);

/** Ground-truth file of a robot beside a rawlog: "x.rawlog" -> "x.<robot>.gt.txt". */
std::string groundTruthPath(const std::string& rawlogPath, const std::string& robot);

}  // namespace mrloc::common
