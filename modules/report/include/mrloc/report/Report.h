#pragma once
// `mrloc report <run-dir>`: the page framework. It reads what `mrloc localize` wrote and
// renders report.html: provenance on top (INI, seed, mrloc version, command line), the
// metrics in tables with heads in words and units, the top view (unless the method draws
// its own picture), the error plots, and the method's registered section.
#include <mrloc/common/Localizer.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/report/Html.h>
#include <mrloc/report/TopView.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace mrloc::report {

/** What the framework read from a run directory; a method's section reads its own files. */
struct RunView {
    std::string dir;
    nlohmann::json metrics;
    std::shared_ptr<mrpt::config::CConfigFileMemory>
        effective;                   ///< effective.ini (empty if absent)
    common::Trajectories estimates;  ///< per robot
    common::Trajectories truth;      ///< groundtruth.<robot>.txt, estimates' frame
};

/** A method's part of the report. */
struct Section {
    /** What the method is, in a few words with its paper ("active ultrasonic beacons,
     *  seed 001"): the page's title after the scenario's name, and its "what ran" row. */
    std::string subject;
    /** The section, built from report::Html's nodes (so escaped by construction); it may
     *  render pictures into the run directory. */
    std::function<Html(const RunView&)> html;
    /** Adds the method's static points (beacons...) to the world top view. Unset: the method
     *  draws its own picture in html() and the page has no top view. */
    std::function<void(const RunView&, TopViewContent&)> topView;
};

/** Returns the path of report.html. Throws mrloc::Error if runDir is not a run directory. */
std::string makeReport(const std::string& runDir, const Section& section);

/** A metrics key in words with its unit: "max_distance_between_fixes_m" -> "max distance
 *  between fixes (m)", "p95_m" -> "95th percentile (m)". */
std::string keyInWords(const std::string& key);
/** A metrics.json value as a table cell: null "none", booleans "yes"/"no", numbers to 4
 *  significant digits, arrays comma-separated. */
std::string cellText(const nlohmann::json& value);
/** A headline figure as four cells: its name (bold, or marked as a baseline), its value with
 *  its unit, the paper's figure, and how this run's experiment differs from the paper's (the
 *  report's headline table and the tour's index share them). */
std::vector<Html> figureCells(const common::HeadlineFigure& figure);
/** A two-column table of the object's scalar members, keys in words; null reads "none". */
Html metricsTable(const nlohmann::json& object);

}  // namespace mrloc::report
