#include <mrloc/common/Error.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/polymap/ViewComparison.h>

#include <algorithm>
#include <cmath>

#include "EliminatorRegion.h"

namespace mrloc::polymap {

std::string probeSourceName(ProbeSource s) {
    switch (s) {
        case ProbeSource::Own:
            return "own";
        case ProbeSource::Completed:
            return "completed";
        case ProbeSource::Triangulation:
            return "triangulation";
        case ProbeSource::Every:
            return "every algorithm's";
    }
    return "?";
}

std::string strategyName(ProbeStrategy s) {
    switch (s) {
        case ProbeStrategy::VisibilityCells:
            return "cells";
        case ProbeStrategy::Randomized:
            return "randomized";
        case ProbeStrategy::Triangulation:
            return "triangulation";
        case ProbeStrategy::Windows:
            return "windows";
    }
    return "?";
}

ProbeStrategy strategyFromName(const std::string& name) {
    for (const auto s : {ProbeStrategy::VisibilityCells, ProbeStrategy::Randomized,
                         ProbeStrategy::Triangulation, ProbeStrategy::Windows})
        if (strategyName(s) == name) return s;
    throw Error("probe strategy '" + name +
                "': expected cells, randomized, triangulation or windows");
}

std::vector<TPoint2D> Eliminator::positionsOf(const std::vector<size_t>& live) const {
    std::vector<TPoint2D> out;
    for (size_t i : live) out.push_back(hypotheses_[i]);
    return out;
}

Eliminator::Eliminator(const common::Polygon& P, std::vector<TPoint2D> hypotheses,
                       EliminationOptions options)
    : P_(P),
      T_(P),
      hypotheses_(std::move(hypotheses)),
      options_(options),
      chords_(std::make_shared<ChordCache>()) {
    if (hypotheses_.empty()) throw Error("elimination: no hypotheses");
    if (options_.randomPoints < 1) throw Error("elimination: random_points must be at least 1");
    if (!(options_.tolerance > 0)) throw Error("elimination: the tolerance must be positive");
    if (!(options_.clearance >= 0)) throw Error("elimination: the clearance must not be negative");
}

VisibilityPolygon Eliminator::viewOf(size_t i, const TPoint2D& at) const {
    return visibilityPolygon(T_, hypotheses_[i] + at);
}

bool Eliminator::sameView(const VisibilityPolygon& a, const VisibilityPolygon& b,
                          double tolerance) {
    if (vertexwiseDistance(a, b) <= tolerance) return true;
    double extent = 0;
    for (const auto& v : a.vertices) extent = std::max(extent, v.norm());
    return boundaryDistance(a, b, std::max(tolerance / 4, extent / 250), tolerance) <= tolerance;
}

bool Eliminator::separates(const std::vector<size_t>& live, const TPoint2D& at) const {
    const double extent = (P_.max() - P_.min()).norm();
    std::vector<VisibilityPolygon> views;
    views.reserve(live.size());
    for (size_t i : live) {
        views.push_back(viewOf(i, at));
        if (!wellConditioned(views.back(), options_.clearance)) return false;
    }
    for (size_t k = 1; k < views.size(); ++k)
        if (options_.sensorBeams > 0
                // identical views first (cheap), then the beams
                ? vertexwiseDistance(views.front(), views[k]) > 1e-9 * extent &&
                      beamsTellApart(views.front(), views[k], options_.sensorBeams,
                                     2 * options_.rangeTolerance, options_.sensorMaxRange)
                : !sameView(views.front(), views[k], 2 * options_.tolerance))
            return true;
    return false;
}

std::optional<Probe> Eliminator::chooseProbe(const std::vector<size_t>& live, const TPoint2D& at,
                                             const std::vector<TPoint2D>& avoid,
                                             double avoidRadius) const {
    if (live.size() < 2) return std::nullopt;
    const Region region(P_, positionsOf(live));
    Probe probe;
    probe.oiArea = region.oi.area;
    const size_t step = hypotheses_.size() - live.size();
    const double spacing = std::max(options_.clearance, 1e-3);
    std::vector<TPoint2D> found;
    std::optional<std::pair<double, size_t>> best;
    // Nearest first by travel inside OI; the first that separates is the probe (step 7).
    const auto search = [&](std::vector<TPoint2D> candidates) {
        found = std::move(candidates);
        probe.candidates += found.size();
        best = region.nearest(
            at, found, options_.clearance,
            [&](const TPoint2D& c) {
                for (const auto& a : avoid)
                    if ((c - a).norm() <= avoidRadius) return false;
                return separates(live, c);
            },
            &probe.tested);
        return best.has_value();
    };
    // The paper's own candidates first. Algorithm 2 draws another X points while none
    // separates (a place that tells the hypotheses apart may be small: a passage's far leg),
    // up to kRandomBatches draws; the other algorithms' candidates are fixed. Batch b of step
    // s is seeded by s + b * k.
    const size_t batches = options_.strategy == ProbeStrategy::Randomized ? kRandomBatches : 1;
    for (size_t batch = 0; batch < batches && !best; ++batch)
        search(candidates(live, region, at, step + batch * hypotheses_.size(), options_.strategy,
                          spacing, 32));
    // Then, only if none separates, the completions (ProbeSource): what tells the hypotheses
    // apart may be seen only beyond OI's own corners and windows.
    // (each set computed only if the ones before it separated nothing)
    const auto fallBack = [&](ProbeSource source, const auto& more) {
        if (best || !search(more())) return;
        probe.source = source;
    };
    if (options_.strategy == ProbeStrategy::VisibilityCells)
        fallBack(ProbeSource::Completed,
                 [&] { return mapChordCandidates(live, region, spacing, 32); });
    if (options_.strategy == ProbeStrategy::Windows)
        fallBack(ProbeSource::Completed, [&] { return mapWindowCandidates(live, region, at); });
    if (options_.strategy != ProbeStrategy::Triangulation)
        fallBack(ProbeSource::Triangulation, [&] {
            return candidates(live, region, at, step, ProbeStrategy::Triangulation, spacing, 32);
        });
    fallBack(ProbeSource::Every, [&] { return everyCandidate(live, region, at, spacing, 4096); });
    if (!best) return std::nullopt;
    probe.at = found[best->second];
    probe.path = region.paths.path(at, probe.at);
    return probe;
}

std::pair<std::vector<TPoint2D>, OverlayRegion> Eliminator::candidatesAndRegion(
    const std::vector<size_t>& live) const {
    const Region region(P_, positionsOf(live));
    auto found = candidates(live, region, {0, 0}, hypotheses_.size() - live.size(),
                            options_.strategy, std::max(options_.clearance, 1e-3), 32);
    found.erase(
        std::remove_if(found.begin(), found.end(),
                       [&](const TPoint2D& c) { return !region.clear(c, options_.clearance); }),
        found.end());
    return {std::move(found), region.oi};
}

std::optional<double> Eliminator::firstSeparation(const std::vector<size_t>& live,
                                                  const TPoint2D& at, double spacing) const {
    if (live.size() < 2) return std::nullopt;
    const Region region(P_, positionsOf(live));
    const auto found = everyCandidate(live, region, at, spacing, 1 << 20);
    const auto best = region.nearest(at, found, options_.clearance,
                                     [&](const TPoint2D& c) { return separates(live, c); });
    if (!best) return std::nullopt;
    return best->first;
}

std::vector<std::optional<VisibilityPolygon>> Eliminator::viewsAt(const TPoint2D& at) const {
    std::vector<std::optional<VisibilityPolygon>> views(hypotheses_.size());
    for (size_t i = 0; i < hypotheses_.size(); ++i)
        if (P_.locate(hypotheses_[i] + at) == common::Polygon::Where::Inside)
            views[i] = viewOf(i, at);
    return views;
}

std::vector<std::optional<std::vector<size_t>>> Eliminator::ruledOutByEach(
    const std::vector<std::optional<VisibilityPolygon>>& views) const {
    const size_t k = views.size();
    std::vector<std::optional<std::vector<size_t>>> out(k);
    for (size_t truth = 0; truth < k; ++truth)
        if (views[truth] && wellConditioned(*views[truth], options_.clearance))
            out[truth].emplace();
    for (size_t i = 0; i < k; ++i)
        for (size_t j = i + 1; j < k; ++j) {
            if (!out[i] && !out[j]) continue;
            // Consistent()'s rule: a view outside P, or one beyond the tolerance, differs.
            const bool differ =
                !views[i] || !views[j] || !sameView(*views[j], *views[i], options_.tolerance);
            if (differ && out[i]) out[i]->push_back(j);
            if (differ && out[j]) out[j]->push_back(i);
        }
    for (auto& o : out)
        if (o) std::sort(o->begin(), o->end());
    return out;
}

std::vector<size_t> Eliminator::consistent(const std::vector<size_t>& live, const TPoint2D& at,
                                           const VisibilityPolygon& sensed,
                                           double tolerance) const {
    if (tolerance < 0) tolerance = options_.tolerance;
    std::vector<size_t> out;
    for (size_t i : live)  // seed 002 step 9
        if (sameView(viewOf(i, at), sensed, tolerance)) out.push_back(i);
    return out;
}

std::vector<size_t> Eliminator::consistentWithScan(const std::vector<size_t>& live,
                                                   const TPoint2D& at,
                                                   const mrpt::obs::CObservation2DRangeScan& scan,
                                                   double heading, double rangeTolerance,
                                                   double searchRadius,
                                                   std::vector<TPoint2D>* refined) const {
    // A beam without return agrees where the view reaches at least the max range: at a probe
    // the robot may look down a corridor longer than its scanner reaches.
    const ScanBeams beams = beamsOf(scan, heading, true);
    const size_t n = beams.range.size();
    // How badly the view at displacement x explains the beams (every `stride`-th): the beams
    // that disagree, and the sum of their errors capped at 4 tolerances (a score to refine
    // the position by).
    const auto fit = [&](size_t i, const TPoint2D& x, size_t stride) {
        VisibilityPolygon V;
        try {
            V = viewOf(i, x);
        } catch (const Error&) {
            return std::make_pair(n, double(INFINITY));  // x outside P under this hypothesis
        }
        const RadialProfile profile(V);
        size_t disagree = 0;
        double score = 0;
        for (size_t b = 0; b < n; b += stride) {
            const double e = beams.noReturn[b]
                                 ? std::max(0.0, beams.range[b] - profile.radius(beams.angle[b]))
                                 : radialMismatch(profile, beams.angle[b], beams.range[b],
                                                  beams.step, rangeTolerance);
            disagree += e > rangeTolerance;
            score += std::min(e, 4 * rangeTolerance);
        }
        return std::make_pair(disagree, score);
    };
    const size_t stride = (n + kRefineBeams - 1) / kRefineBeams;
    std::vector<size_t> out;
    for (size_t i : live) {  // seed 002 step 9, on the beams
        // Where the robot stopped, if not on the probe: 7 x 7 grids, each a sixth of the last
        // around its best point (1 cm, then 1.7 mm, then 0.3 mm for a 3 cm radius), scored on
        // a subset of the beams; the verdict is on all of them at the best point.
        TPoint2D best = at;
        if (searchRadius > 0) {
            double score = fit(i, at, stride).second;
            for (double cell = searchRadius / 3; cell > 2e-4; cell /= 6) {
                const TPoint2D centre = best;
                for (int gx = -3; gx <= 3; ++gx)
                    for (int gy = -3; gy <= 3; ++gy) {
                        const TPoint2D x = centre + TPoint2D{double(gx), double(gy)} * cell;
                        if (gx == 0 && gy == 0) continue;
                        const double sc = fit(i, x, stride).second;
                        if (sc < score) score = sc, best = x;
                    }
            }
        }
        const size_t disagree = fit(i, best, 1).first;
        if (disagree * 100 > n) continue;
        out.push_back(i);
        if (refined) refined->push_back(best);
    }
    return out;
}

EliminationSession::EliminationSession(const common::Polygon& P, std::vector<TPoint2D> hypotheses,
                                       EliminationOptions options, double heading,
                                       double arrivalRadius)
    : eliminator_(P, std::move(hypotheses), options),
      heading_(heading),
      arrivalRadius_(arrivalRadius) {
    for (size_t i = 0; i < eliminator_.hypotheses().size(); ++i) live_.push_back(i);
    plan_ = eliminator_.chooseProbe(live_, {0, 0});
}

void EliminationSession::observe(const mrpt::obs::CObservation2DRangeScan& scan) {
    if (!plan_) throw Error("elimination: a scan came with no probe planned");
    const auto& o = eliminator_.options();
    std::vector<TPoint2D> refined;
    const size_t before = live_.size();
    live_ = eliminator_.consistentWithScan(live_, plan_->at, scan, heading_, o.rangeTolerance,
                                           arrivalRadius_, &refined);
    if (live_.size() == before)
        fruitless_.push_back(plan_->at);
    else
        fruitless_.clear();  // a new live set: its own probes
    stops_.emplace_back();
    for (size_t k = 0; k < live_.size(); ++k) stops_.back()[live_[k]] = refined[k];
    visited_.push_back(*plan_);
    plan_.reset();
    if (live_.size() > 1)
        plan_ = eliminator_.chooseProbe(live_, visited_.back().at, fruitless_,
                                        std::max(arrivalRadius_, o.clearance));
}

EliminationRun eliminateExactly(const Eliminator& eliminator, size_t truth) {
    EliminationRun run;
    for (size_t i = 0; i < eliminator.hypotheses().size(); ++i) run.survivors.push_back(i);
    TPoint2D at{0, 0};
    while (run.survivors.size() > 1) {
        const auto probe = eliminator.chooseProbe(run.survivors, at);
        if (!probe) break;  // no candidate of the strategy separates what is left
        run.survivors =
            eliminator.consistent(run.survivors, probe->at, eliminator.viewOf(truth, probe->at));
        run.leftAfter.push_back(run.survivors.size());
        run.travel += probe->path.length;
        at = probe->at;
        run.probes.push_back(*probe);
    }
    return run;
}

}  // namespace mrloc::polymap