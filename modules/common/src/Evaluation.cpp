#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/RigidFit.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mrloc::common {

using mrpt::poses::CPose2D;

const char* alignmentName(Alignment a) {
    switch (a) {
        case Alignment::None:
            return "none";
        case Alignment::SE2:
            return "se2";
        case Alignment::Origin:
            return "origin";
    }
    return "";
}

std::optional<Alignment> alignmentNamed(const std::string& name) {
    for (const auto a : {Alignment::None, Alignment::SE2, Alignment::Origin})
        if (name == alignmentName(a)) return a;
    return std::nullopt;
}

namespace {

constexpr double kSameStamp = 1e-6;  // s: TUM files keep 9 decimals

CPose2D planar(const mrpt::poses::CPose3D& p) { return {p.x(), p.y(), p.yaw()}; }

/** A covered truth stamp: its index in the truth, the truth's pose and the estimate's there. */
struct Pair {
    size_t index;
    double t;
    CPose2D truth, estimate;
};

/** Five times the median interval between estimates, at least 1 s. */
double defaultMaxGap(const Trajectory& estimate) {
    if (estimate.size() < 2) return 1.0;
    std::vector<double> steps;
    steps.reserve(estimate.size() - 1);
    for (size_t i = 1; i < estimate.size(); ++i) steps.push_back(estimate[i].t - estimate[i - 1].t);
    return std::max(1.0, 5.0 * percentile(std::move(steps), 50));
}

/** Each truth stamp with the estimate there, or none (not covered); one pass over both. */
std::vector<Pair> associate(const Trajectory& estimate, const Trajectory& truth, double maxGap) {
    std::vector<Pair> pairs;
    if (estimate.empty()) return pairs;
    pairs.reserve(truth.size());
    size_t j = 0;  // the last estimate at or before the truth stamp
    for (size_t i = 0; i < truth.size(); ++i) {
        const double t = truth[i].t;
        while (j + 1 < estimate.size() && estimate[j + 1].t <= t) ++j;
        std::optional<CPose2D> at;
        if (std::abs(estimate[j].t - t) <= kSameStamp)
            at = planar(estimate[j].pose);
        else if (j + 1 < estimate.size() && std::abs(estimate[j + 1].t - t) <= kSameStamp)
            at = planar(estimate[j + 1].pose);
        else if (estimate[j].t < t && j + 1 < estimate.size() &&
                 estimate[j + 1].t - estimate[j].t <= maxGap)
            at = planar(interpolateBetween(estimate[j], estimate[j + 1], t));
        if (at) pairs.push_back({i, t, planar(truth[i].pose), *at});
    }
    return pairs;
}

Coverage coverageOf(const std::vector<Pair>& pairs, const Trajectory& truth, double maxGap) {
    Coverage c;
    c.truthStamps = truth.size();
    c.covered = pairs.size();
    c.maxGap = maxGap;
    if (truth.empty()) return c;
    if (pairs.empty()) {
        c.longestGap = truth.back().t - truth.front().t;
        c.uncovered.emplace_back(truth.front().t, truth.back().t);
        return c;
    }
    c.start = pairs.front().t;
    c.end = pairs.back().t;
    // a stretch of uncovered stamps, from the covered stamp before it (or the truth's start)
    // to the covered stamp after it (or the truth's end)
    if (pairs.front().index > 0) c.uncovered.emplace_back(truth.front().t, pairs.front().t);
    for (size_t k = 1; k < pairs.size(); ++k)
        if (pairs[k].index > pairs[k - 1].index + 1)
            c.uncovered.emplace_back(pairs[k - 1].t, pairs[k].t);
    if (pairs.back().index + 1 < truth.size())
        c.uncovered.emplace_back(pairs.back().t, truth.back().t);
    for (const auto& [from, to] : c.uncovered) c.longestGap = std::max(c.longestGap, to - from);
    return c;
}

/** The transform that puts the estimate in the truth's frame. */
CPose2D alignmentOf(Alignment a, const std::vector<Pair>& pairs) {
    if (a == Alignment::None || pairs.empty()) return {};
    if (a == Alignment::Origin) return pairs.front().truth + (-pairs.front().estimate);
    if (pairs.size() < 2)
        throw Error("SE(2) alignment needs at least two covered truth stamps, there is one");
    Eigen::Matrix2Xd from(2, pairs.size()), to(2, pairs.size());
    for (size_t k = 0; k < pairs.size(); ++k) {
        from.col(Eigen::Index(k)) << pairs[k].estimate.x(), pairs[k].estimate.y();
        to.col(Eigen::Index(k)) << pairs[k].truth.x(), pairs[k].truth.y();
    }
    const Eigen::Matrix3d T = rigidFit2D(from, to);
    return {T(0, 2), T(1, 2), std::atan2(T(1, 0), T(0, 0))};
}

/** RPE over runs of consecutive covered stamps: from each pose, the first later one at least
 *  `delta` away (travelled truth, or time), then on from there (evo's pairs without
 *  all_pairs); a pair never spans an uncovered stamp. */
RelativeError relativeErrors(const std::vector<Pair>& pairs, double delta, bool byDistance) {
    RelativeError r;
    r.delta = delta;
    auto& translation = r.translations;
    auto& heading = r.headings;
    size_t i = 0;
    while (i < pairs.size()) {
        double travelled = 0;
        size_t j = i + 1;
        for (; j < pairs.size() && pairs[j].index == pairs[j - 1].index + 1; ++j) {
            travelled += std::hypot(pairs[j].truth.x() - pairs[j - 1].truth.x(),
                                    pairs[j].truth.y() - pairs[j - 1].truth.y());
            if ((byDistance ? travelled : pairs[j].t - pairs[i].t) >= delta) break;
        }
        if (j >= pairs.size() || pairs[j].index != pairs[j - 1].index + 1) {
            i = j;  // the run ended before delta: its next run starts a new pair
            continue;
        }
        const CPose2D truthMotion = pairs[j].truth - pairs[i].truth;
        const CPose2D estimateMotion = pairs[j].estimate - pairs[i].estimate;
        const CPose2D e = estimateMotion - truthMotion;  // (Q_i^-1 Q_j)^-1 (P_i^-1 P_j)
        translation.push_back(std::hypot(e.x(), e.y()));
        heading.push_back(std::abs(mrpt::math::wrapToPi(e.phi())));
        i = j;
    }
    r.translation = computeStats(translation);
    r.heading = computeStats(heading);
    return r;
}

}  // namespace

