#pragma once
// Plots drawn by gnuplot (pngcairo): error over time and the error CDF, one curve per robot.
#include <mrloc/common/Metrics.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::report {

using RobotErrors = std::map<std::string, std::vector<common::TimedError>>;

void plotErrorOverTime(const RobotErrors& errors, const std::string& pngPath);
void plotErrorCdf(const RobotErrors& errors, const std::string& pngPath);

/** One robot of a relative layout (seed 000): the paper's position, the refined one with
 *  its covariance, and the truth, all in the layout's frame. NaN where unknown. */
struct LayoutPoint {
    std::string robot;
    double paperX, paperY, refinedX, refinedY, cxx, cxy, cyy, trueX, trueY;
};
/** True and recovered layouts, with 3-sigma ellipses of the refined positions. */
void plotLayout(const std::vector<LayoutPoint>& points, const std::string& title,
                const std::string& pngPath);

/** Rows of an accuracy sweep: axis ("angle" or "distance"), angle sigma (deg), distance
 *  sigma (relative), median relative distance error of the paper's and the refined
 *  solution. Two panels: against the angle noise and against the distance noise. */
struct AccuracyRow {
    std::string axis;
    double angleSigmaDeg, distanceSigma, paper, refined;
};
void plotAccuracy(const std::vector<AccuracyRow>& rows, const std::string& distanceName,
                  const std::string& pngPath);

}  // namespace mrloc::report
