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

}  // namespace mrloc::report