Evaluation evaluate(const Trajectory& estimate, const Trajectory& truth,
                    const EvaluationOptions& o) {
    Evaluation e;
    e.align = o.align;
    const double maxGap = o.maxGap > 0 ? o.maxGap : defaultMaxGap(estimate);
    auto pairs = associate(estimate, truth, maxGap);
    e.coverage = coverageOf(pairs, truth, maxGap);
    e.alignment = alignmentOf(o.align, pairs);
    std::vector<double> translation, heading;
    translation.reserve(pairs.size());
    heading.reserve(pairs.size());
    e.errors.reserve(pairs.size());
    for (auto& p : pairs) {
        // none: the identity, whose composition a 10^6-stamp evaluation need not pay for
        if (o.align != Alignment::None) p.estimate = e.alignment + p.estimate;
        const double dt = std::hypot(p.estimate.x() - p.truth.x(), p.estimate.y() - p.truth.y());
        const double dh = std::abs(mrpt::math::wrapToPi(p.estimate.phi() - p.truth.phi()));
        e.errors.push_back({p.t, dt, dh, p.truth, p.estimate});
        translation.push_back(dt);
        heading.push_back(dh);
    }
    e.translation = computeStats(translation);
    e.heading = computeStats(heading);
    e.rpeDistance = relativeErrors(pairs, o.rpeDistance, true);
    e.rpeTime = relativeErrors(pairs, o.rpeTime, false);
    return e;
}

nlohmann::json toJson(const Evaluation& e) {
    const auto& c = e.coverage;
    nlohmann::json j;
    j["alignment"] = alignmentName(e.align);
    j["alignment_pose"] = {e.alignment.x(), e.alignment.y(), mrpt::RAD2DEG(e.alignment.phi())};
    j["coverage"] = {{"share", c.share()},   {"truth_stamps", c.truthStamps},
                     {"covered", c.covered}, {"start_s", c.start},
                     {"end_s", c.end},       {"longest_gap_s", c.longestGap},
                     {"max_gap_s", c.maxGap}};
    j["ape"] = statsToJson(e.translation, "m");
    j["ape_heading"] = statsToJson(e.heading, "deg", mrpt::RAD2DEG(1.0));
    for (const auto* r : {&e.rpeDistance, &e.rpeTime}) {
        nlohmann::json rj{{"delta", r->delta}, {"unit", r == &e.rpeDistance ? "m" : "s"}};
        rj["translation"] = statsToJson(r->translation, "m");
        rj["heading"] = statsToJson(r->heading, "deg", mrpt::RAD2DEG(1.0));
        j["rpe"].push_back(rj);
    }
    return j;
}

nlohmann::json pooledJson(const std::vector<Evaluation>& robots) {
    size_t stamps = 0, covered = 0;
    std::vector<double> translation, heading;
    for (const auto& e : robots) {
        stamps += e.coverage.truthStamps;
        covered += e.coverage.covered;
        for (const auto& p : e.errors)
            translation.push_back(p.translation), heading.push_back(p.heading);
    }
    nlohmann::json j{
        {"robots", robots.size()},
        {"truth_stamps", stamps},
        {"covered", covered},
        {"share", stamps ? double(covered) / double(stamps) : 0.0},
        {"ape", statsToJson(computeStats(translation), "m")},
        {"ape_heading", statsToJson(computeStats(heading), "deg", mrpt::RAD2DEG(1.0))}};
    if (robots.empty()) return j;
    // RPE per delta over every robot's pairs (the robots share the options, so the deltas)
    for (const bool byDistance : {true, false}) {
        std::vector<double> t, h;
        for (const auto& e : robots) {
            const auto& r = byDistance ? e.rpeDistance : e.rpeTime;
            t.insert(t.end(), r.translations.begin(), r.translations.end());
            h.insert(h.end(), r.headings.begin(), r.headings.end());
        }
        const auto& first = byDistance ? robots.front().rpeDistance : robots.front().rpeTime;
        j["rpe"].push_back({{"delta", first.delta},
                            {"unit", byDistance ? "m" : "s"},
                            {"translation", statsToJson(computeStats(t), "m")},
                            {"heading", statsToJson(computeStats(h), "deg", mrpt::RAD2DEG(1.0))}});
    }
    return j;
}

}  // namespace mrloc::common
