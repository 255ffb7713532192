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
#include <mrloc/common/MrptKeys.h>
#include <mrpt/math/TPoint3D.h>

#include <map>
#include <string>

namespace mrloc::beacons {

using common::IniSection;

/** A beacon's position. MRPT packs TPoint3D to 1-byte alignment, so in a std::map<int,
 *  TPoint3D> its doubles sit at offset 4 of the node and every read of them is a misaligned
 *  load (undefined behaviour, fatal under UBSan). This keeps the doubles 8-byte aligned and
 *  converts to TPoint3D wherever MRPT wants one. */
struct alignas(alignof(double)) BeaconPosition : mrpt::math::TPoint3D {
    using mrpt::math::TPoint3D::TPoint3D;
    BeaconPosition() = default;
    BeaconPosition(const mrpt::math::TPoint3D& p) : mrpt::math::TPoint3D(p) {}
};

using BeaconMap = std::map<int, BeaconPosition>;  ///< beacon ID -> position

inline constexpr const char* kMrptLandmarksSection = common::mrpt_ini::kBeaconCount.section;

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
