#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/MrptKeys.h>
#include <mrpt/core/format.h>
#include <mrpt/system/string_utils.h>

#include <cstdlib>

namespace mrloc::beacons {

using common::configOrigin;

BeaconMap readBeaconKeys(IniSection& section) {
    BeaconMap map;
    for (const auto& [id, key] : section.numberedKeys("beacon_")) {
        const auto xyz = section.reals(key, {}, 3);
        map[id] = {xyz[0], xyz[1], xyz[2]};
    }
    return map;
}

BeaconMap readMrptLandmarksMap(const mrpt::config::CConfigFileBase& cfg, const std::string& name) {
    BeaconMap map;
    if (!cfg.sectionExists(name)) return map;
    IniSection sec(cfg, name);
    namespace k = common::mrpt_ini;
    const long n = sec.integer(k::kBeaconCount.name, 0, 0, 100000);
    for (long q = 1; q <= n; ++q) {
        const std::string idKey = k::numbered(k::kBeaconId, q), xKey = k::numbered(k::kBeaconX, q),
                          yKey = k::numbered(k::kBeaconY, q), zKey = k::numbered(k::kBeaconZ, q);
        for (const auto& key : {idKey, xKey, yKey, zKey})
            if (!sec.has(key)) sec.fail(key, "missing (nBeacons = " + std::to_string(n) + ")");
        const int id = int(sec.integer(idKey, 0, 0, 1L << 30));
        if (map.count(id)) sec.fail(idKey, "beacon ID " + std::to_string(id) + " appears twice");
        map[id] = {sec.real(xKey, 0), sec.real(yKey, 0), sec.real(zKey, 0)};
    }
    return map;
}

BeaconMap loadBeaconMap(const mrpt::config::CConfigFileBase& cfg, IniSection& beacons) {
    BeaconMap map = readBeaconKeys(beacons);
    if (map.empty()) map = readMrptLandmarksMap(cfg);
    if (map.empty())
        throw Error(configOrigin(cfg) + ": no beacons: give beacon_<id> = x y z keys in [" +
                    beacons.section() + "] or MRPT's [" + kMrptLandmarksSection + "] keys");
    return map;
}

void saveBeaconKeys(const BeaconMap& map, mrpt::config::CConfigFileBase& target,
                    const std::string& section) {
    for (const auto& [id, p] : map)
        target.write(section, "beacon_" + std::to_string(id),
                     mrpt::format("%.4f %.4f %.4f", p.x, p.y, p.z));
}

}  // namespace mrloc::beacons
