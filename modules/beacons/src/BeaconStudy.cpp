// The beacon study's trials (BeaconStudy.h): one fix at a point, and coverage over a grid
// of test points, each point its own random stream. Rooms in StudyLayout.cpp, agents in
// AgentsScheduler.cpp, the parts of a study in BeaconStudyFile.cpp.
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/Seeds.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "TrialRunner.h"

namespace mrloc::beacons {

using mrpt::math::TPoint2D;
using mrpt::math::TPoint3D;

std::string StudyMethod::describe() const {
    std::string out = threeD ? "3-D" : "2-D (height known)";
    out += residual == Residual::Range ? ", range residual" : ", squared residual";
    if (delayCompensation) out += ", delay compensation";
    if (jitterWeights) out += ", jitter weights";
    out += mrpt::format(", %d shot%s per beacon", shotsPerBeacon, shotsPerBeacon > 1 ? "s" : "");
    return out;
}

/** A generator seed per point, whatever the thread. */
using common::streamSeed;

TrialOutcome runTrial(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                      const TPoint2D& at, mrpt::random::CRandomGenerator& rng) {
    TrialRunner runner(room, hw, method);
    return runner.trial(at, rng);
}

double CoverageResult::minReception() const {
    double m = points.empty() ? 0.0 : 1.0;
    for (const auto& p : points) m = std::min(m, p.reception());
    return m;
}

double CoverageResult::meanError() const {
    double sum = 0;
    int n = 0;
    for (const auto& p : points) sum += p.meanError * p.fixes, n += p.fixes;
    return n ? sum / n : 0.0;
}

double CoverageResult::maxError() const {
    double m = 0;
    for (const auto& p : points) m = std::max(m, p.maxError);
    return m;
}

size_t CoverageResult::pointsCovered(const CoverageCriteria& c) const {
    return size_t(std::count_if(points.begin(), points.end(), [&](const PointStats& p) {
        return p.trials > 0 && p.reception() >= c.reception - 1e-12 && p.maxError <= c.errorBound;
    }));
}

CoverageResult evaluateCoverage(const StudyRoom& room, const StudyHardware& hw,
                                const StudyMethod& method, const std::vector<TPoint2D>& points,
                                int trials, uint64_t seed, const CoverageCriteria& criteria,
                                bool stopAtFailure) {
    CoverageResult out;
    out.points.resize(points.size());
    std::atomic<bool> failed{false};
    // a point fails once its misses exceed what the reception rate allows, or one error
    // is over the bound: a search for the verdict stops there
    const int missesAllowed = int(std::floor((1.0 - criteria.reception) * trials + 1e-9));
    common::parallelFor(points.size(), [&](size_t i) {
        if (stopAtFailure && failed) return;
        // a runner per point: nothing a fix leaves behind reaches another point's
        TrialRunner runner(room, hw, method);
        PointStats& p = out.points[i];
        p.at = points[i];
        mrpt::random::CRandomGenerator rng(streamSeed(seed, i));
        double sum = 0;
        for (int k = 0; k < trials; ++k) {
            const auto t = runner.trial(points[i], rng);
            ++p.trials;
            if (t.fixed) {
                ++p.fixes;
                sum += t.error;
                p.maxError = std::max(p.maxError, t.error);
            }
            if (stopAtFailure &&
                (p.trials - p.fixes > missesAllowed || p.maxError > criteria.errorBound)) {
                failed = true;
                break;
            }
        }
        p.meanError = p.fixes ? sum / p.fixes : 0.0;
    });
    if (stopAtFailure && failed) out.complete = false;
    return out;
}

}  // namespace mrloc::beacons
