#pragma once
// The layout of out/<run>/, written by `mrloc simulate` / `localize` and read by `report`:
//   <name>.rawlog, <name>.<robot>.gt.txt   the simulated rawlog and its ground truth
//   config.ini               a copy of the INI the run was started with
//   effective.ini            the configuration actually used (defaults filled in)
//   provenance.json          INI, seed, mrloc version and command line of each step
//   metrics.json             method, errors (n, rmse_m, ...), per robot, method figures
//   estimates.<robot>.txt    TUM format
//   groundtruth.<robot>.txt  the rawlog's ground truth in the estimates' frame
//   odometry.<robot>.txt     the robot's odometry alone (dead reckoning), TUM, as read
//   covariance.<robot>.txt   each estimate's covariance, when the method has one
//   report.html, *.png       written by `mrloc report`
// plus the files each method writes for its report section (defined in the method).
#include <string>

namespace mrloc::common::run_dir {

inline std::string configCopy(const std::string& d) { return d + "/config.ini"; }
inline std::string effectiveIni(const std::string& d) { return d + "/effective.ini"; }
inline std::string provenance(const std::string& d) { return d + "/provenance.json"; }
inline std::string metrics(const std::string& d) { return d + "/metrics.json"; }
inline std::string estimates(const std::string& d, const std::string& robot) {
    return d + "/estimates." + robot + ".txt";
}
inline std::string groundTruth(const std::string& d, const std::string& robot) {
    return d + "/groundtruth." + robot + ".txt";
}
inline std::string odometry(const std::string& d, const std::string& robot) {
    return d + "/odometry." + robot + ".txt";
}
inline std::string covariance(const std::string& d, const std::string& robot) {
    return d + "/covariance." + robot + ".txt";
}
inline std::string report(const std::string& d) { return d + "/report.html"; }

}  // namespace mrloc::common::run_dir
