#include <mrloc/common/IniSection.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrloc::omnivision {

namespace {

using Pairs = std::vector<std::pair<std::string, std::string>>;

/** "A B, C D": the INI's text of a list of pairs. */
std::string pairsText(const Pairs& pairs) {
    std::string list;
    for (const auto& [a, b] : pairs) list += (list.empty() ? "" : ", ") + a + " " + b;
    return list;
}

Pairs parsePairs(common::IniSection& s, const std::string& key, const Pairs& def) {
    Pairs out;
    std::stringstream list(s.text(key, pairsText(def)));
    for (std::string item; std::getline(list, item, ',');) {
        std::istringstream in(item);
        std::string a, b, extra;
        if (!(in >> a >> b) || (in >> extra) || a == b)
            s.fail(key, "expected pairs of two different robots 'A B, C D', got '" + item + "'");
        out.push_back({a, b});
    }
    return out;
}

}  // namespace

void OmniOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                     const std::string& section) {
    *this = OmniOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    method = s.choice("method", "proposed", {"proposed", "conventional"});
    pairs = parsePairs(s, "pairs", pairs);
    if (pairs.empty()) s.fail("pairs", "at least one pair of robots to stop");
    tb = s.real("t_b", tb, 0, 1e6);
    te = s.real("t_e", te, 0, 1e6);
    if (te <= tb) s.fail("t_e", mrpt::format("must be after t_b (%g)", tb));
    roundPeriod = s.real("round_period", roundPeriod, 0, 1e6);
    localizedSearch = s.choice("search_at_tb", "full", {"full", "localized"}) == "localized";
    if (pairs.size() > 1 && roundPeriod <= te - tb)
        s.fail("round_period", "must exceed t_e - t_b when several pairs are listed");
    const auto measured = parsePairs(s, "measured_pair", {measuredPair});
    if (measured.size() != 1) s.fail("measured_pair", "exactly one pair");
    measuredPair = measured[0];
    snapshot = s.real("snapshot", snapshot, 0, 1e6);
    lidarSigma = s.real("lidar_sigma", lidarSigma, 0, 10);
    render = s.choice("camera", "render", {"render", "bearings"}) == "render";
    panorama.views = int(s.integer("views", long(panorama.views), 3, 12));
    panorama.viewWidth = int(s.integer("view_width", long(panorama.viewWidth), 32, 8192));
    if (panorama.viewWidth % 4 != 0)  // the renderer reads rows of whole 4-byte words: an
        s.fail("view_width", "a multiple of 4 px");  // odd width overran the picture
    panorama.height = int(s.integer("view_height", long(panorama.height), 8, 4096));
    bearingSigma = s.real("bearing_sigma", bearingSigma, 0, 10);
    maxRange = s.real("max_range", maxRange, 0, 1e6);
    markerRadius = s.real("marker_radius", markerRadius, 1e-3, 10);
    markerHeight = s.real("marker_height", markerHeight, 1e-3, 10);
    cameraHeight = s.real("camera_height", cameraHeight, 0, 100);
    sumTolerance = s.real("sum_tolerance", sumTolerance, 0, 30);
    bearingTolerance = s.real("bearing_tolerance", bearingTolerance, 0, 30);
    odometerSigma = s.real("odometer_sigma", odometerSigma, 1e-6, 1);
    refine = s.flag("refine", refine);
    swarm = int(s.integer("swarm", long(swarm), 0, 1000));
    if (swarm > 0 && swarm < 3) s.fail("swarm", "a swarm has at least 3 robots (0: none)");
    swarmArea = s.real("swarm_area", swarmArea, 1, 1e4);
    swarmSpeed = s.real("swarm_speed", swarmSpeed, 0, 10);
    swarmSeparation = s.real("swarm_separation", swarmSeparation, 0, 100);
    swarmSeed = common::subSeed(s, "swarm_seed", common::runSeed(src), "omnivision swarm");
    accuracyTrials = int(s.integer("accuracy_trials", long(accuracyTrials), 0, 100000));
    s.finish();
}

void OmniOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                   const std::string& section) const {
    t.write(section, "method", method);
    t.write(section, "pairs", pairsText(pairs));
    t.write(section, "t_b", tb);
    t.write(section, "t_e", te);
    t.write(section, "round_period", roundPeriod);
    t.write(section, "search_at_tb", std::string(localizedSearch ? "localized" : "full"));
    t.write(section, "measured_pair", measuredPair.first + " " + measuredPair.second);
    t.write(section, "snapshot", snapshot);
    t.write(section, "lidar_sigma", lidarSigma);
    t.write(section, "camera", std::string(render ? "render" : "bearings"));
    t.write(section, "views", panorama.views);
    t.write(section, "view_width", panorama.viewWidth);
    t.write(section, "view_height", panorama.height);
    t.write(section, "bearing_sigma", bearingSigma);
    t.write(section, "max_range", maxRange);
    t.write(section, "marker_radius", markerRadius);
    t.write(section, "marker_height", markerHeight);
    t.write(section, "camera_height", cameraHeight);
    t.write(section, "sum_tolerance", sumTolerance);
    t.write(section, "bearing_tolerance", bearingTolerance);
    t.write(section, "odometer_sigma", odometerSigma);
    t.write(section, "refine", refine);
    t.write(section, "swarm", swarm);
    t.write(section, "swarm_area", swarmArea);
    t.write(section, "swarm_speed", swarmSpeed);
    t.write(section, "swarm_separation", swarmSeparation);
    if (swarmSeed.given) t.write(section, "swarm_seed", std::to_string(swarmSeed.value));
    t.write(section, "accuracy_trials", accuracyTrials);
}

double OmniOptions::bearingAccuracy() const {
    // Render mode: a blob's centre errs by up to about half a pixel at the view centre (a
    // pixel there is 1 / focal rad), uniformly: sigma ~ 0.3 px (doc/omnivision.md).
    if (render) return 0.3 / panorama.focal();
    return std::max(bearingSigma * M_PI / 180, 1e-6);
}

double OmniOptions::bearingNoise() const {
    // The middle of a marker's columns: each edge uniform over a pixel, sd 1/sqrt(12) px,
    // their mean 1/sqrt(24) px (at the view's centre; less off its axis). Measured over the
    // rendered markers of omnivision_5robots.ini: 0.16 px RMS.
    if (render) return 1.0 / std::sqrt(24.0) / panorama.focal();
    return std::max(bearingSigma * M_PI / 180, 1e-6);
}

double OmniOptions::sumToleranceRad() const {
    return sumTolerance > 0 ? sumTolerance * M_PI / 180 : 6 * bearingAccuracy();
}

double OmniOptions::bearingToleranceRad() const {
    return bearingTolerance > 0 ? bearingTolerance * M_PI / 180 : 4 * bearingAccuracy();
}

std::vector<double> OmniOptions::snapshotTimes() const {
    if (method == "conventional") return {snapshot};
    std::vector<double> t;
    for (size_t r = 0; r < pairs.size(); ++r) {
        t.push_back(tb + double(r) * roundPeriod);
        t.push_back(te + double(r) * roundPeriod);
    }
    return t;
}

}  // namespace mrloc::omnivision
