#pragma once
// Plays a rawlog through a Localizer and writes the run directory (see RunDirectory.h):
// estimates, ground truth in the estimates' frame, errors against it, metrics.json and the
// method's own files. effective.ini and provenance.json are the app's to write.
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/common/Localizer.h>
#include <mrloc/common/Log.h>

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace mrloc::common {

struct LocalizationRunOptions {
    std::string methodName;
    std::string rawlogPath;
    std::string outDir;
    /** Where the warnings and the progress go (the app's log: stderr). */
    const Log* log = &silentLog();
    /** A ground-truth file named in the INI; without one, <rawlog stem>.<robot>.gt.txt. */
    GroundTruthSource groundTruth = {};
    /** Where `groundTruth` came from, in words (metrics.json "ground_truth_from"). */
    std::string groundTruthFrom = {};
    /** The rawlog's path as metrics.json records it, if not rawlogPath (a rawlog simulated
     *  into a staging folder is recorded under the run folder it ends in). */
    std::string rawlogShownAs = {};
    /** Given the log's observations per MRPT class, which method or INI would fit it (the
     *  registry's to say): appended to the error of a run that used none of the log. */
    std::function<std::string(const std::map<std::string, size_t>&)> fitHint = {};
};

/** "mrpt::obs::CObservationOdometry" -> "CObservationOdometry", as users name it. */
std::string shortClassName(const mrpt::obs::CObservation& obs);
/** "1201 CObservationOdometry, 292 CObservationBeaconRanges": what a log holds. */
std::string contentInWords(const std::map<std::string, size_t>& classCounts);

/** Estimates that stop long before the log does while the robot goes on moving (a method
 *  that lost track): a warning per robot whose estimates cover under 90 % of the log's span
 *  [logStart, logEnd] (s). A robot whose odometry moves under 5 cm after its last estimate (a
 *  march that arrived, a robot localized at its last probe) has nothing more to estimate; a
 *  robot with a single estimate (a layout, a start) covers no span. */
std::vector<std::string> earlyEnds(const Trajectories& estimates, const Trajectories& odometry,
                                   double logStart, double logEnd);
/** How far (m, in the plane) the odometry moves after time t. */
double odometryTravelAfter(const Trajectory& odometry, double t);

struct LocalizationResult {
    nlohmann::json metrics;  ///< as written to metrics.json
    Trajectories truth;      ///< ground truth in the estimates' frame (empty without one)
};

/** Throws mrloc::Error, before writing anything, when the rawlog is unreadable, the
 *  method used none of its observations (the message says what the log holds, and
 *  `fitHint`'s advice). A run with no estimate is written (its headline says what the method
 *  found instead: polymap's hypotheses). Partial use (observations of
 *  the method's kind it could not match) and estimates that stop well before the log ends
 *  are warnings: told to the options' log and kept in metrics.json's "warnings". */
LocalizationResult runLocalization(Localizer& localizer, const LocalizationRunOptions& options);

}  // namespace mrloc::common
