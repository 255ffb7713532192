#pragma once
// What a run can honestly claim: how much of the rawlog the method used (a run that used
// none of it is not a success), and the method's headline (its own figures, the paper's
// beside them, the baselines apart), as metrics.json's "use" and "headline" hold them and
// the CLI's last line and the report's top block show them.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::common {

/** The observations of the kind a method localizes from (its sensing, not odometry). */
struct ObservationUse {
    std::string
        kind;         ///< in words, with the MRPT class: "beacon ranges (CObservationBeaconRanges)"
    size_t seen = 0;  ///< of that kind in the log
    size_t used = 0;  ///< of those, matched to the method's map or robots and used
    /** Why the others were not used: what was counted and why, in words ("ranges from
     *  beacons not in the map"), and the count. */
    std::vector<std::pair<std::string, size_t>> unmatched;
};

nlohmann::json toJson(const ObservationUse& use);

/** One figure of the headline. */
struct HeadlineFigure {
    std::string name;             ///< "RMSE", "error at the destination"
    std::optional<double> value;  ///< none: the run has nothing to compute it from
    std::string unit;             ///< "m", "%", "" for a count
    /** The paper's figure for it, in words with its source ("30 mm mean (seed 001 Table 4)");
     *  empty when the paper gives none. */
    std::string paper;
    /** How this run's experiment differs from the paper's, in a sentence; empty when it is
     *  the paper's experiment or there is no paper figure. */
    std::string differs;
    /** A baseline (dead reckoning, odometry alone): shown beside, never averaged in. */
    bool baseline = false;
};

/** The exit status of a run whose method failed (Headline::failed; doc/errors.md). */
inline constexpr int kFailedExit = 3;

/** A method's outcome: did it reach its goal, and its figures. */
struct Headline {
    /** false: the method found nothing (0 hypotheses, no fix) or the run ended before its
     *  goal; `status` says which (metrics.json, the CLI's last line). */
    bool reached = true;
    /** The method could not do its job on this input, as opposed to a run that stopped short
     *  (0 hypotheses fit the robot's scan: not its map; no probe separates the hypotheses
     *  left). The run folder is written all the same; `mrloc run` and `mrloc localize` then
     *  exit with kFailedExit so that scripts see it. Implies !reached. */
    bool failed = false;
    std::string status;  ///< "localized", "not localized: 0 hypotheses fit the first scan", ...
    std::vector<HeadlineFigure> figures;
    /** What ran, in the paper's terms: the paper's own mechanism or mrloc's variant of it,
     *  named with its key ("t_b: the full search ...; paper 000's eq. (11)-(12) is
     *  search_at_tb = localized"); each module's doc page has the table. Empty: nothing to
     *  choose between. The report prints it under the outcome, metrics.json keeps it. */
    std::string mechanism;
};

nlohmann::json toJson(const Headline& h);
/** Reads metrics.json's "headline"; throws mrloc::Error naming `where` for a malformed one. */
Headline headlineFromJson(const nlohmann::json& j, const std::string& where);
/** A figure's value to 3 digits with its unit, "0.0123 m" ("none" without a value);
 *  `space` goes between number and unit (a page keeps them together with a no-break space). */
std::string valueText(const HeadlineFigure& f, const std::string& space = " ");
/** A figure as the CLI and the report print it: "RMSE 0.0123 m". */
std::string figureText(const HeadlineFigure& f);
/** The CLI's last line: "beacons: localized: RMSE 0.027 m; odometry alone 0.76 m". */
std::string headlineLine(const std::string& method, const Headline& h);

/** The headline figures of a method whose output is a trajectory per robot, from
 *  metrics.json's truth_timeline (doc/evaluation.md): APE RMSE over every covered truth stamp,
 *  the share of the truth's stamps covered beside it, RPE over 1 m, and odometry alone on its
 *  own truth timeline (a baseline). */
std::vector<HeadlineFigure> trajectoryFigures(const nlohmann::json& metrics);

/** A number of metrics.json at `path` (a/b/c), if present and finite. */
std::optional<double> numberAt(const nlohmann::json& j, const std::string& path);

}  // namespace mrloc::common
