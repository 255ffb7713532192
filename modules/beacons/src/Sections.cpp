#include <mrloc/beacons/Sections.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/core/format.h>
#include <mrpt/system/string_utils.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace mrloc::beacons {

namespace {
bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

double Section::distanceTo(const mrpt::math::TPoint2D& p) const {
    const double dx = std::max({min.x - p.x, 0.0, p.x - max.x});
    const double dy = std::max({min.y - p.y, 0.0, p.y - max.y});
    return std::hypot(dx, dy);
}

size_t SectionMap::at(const mrpt::math::TPoint2D& p) const {
    size_t best = 0;
    for (size_t i = 1; i < sections_.size(); ++i)
        if (sections_[i].distanceTo(p) < sections_[best].distanceTo(p)) best = i;
    return best;
}

SectionMap readSections(common::IniSection& s, const BeaconMap& map) {
    const std::string prefix = "section_";
    s.allowPrefix(prefix);
    std::set<std::string> names;
    for (const auto& key : s.keys()) {
        const std::string k = mrpt::system::lowerCase(key);
        if (k.rfind(prefix, 0) != 0 || endsWith(k, "_beacons") || endsWith(k, "_aim")) continue;
        names.insert(k.substr(prefix.size()));
    }
    for (const auto& key : s.keys()) {  // an attribute of a section that has no rectangle
        const std::string k = mrpt::system::lowerCase(key);
        if (k.rfind(prefix, 0) != 0) continue;
        for (const std::string tail : {"_beacons", "_aim"})
            if (endsWith(k, tail) &&
                !names.count(k.substr(prefix.size(), k.size() - prefix.size() - tail.size())))
                s.fail(key, "no matching section_<name> = xmin ymin xmax ymax");
    }
    std::vector<Section> sections;
    for (const auto& name : names) {
        Section sec;
        sec.name = name;
        const std::string key = prefix + name;
        const auto r = s.reals(key, {}, 4);
        if (!(r[2] > r[0] && r[3] > r[1]))
            s.fail(key, "expected xmin ymin xmax ymax with xmax > xmin and ymax > ymin");
        sec.min = {r[0], r[1]};
        sec.max = {r[2], r[3]};
        if (!s.has(key + "_beacons")) s.fail(key + "_beacons", "required for section " + name);
        for (double id : s.reals(key + "_beacons", {})) {
            // a whole number within int's range before it is one (1e112 is not a beacon)
            if (id != std::floor(id) || std::abs(id) > 1e9 || !map.count(int(id)))
                s.fail(key + "_beacons", mrpt::format("beacon %g is not in the beacon map", id));
            sec.beacons.push_back(int(id));
        }
        if (sec.beacons.empty()) s.fail(key + "_beacons", "lists no beacon");
        const auto aim = s.reals(key + "_aim", {(r[0] + r[2]) / 2, (r[1] + r[3]) / 2, 0.0}, 3);
        sec.aim = {aim[0], aim[1], aim[2]};
        sections.push_back(sec);
    }
    if (sections.empty()) {  // one section over everything
        Section all;
        all.name = "all";
        double n = 0;
        all.min = {map.begin()->second.x, map.begin()->second.y};
        all.max = all.min;
        for (const auto& [id, p] : map) {
            all.beacons.push_back(id);
            all.min = {std::min(all.min.x, p.x), std::min(all.min.y, p.y)};
            all.max = {std::max(all.max.x, p.x), std::max(all.max.y, p.y)};
            all.aim.x += p.x;
            all.aim.y += p.y;
            ++n;
        }
        all.aim = {all.aim.x / n, all.aim.y / n, 0.0};
        sections.push_back(all);
    }
    return SectionMap(std::move(sections));
}

void saveSections(const SectionMap& sections, mrpt::config::CConfigFileBase& t,
                  const std::string& section) {
    for (const auto& s : sections.sections()) {
        if (s.name == "all" && sections.size() == 1) return;  // the implicit one
        const std::string key = "section_" + s.name;
        t.write(section, key, common::keyListText({s.min.x, s.min.y, s.max.x, s.max.y}));
        std::string ids;
        for (int id : s.beacons) ids += (ids.empty() ? "" : " ") + std::to_string(id);
        t.write(section, key + "_beacons", ids);
        t.write(section, key + "_aim", common::keyListText({s.aim.x, s.aim.y, s.aim.z}));
    }
}

}  // namespace mrloc::beacons
