#include <mrloc/common/KeyTable.h>
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

/** `search_at_tb`'s words, spelt once (the key, metrics.json, the headline). */
const std::vector<std::pair<std::string, OmniOptions::SearchAtTb>> kSearchAtTbWords{
    {"full", OmniOptions::SearchAtTb::Full},
    {"localized", OmniOptions::SearchAtTb::Localized},
    {"localized_turn", OmniOptions::SearchAtTb::LocalizedTurn}};

}  // namespace

const std::string& OmniOptions::wordOf(SearchAtTb search) {
    for (const auto& [word, value] : kSearchAtTbWords)
        if (value == search) return word;
    return kSearchAtTbWords.front().first;
}

const common::KeyTable<OmniOptions>& OmniOptions::keys() {
    using Opt = OmniOptions;
    static const auto table =
        common::KeyTable<Opt>("omnivision")
            .choice("method", MRLOC_KEY_FIELD(method), {"proposed", "conventional"},
                    "`proposed` (paper 000 section 3: two robots stop, odometry gives L) or "
                    "`conventional` (section 2: one measured distance)")
            .custom(
                "pairs", "", "",
                "proposed: the pairs to stop, in order, `A B, C D`; the next "
                "pair is the paper's restart",
                [](common::IniSection& s, Opt& o) { o.pairs = parsePairs(s, "pairs", o.pairs); },
                [](const Opt& o) { return pairsText(o.pairs); })
            .real("t_b", MRLOC_KEY_FIELD(tb), {0, 1e6}, "s",
                  "from the start (the rawlog's first observation): the first snapshot; the "
                  "pair stands still until `t_e`")
            .real("t_e", MRLOC_KEY_FIELD(te), {0, 1e6}, "s", "the second snapshot, after `t_b`")
            .real("round_period", MRLOC_KEY_FIELD(roundPeriod), {0, 1e6}, "s",
                  "round r stops pair r at `t_b + r * round_period` (must exceed `t_e - t_b` "
                  "with several pairs)")
            .choice("search_at_tb", MRLOC_KEY_FIELD(searchAtTb), kSearchAtTbWords,
                    "the search at t_b: `full` (every image identified, as at t_e: the "
                    "refinement then has every robot's odometer), `localized` (paper 000 eq. "
                    "(11)-(12): only a triangle of the stopped pair and one witness of t_e, "
                    "confirmed without headings by the robots the witness saw; the full search "
                    "when no witness is confirmed) or `localized_turn` (confirmed by the "
                    "witness's odometer turn instead, beyond the paper)")
            .custom(
                "measured_pair", "", "",
                "conventional: `A` measures its distance to `B` (label `A.lidar.B`)",
                [](common::IniSection& s, Opt& o) {
                    const auto measured = parsePairs(s, "measured_pair", {o.measuredPair});
                    if (measured.size() != 1) s.fail("measured_pair", "exactly one pair");
                    o.measuredPair = measured[0];
                },
                [](const Opt& o) { return o.measuredPair.first + " " + o.measuredPair.second; })
            .real("snapshot", MRLOC_KEY_FIELD(snapshot), {0, 1e6}, "s",
                  "conventional: when the cameras fire and the distance is measured")
            .real("lidar_sigma", MRLOC_KEY_FIELD(lidarSigma), {0, 10}, "m", "the LiDAR's noise")
            .choice(
                "camera", MRLOC_KEY_FIELD(render),
                std::vector<std::pair<std::string, bool>>{{"render", true}, {"bearings", false}},
                "`render` (CFBORender panoramas, detected with OpenCV) or `bearings` "
                "(direct bearings with noise)")
            .integer("views", MRLOC_KEY_FIELD(panorama.views), 3, 12, "",
                     "pinhole views in the 360-degree strip")
            .integer("view_width", MRLOC_KEY_FIELD(panorama.viewWidth), 32, 8192, "px",
                     "per view, a multiple of 4")
            .integer("view_height", MRLOC_KEY_FIELD(panorama.height), 8, 4096, "px", "per view")
            .real("bearing_sigma", MRLOC_KEY_FIELD(bearingSigma), {0, 10}, "deg",
                  "bearings mode noise (and the refinement's weight there; in render mode the "
                  "refinement weighs each bearing by the detector's 1/sqrt(24) px times cos^2 "
                  "of its angle off its view's axis, `doc/omnivision.md`)")
            .real("max_range", MRLOC_KEY_FIELD(maxRange), {0, 1e6}, "m",
                  "a camera sees this far (0: unlimited)")
            .real("marker_radius", MRLOC_KEY_FIELD(markerRadius), {1e-3, 10}, "m",
                  "the red band around every camera, which also hides robots behind it")
            .real("marker_height", MRLOC_KEY_FIELD(markerHeight), {1e-3, 10}, "m",
                  "the band's height")
            .real("camera_height", MRLOC_KEY_FIELD(cameraHeight), {0, 100}, "m", "above the floor")
            .real("sum_tolerance", MRLOC_KEY_FIELD(sumTolerance), {0, 30}, "deg",
                  "|sum - 180| accepted; 0: 6 x the bearing accuracy")
            .real("bearing_tolerance", MRLOC_KEY_FIELD(bearingTolerance), {0, 30}, "deg",
                  "a predicted bearing matches; 0: 4 x the bearing accuracy (bearings: "
                  "`bearing_sigma`; render: 0.3 px at the view centre)")
            .real("odometer_sigma", MRLOC_KEY_FIELD(odometerSigma), {1e-6, 1}, "",
                  "relative odometer accuracy, the refinement's weight (set it to your "
                  "robots': the shipped INIs use 0.002, the simulated odometers' 1 mm over "
                  "0.6-0.8 m)")
            .flag("refine", MRLOC_KEY_FIELD(refine),
                  "least-squares refinement with covariance; the estimates are the refined "
                  "layout")
            .integer("swarm", MRLOC_KEY_FIELD(swarm), 0, 1000, "robots",
                     "N > 0: generate N robots `R01..` (then `[scenario] robots` must be "
                     "empty); at least 3")
            .real("swarm_area", MRLOC_KEY_FIELD(swarmArea), {1, 1e4}, "m",
                  "the swarm's square, centred in the room")
            .real("swarm_speed", MRLOC_KEY_FIELD(swarmSpeed), {0, 10}, "m/s",
                  "straight ahead at a random heading")
            .real("swarm_separation", MRLOC_KEY_FIELD(swarmSeparation), {0, 100}, "m",
                  "between starts")
            .subSeed("swarm_seed", MRLOC_KEY_FIELD(swarmSeed), "omnivision swarm",
                     "the layout's seed (absent: drawn from `[scenario] seed`, purpose "
                     "`omnivision swarm`; given: fixes the layout, and the report names it)")
            .integer("accuracy_trials", MRLOC_KEY_FIELD(accuracyTrials), 0, 100000, "",
                     "Monte Carlo trials per noise level for the report's accuracy plot (0: "
                     "none)");
    return table;
}

void OmniOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                     const std::string& section) {
    *this = OmniOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    if (pairs.empty()) s.fail("pairs", "at least one pair of robots to stop");
    if (te <= tb) s.fail("t_e", mrpt::format("must be after t_b (%g)", tb));
    if (pairs.size() > 1 && roundPeriod <= te - tb)
        s.fail("round_period", "must exceed t_e - t_b when several pairs are listed");
    if (panorama.viewWidth % 4 != 0)  // the renderer reads rows of whole 4-byte words: an
        s.fail("view_width", "a multiple of 4 px");  // odd width overran the picture
    if (swarm > 0 && swarm < 3) s.fail("swarm", "a swarm has at least 3 robots (0: none)");
    s.finish();
}

void OmniOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                   const std::string& section) const {
    keys().save(*this, t, section);
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
