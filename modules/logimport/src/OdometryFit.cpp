#include <mrloc/logimport/OdometryFit.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace mrloc::logimport {

std::optional<OdometryFit> fitOdometry(const common::Trajectory& odometry,
                                       const common::Trajectory& truth) {
    if (odometry.size() < 2 || truth.size() < 2) return std::nullopt;
    const double start = std::max(odometry.front().t, truth.front().t);
    const double end = std::min({odometry.back().t, truth.back().t, start + OdometryFit::kSpan});
    if (end - start < 5) return std::nullopt;
    constexpr double kStep = 0.5;      // s between the samples compared
    constexpr double kMinStep = 0.05;  // m in a step for its course to count
    OdometryFit fit;
    fit.seconds = end - start;
    // the course (direction of travel) of each, not the heading: a truth of positions only
    // (libRSF's point2) has none, and the course turns as the heading does
    double odoDistance = 0, cross = 0, truthSquares = 0;
    std::optional<mrpt::poses::CPose3D> lastOdo, lastTruth;
    // the last step's courses of both, while both moved (not an optional pair: GCC 12 warned
    // that one read here might be uninitialized)
    struct {
        double odometry = 0, truth = 0;
        bool valid = false;
    } lastCourse;
    for (double t = start; t <= end; t += kStep) {
        const auto o = common::interpolate(odometry, t), g = common::interpolate(truth, t);
        if (!o || !g) continue;
        if (lastOdo && lastTruth) {
            const double dxo = o->x() - lastOdo->x(), dyo = o->y() - lastOdo->y();
            const double dxg = g->x() - lastTruth->x(), dyg = g->y() - lastTruth->y();
            odoDistance += std::hypot(dxo, dyo);
            fit.truthDistance += std::hypot(dxg, dyg);
            // a course is a course only while both move (5 cm in the half second)
            if (std::hypot(dxo, dyo) < kMinStep || std::hypot(dxg, dyg) < kMinStep) {
                lastCourse.valid = false;
            } else {
                const double co = std::atan2(dyo, dxo), cg = std::atan2(dyg, dxg);
                if (lastCourse.valid) {
                    const double dOdo = mrpt::math::wrapToPi(co - lastCourse.odometry);
                    const double dTruth = mrpt::math::wrapToPi(cg - lastCourse.truth);
                    fit.truthTurn += std::abs(dTruth);
                    cross += dOdo * dTruth, truthSquares += dTruth * dTruth;
                }
                lastCourse = {co, cg, true};
            }
        }
        lastOdo = o, lastTruth = g;
    }
    fit.scale = fit.truthDistance > 0 ? odoDistance / fit.truthDistance : 1;
    fit.turnGain = truthSquares > 0 ? cross / truthSquares : 1;
    return fit;
}

std::optional<std::string> odometryWarning(const std::string& robot, const OdometryFit& fit,
                                           const std::string& advice) {
    std::string what;
    if (fit.mirrored()) what += "turns the other way";
    if (fit.turnRateOff())
        what += (what.empty() ? "turns " : ", ") +
                mrpt::format("%.2f times as fast", std::abs(fit.turnGain));
    if (fit.scaleOff())
        what +=
            (what.empty() ? "" : ", and ") + mrpt::format("travels %.2f times as far", fit.scale);
    if (what.empty()) return std::nullopt;
    return robot + "'s odometry does not fit its ground truth over the first " +
           mrpt::format("%.0f s (%.1f m, %.1f rad turned): it ", fit.seconds, fit.truthDistance,
                        fit.truthTurn) +
           what + (advice.empty() ? "" : "; try " + advice) + " (doc/import.md#odometry-check)";
}

}  // namespace mrloc::logimport
