#pragma once
// The layout of out/<run>/, written by `mrloc localize` and read by `mrloc report`:
//   effective.ini            the configuration actually used (defaults filled in)
//   metrics.json             method, n, rmse_m, mean_m, max_m, wall_s, per robot, method figures
//   estimates.<robot>.txt    TUM format
//   groundtruth.<robot>.txt  copy of the rawlog's ground truth, when it has one
//   report.html, *.png       written by `mrloc report`
#include <string>

namespace mrloc::common::run_dir {

inline std::string effectiveIni(const std::string& d) { return d + "/effective.ini"; }
inline std::string metrics(const std::string& d) { return d + "/metrics.json"; }
inline std::string estimates(const std::string& d, const std::string& robot) {
    return d + "/estimates." + robot + ".txt";
}
inline std::string groundTruth(const std::string& d, const std::string& robot) {
    return d + "/groundtruth." + robot + ".txt";
}
inline std::string report(const std::string& d) { return d + "/report.html"; }

}  // namespace mrloc::common::run_dir
