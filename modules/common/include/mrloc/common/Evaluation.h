#pragma once
// One evaluation of an estimated trajectory against the truth, on the truth's timeline
// (doc/evaluation.md): every truth stamp is associated with the estimate interpolated there,
// or counted as not covered (before the first estimate, after the last, inside a gap); the
// absolute pose error (APE) over the covered stamps, the coverage beside it, and the relative
// pose error (RPE) over a travelled distance and over a time, as evo defines them. Errors at
// the estimator's own stamps stop counting where the estimator stops answering; these do not.
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/poses/CPose2D.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::common {

/** How the estimate is put in the truth's frame before its errors are taken. */
enum class Alignment {
    None,    ///< the truth's frame is the map's (a localizer's estimates are in it already)
    SE2,     ///< the rotation and translation that fit the covered pairs best (Umeyama, no scale)
    Origin,  ///< the first covered estimate moved onto the truth's pose there
};
const char* alignmentName(Alignment a);  ///< "none", "se2", "origin"
std::optional<Alignment> alignmentNamed(const std::string& name);

struct EvaluationOptions {
    Alignment align = Alignment::None;
    /** Two estimates further apart than this (s) leave the truth stamps between them not
     *  covered. 0: five times the median interval between estimates, at least 1 s. */
    double maxGap = 0;
    double rpeDistance = 1.0;  ///< m of travelled truth between the two poses of an RPE pair
    double rpeTime = 1.0;      ///< s between the two poses of an RPE pair
};

/** The error at one covered truth stamp. */
struct PoseError {
    double t = 0;
    double translation = 0;  ///< m, in the plane
    double heading = 0;      ///< rad, |wrapped difference|
    mrpt::poses::CPose2D truth, estimate;  ///< there (the estimate interpolated and aligned)
};

struct Coverage {
    size_t truthStamps = 0;     ///< every stamp of the truth
    size_t covered = 0;         ///< those with an estimate interpolated there
    double maxGap = 0;          ///< s, the gap limit used
    double start = 0, end = 0;  ///< the first and last covered stamp (0 when none)
    /** s: the longest stretch of the truth's timeline between two covered stamps, or from the
     *  truth's first stamp to the first covered one, or from the last covered one to the
     *  truth's end (the whole truth when none is covered). */
    double longestGap = 0;
    /** The stretches of the truth's timeline with no covered stamp, as [from, to] (s): from
     *  the covered stamp before (or the truth's first) to the covered stamp after (or the
     *  truth's last); what the pictures shade. */
    std::vector<std::pair<double, double>> uncovered;
    double share() const { return truthStamps ? double(covered) / double(truthStamps) : 0.0; }
};

/** RPE over one delta: translation (m) and heading (rad) of each pair's relative motion,
 *  estimate against truth. */
struct RelativeError {
    double delta = 0;
    ErrorStats translation, heading;
    std::vector<double> translations, headings;  ///< each pair's (m, rad): pooled over robots
};

struct Evaluation {
    Alignment align = Alignment::None;
    mrpt::poses::CPose2D alignment;  ///< applied to the estimate (identity with None)
    Coverage coverage;
    std::vector<PoseError> errors;    ///< at each covered truth stamp, in time order
    ErrorStats translation, heading;  ///< APE over the covered stamps (m, rad)
    RelativeError rpeDistance, rpeTime;
};

/** Evaluates `estimate` against `truth` (both in time order, as loadTum gives them). The
 *  poses are taken in the plane (x, y, yaw). A single estimate covers only a truth stamp at
 *  its own time (to 1 us). */
Evaluation evaluate(const Trajectory& estimate, const Trajectory& truth,
                    const EvaluationOptions& options = {});

/** metrics.json's form: alignment, coverage (share, stamps, span, longest gap), ape_m and
 *  ape_heading_deg (statsToJson's keys), rpe per delta. */
nlohmann::json toJson(const Evaluation& e);

/** Several robots' evaluations as one figure: their stamps and covered stamps summed, APE
 *  over every covered stamp of all of them, RPE over every pair of all of them
 *  (metrics.json's top-level "truth_timeline"). */
nlohmann::json pooledJson(const std::vector<Evaluation>& robots);

}  // namespace mrloc::common
