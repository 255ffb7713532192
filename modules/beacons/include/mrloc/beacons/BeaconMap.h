#pragma once
// Known 3-D beacon positions, shared by the simulator (the truth it simulates) and the
// beacon localizer (the map it localizes against).
//
// Two INI forms are read:
//  - ours, in [beacons]:      beacon_<id> = x y z      (metres)
//  - MRPT's landmarks map, as pf-localization / ro-localization INIs write it:
//      [MetricMap_landmarksMap_00_creationOpts]
//      nBeacons = 3
//      beacon_001_ID = 0
//      beacon_001_x = 1.0   beacon_001_y = 2.0   beacon_001_z = 2.5
// MRPT's own parser defaults a missing key to 0; this one stops with an error naming it.
#include <mrloc/common/IniSection.h>
#include <mrpt/math/TPoint3D.h>

#include <map>
#include <string>

namespace mrloc::beacons {

using common::IniSection;

using BeaconMap = std::map<int, mrpt::math::TPoint3D>;  ///< beacon ID -> position

inline constexpr const char* kMrptLandmarksSection = "MetricMap_landmarksMap_00_creationOpts";

/** Reads beacon_<id> keys of `section` (and marks the prefix as allowed). */
BeaconMap readBeaconKeys(IniSection& section);
/** Reads MRPT's landmarks-map creation options; empty if the section is absent. */
BeaconMap readMrptLandmarksMap(const mrpt::config::CConfigFileBase& cfg,
                               const std::string& section = kMrptLandmarksSection);
/** Ours if [beacons] has beacon_<id> keys, else MRPT's; throws if neither has a beacon. */
BeaconMap loadBeaconMap(const mrpt::config::CConfigFileBase& cfg, IniSection& beaconsSection);

/** Writes the map as beacon_<id> keys. */
void saveBeaconKeys(const BeaconMap& map, mrpt::config::CConfigFileBase& target,
                    const std::string& section);

}  // namespace mrloc::beacons
