#pragma once
// The pictures of an evaluation on the truth's timeline (common::evaluate, doc/evaluation.md),
// drawn by gnuplot as every plot of mrloc: the error over time with the stretches the
// estimates do not cover shaded and odometry alone on the same axes; x, y and heading over
// time, truth and estimate; the path seen from above coloured by the error, with covariance
// ellipses where the localizer gives them; the CDF of the error over the covered stamps.
// The report and `mrloc eval --out` draw the same ones.
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/Trajectory.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::report {

/** One robot's evaluation and what its pictures draw beside it. */
struct EvaluatedTrack {
    std::string name;  ///< the robot, as the legends show it
    common::Evaluation estimate;
    std::optional<common::Evaluation> odometry;  ///< odometry alone, on its truth's timeline
    common::Trajectory truth;                    ///< the whole truth (the top view's grey path)
    common::CovarianceTrack covariances;         ///< the estimate's, if the localizer gives any
};

/** Position error against time since the truth's first stamp, one colour per robot, odometry
 *  alone dashed in the same colour; the uncovered stretches shaded full height for one robot,
 *  as a band in the robot's colour along the bottom for several. */
void plotTruthTimelineError(const std::vector<EvaluatedTrack>& tracks, const std::string& pngPath);
/** The CDF of the position error over every covered stamp, per robot (odometry dashed). */
void plotTruthTimelineCdf(const std::vector<EvaluatedTrack>& tracks, const std::string& pngPath);
/** x, y and heading against time, the truth and the estimate at the covered stamps, the
 *  uncovered stretches shaded: three panels, one robot. */
void plotPoseOverTime(const EvaluatedTrack& track, const std::string& pngPath);
/** The robot's path from above (m, equal scales): the truth grey, the estimate coloured by
 *  its position error at each covered stamp (colour bar in m), 2-sigma covariance ellipses
 *  of the estimate's position (at most about 40 of them, evenly spread). */
void plotErrorTopView(const EvaluatedTrack& track, const std::string& pngPath);

/** The 2-sigma ellipse of a position covariance (x, y block): full axes (m) and the major
 *  axis' angle (deg), as gnuplot's `with ellipses` takes them; nullopt when the block is not
 *  a finite covariance. */
struct Ellipse {
    double major = 0, minor = 0, angleDeg = 0;
};
std::optional<Ellipse> twoSigmaEllipse(const mrpt::math::CMatrixDouble33& cov);

}  // namespace mrloc::report
