#pragma once
// The beacon study's part of the run report (beacons.study.json -> tables and pictures).
#include <mrloc/beacons/BeaconStudyFile.h>
#include <mrloc/report/Html.h>

#include <string>

namespace mrloc::beacons {

/** The study's tables and pictures (written into `dir`), or nothing without a study file. */
report::Html studySection(const std::string& dir);

}  // namespace mrloc::beacons
