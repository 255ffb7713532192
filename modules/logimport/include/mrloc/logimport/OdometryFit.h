#pragma once
// Import checks its own output against the truth it holds (doc/import.md, "Odometry against
// the truth"): over the first minute in which both exist, the odometry's increments are set
// beside the truth's, sampled every half second (the truth's jitter at 100 Hz would
// otherwise count as motion): how far it travels (scale), how fast and which way it turns.
#include <mrloc/common/Trajectory.h>

#include <optional>
#include <string>

namespace mrloc::logimport {

struct OdometryFit {
    double seconds = 0;        ///< the span compared
    double truthDistance = 0;  ///< m travelled by the truth
    double truthTurn = 0;      ///< rad the truth's course turned (sum of |increments|)
    double scale = 1;          ///< odometry's distance / the truth's
    double turnGain = 1;       ///< least squares of the odometry's course increments on the
                               ///< truth's: 1 fits, -1 turns the other way, 2 twice as fast
    bool scaleOff() const { return truthDistance >= kMinDistance && (scale < 0.8 || scale > 1.25); }
    bool mirrored() const { return truthTurn >= kMinTurn && turnGain < 0; }
    bool turnRateOff() const {
        return truthTurn >= kMinTurn && (std::abs(turnGain) < 0.8 || std::abs(turnGain) > 1.25);
    }
    static constexpr double kSpan = 60, kMinDistance = 1.0, kMinTurn = 1.0;  // s, m, rad
};

/** The fit over the first kSpan seconds both cover; nothing if they share under 5 s. */
std::optional<OdometryFit> fitOdometry(const common::Trajectory& odometry,
                                       const common::Trajectory& truth);

/** One line when the fit is off: what was measured and, if given, the option to try. */
std::optional<std::string> odometryWarning(const std::string& robot, const OdometryFit& fit,
                                           const std::string& advice);

}  // namespace mrloc::logimport
