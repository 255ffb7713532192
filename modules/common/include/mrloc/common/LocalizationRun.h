#pragma once
// Plays a rawlog through a Localizer and writes the run directory (see RunDirectory.h):
// estimates, ground truth copies, errors against it, metrics.json and effective.ini.
#include <mrloc/common/Localizer.h>
#include <mrpt/config/CConfigFileBase.h>

#include <nlohmann/json.hpp>
#include <string>

namespace mrloc::common {

struct LocalizationRunOptions {
    std::string methodName;
    std::string rawlogPath;
    std::string outDir;
    bool quiet = false;
};

/** `effective` holds the options of everything else in the run (scenario, world...); the
 *  localizer's own are added. Returns the metrics written. */
nlohmann::json runLocalization(Localizer& localizer, const LocalizationRunOptions& options,
                               const mrpt::config::CConfigFileBase& effective);

}  // namespace mrloc::common
