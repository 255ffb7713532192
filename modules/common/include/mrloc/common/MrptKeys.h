#pragma once
// The keys mrloc reads from MRPT's own INI sections, spelt once: the readers (beacons,
// polymap, the app's ground truth and advice) take their names from here, and the app's
// `mrloc keys mrpt` and its "did you mean" check of those sections list the same table
// (apps/mrloc/MrptSections.h), so a key a reader adds cannot be missing from the check.
#include <array>
#include <cstdio>
#include <string>

namespace mrloc::common::mrpt_ini {

struct Key {
    const char* section;
    const char* name;  ///< the key, or for a numbered family a pattern ("beacon_NNN_ID")
    const char* readBy;
};

inline constexpr Key kGroundTruthFile{"ro-localization", "groundTruthFile",
                                      "every method: the ground truth of the log"};
inline constexpr Key kRoRawlogFile{"ro-localization", "rawlog_file",
                                   "every method: the rawlog the ground truth is beside; "
                                   "the advice on an MRPT app's INI"};
inline constexpr Key kOdometryX{
    "OdometryEstimation", "odometry_X",
    "beacons: the start (with odometry_Y) when [beacons] start is absent; the truth's origin"};
inline constexpr Key kOdometryY{"OdometryEstimation", "odometry_Y",
                                "beacons: the start (with odometry_X)"};
inline constexpr Key kOdometryPhi{"OdometryEstimation", "odometry_PHI",
                                  "beacons: the start's heading (deg)"};
inline constexpr Key kBeaconRangesStd{
    "MetricMap_landmarksMap_00_likelihoodOpts", "beaconRangesStd",
    "beacons: the ranges' sigma (m) when [beacons] range_sigma is absent"};
inline constexpr Key kBeaconCount{"MetricMap_landmarksMap_00_creationOpts", "nBeacons",
                                  "beacons: the map, when [beacons] has no beacon_<id> keys"};
inline constexpr Key kBeaconId{"MetricMap_landmarksMap_00_creationOpts", "beacon_NNN_ID",
                               "beacons: beacon NNN's ID (NNN = 001 .. nBeacons)"};
inline constexpr Key kBeaconX{"MetricMap_landmarksMap_00_creationOpts", "beacon_NNN_x",
                              "beacons: beacon NNN's position (m), with _y and _z"};
inline constexpr Key kBeaconY{"MetricMap_landmarksMap_00_creationOpts", "beacon_NNN_y",
                              "beacons: beacon NNN's position (m)"};
inline constexpr Key kBeaconZ{"MetricMap_landmarksMap_00_creationOpts", "beacon_NNN_z",
                              "beacons: beacon NNN's position (m)"};
inline constexpr Key kMapFile{"LocalizationExperiment", "map_file",
                              "polymap: the .gridmap or .simplemap to localize in"};
inline constexpr Key kExperimentRawlogFile{"LocalizationExperiment", "rawlog_file",
                                           "the advice on an MRPT app's INI: its log"};
inline constexpr Key kInitMinX{"LocalizationExperiment", "init_PDF_min_x",
                               "polymap: the box searched for the start"};
inline constexpr Key kInitMaxX{"LocalizationExperiment", "init_PDF_max_x",
                               "polymap: the box searched for the start"};
inline constexpr Key kInitMinY{"LocalizationExperiment", "init_PDF_min_y",
                               "polymap: the box searched for the start"};
inline constexpr Key kInitMaxY{"LocalizationExperiment", "init_PDF_max_y",
                               "polymap: the box searched for the start"};
inline constexpr Key kGridResolution{"MetricMap_occupancyGrid_00_creationOpts", "resolution",
                                     "polymap: the grid a .simplemap is drawn into (m)"};
inline constexpr Key kMappingRawlogFile{"MappingApplication", "rawlog_file",
                                        "the advice on an MRPT SLAM app's INI: its log"};

/** Every key above, in the order `mrloc keys mrpt` lists them. */
inline constexpr std::array<Key, 19> kAll{
    kGroundTruthFile,      kRoRawlogFile, kOdometryX, kOdometryY, kOdometryPhi, kBeaconRangesStd,
    kBeaconCount,          kBeaconId,     kBeaconX,   kBeaconY,   kBeaconZ,     kMapFile,
    kExperimentRawlogFile, kInitMinX,     kInitMaxX,  kInitMinY,  kInitMaxY,    kGridResolution,
    kMappingRawlogFile};

/** A numbered family's key for number n: beacon_NNN_ID and 7 give "beacon_007_ID". */
inline std::string numbered(const Key& k, long n) {
    std::string key = k.name;
    const auto at = key.find("NNN");
    if (at == std::string::npos) return key;
    char digits[24];
    std::snprintf(digits, sizeof digits, "%03ld", n);
    return key.replace(at, 3, digits);
}

}  // namespace mrloc::common::mrpt_ini
