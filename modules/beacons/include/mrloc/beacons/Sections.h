#pragma once
// Sections (seed 001 section 2.1): the floor is split into rectangles, each covered by its
// own beacon set with one RF beacon. Read from [beacons]:
//   section_<name>         = xmin ymin xmax ymax      (m)
//   section_<name>_beacons = <rf id> <id> ...          (the RF beacon first)
//   section_<name>_aim     = x y z                     (where fixed heads point; default:
//                                                       the rectangle's centre on the floor)
// Without section keys there is one section, "all", holding every beacon of the map.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/common/IniSection.h>
#include <mrpt/math/TPoint2D.h>

#include <string>
#include <vector>

namespace mrloc::beacons {

struct Section {
    std::string name;
    mrpt::math::TPoint2D min, max;  ///< the rectangle it covers
    std::vector<int> beacons;       ///< firing order; the RF beacon first
    mrpt::math::TPoint3D aim;       ///< where its heads point when fixed

    /** 0 inside the rectangle, else the distance to it. */
    double distanceTo(const mrpt::math::TPoint2D& p) const;
};

class SectionMap {
 public:
    SectionMap() = default;
    explicit SectionMap(std::vector<Section> sections) : sections_(std::move(sections)) {}
    const std::vector<Section>& sections() const { return sections_; }
    size_t size() const { return sections_.size(); }
    const Section& operator[](size_t i) const { return sections_[i]; }
    /** The section containing p or, outside all of them, the nearest (first wins ties). */
    size_t at(const mrpt::math::TPoint2D& p) const;

 private:
    std::vector<Section> sections_;
};

/** Reads the section keys of [beacons]; errors name the key. */
SectionMap readSections(common::IniSection& s, const BeaconMap& map);
void saveSections(const SectionMap& sections, mrpt::config::CConfigFileBase& target,
                  const std::string& section);

}  // namespace mrloc::beacons
