#include "MrptSections.h"

#include <mrloc/common/Names.h>

#include <map>

namespace mrloc::app {

const std::vector<MrptKey>& mrptKeysRead() {
    static const std::vector<MrptKey> table{
        {"ro-localization", "groundTruthFile", "every method: the ground truth of the log"},
        {"ro-localization", "rawlog_file", "every method: the rawlog the ground truth is beside"},
        {"OdometryEstimation", "odometry_X",
         "beacons: the start (with odometry_Y) when [beacons] start is absent; the truth's origin"},
        {"OdometryEstimation", "odometry_Y", "beacons: the start (with odometry_X)"},
        {"OdometryEstimation", "odometry_PHI", "beacons: the start's heading (deg)"},
        {"MetricMap_landmarksMap_00_likelihoodOpts", "beaconRangesStd",
         "beacons: the ranges' sigma (m) when [beacons] range_sigma is absent"},
        {"LocalizationExperiment", "map_file",
         "polymap: the .gridmap or .simplemap to localize in"},
        {"LocalizationExperiment", "init_PDF_min_x", "polymap: the box searched for the start"},
        {"LocalizationExperiment", "init_PDF_max_x", "polymap: the box searched for the start"},
        {"LocalizationExperiment", "init_PDF_min_y", "polymap: the box searched for the start"},
        {"LocalizationExperiment", "init_PDF_max_y", "polymap: the box searched for the start"},
        {"MetricMap_occupancyGrid_00_creationOpts", "resolution",
         "polymap: the grid a .simplemap is drawn into (m)"},
    };
    return table;
}

std::vector<std::string> mrptKeyWarnings(const mrpt::config::CConfigFileBase& ini,
                                         const std::string& iniPath) {
    std::map<std::string, std::vector<std::string>> read;  // section -> keys mrloc reads
    for (const auto& k : mrptKeysRead()) read[k.section].push_back(k.key);
    std::vector<std::string> warnings;
    for (const auto& [section, keys] : read) {
        if (!ini.sectionExists(section)) continue;
        std::vector<std::string> present;
        ini.getAllKeys(section, present);
        for (const auto& key : present) {
            bool known = false;
            for (const auto& k : keys) known = known || k == key;
            if (known) continue;
            if (const auto near = common::nearMiss(key, keys))
                warnings.push_back(
                    iniPath + ": [" + section + "] " + common::printable(key) +
                    ": not a key mrloc reads, so its default is used (did you mean " + *near +
                    "? mrloc keys mrpt lists what mrloc reads here)");
        }
    }
    return warnings;
}

std::string mrptKeysText() {
    std::string out =
        "Keys mrloc reads from MRPT's sections (the rest of those sections belong to MRPT's\n"
        "apps, pf-localization and ro-localization, and mrloc leaves them to them; a key within\n"
        "an edit or two of one below is a warning with \"did you mean\"):\n";
    std::string section;
    for (const auto& k : mrptKeysRead()) {
        if (k.section != section) out += "[" + (section = k.section) + "]\n";
        out += "  " + k.key + std::string(k.key.size() < 18 ? 18 - k.key.size() : 1, ' ') +
               k.readBy + "\n";
    }
    return out;
}

}  // namespace mrloc::app
