#pragma once
// `mrloc report <run-dir>`: reads what `mrloc localize` wrote and renders topview.png,
// error_time.png, error_cdf.png and report.html (the metrics table and the pictures).
#include <string>

namespace mrloc::report {

/** Returns the path of report.html. Throws mrloc::Error if runDir is not a run directory. */
std::string makeReport(const std::string& runDir);

}  // namespace mrloc::report
