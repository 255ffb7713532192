#pragma once
// Ground truth as MRPT's apps find it, for a run whose INI names none of mrloc's own
// ([scenario] ground_truth): ro-localization's `groundTruthFile` when the log is the INI's own
// rawlog_file, else the `<rawlog stem>_GT.txt` MRPT's datasets put beside their rawlogs. The
// INI's start ([OdometryEstimation] odometry_X/Y/PHI) is the offset, as ro-localization starts
// its robot there and its truth at the origin.
#include <mrloc/common/GroundTruthFile.h>
#include <mrpt/config/CConfigFileBase.h>

#include <optional>
#include <string>

namespace mrloc::app {

struct FoundTruth {
    common::GroundTruthSource source;
    std::string from;  ///< in words, for metrics.json and the report
};

/** MRPT's ground truth for `rawlog`, or nullopt. `note` receives why a truth file the INI
 *  names was not used (it is for another log), if that is the case. */
std::optional<FoundTruth> mrptTruthOf(const mrpt::config::CConfigFileBase& ini,
                                      const std::string& iniPath, const std::string& rawlog,
                                      std::string& note);

}  // namespace mrloc::app
