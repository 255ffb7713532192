#include <mrloc/common/Error.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/polymap/VerificationTour.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cstdint>
#include <queue>
#include <tuple>
#include <unordered_map>

namespace mrloc::polymap {

namespace {

using Mask = uint32_t;

/** A search state: where the robot is (a site, or the start) and what it has ruled out. */
uint64_t key(size_t at, Mask ruledOut) { return (uint64_t(at) << 32) | ruledOut; }

void checkSize(const Eliminator& eliminator) {
    const size_t k = eliminator.hypotheses().size();
    if (k > kMaxTourHypotheses)
        throw Error(
            mrpt::format("verification tour: %zu hypotheses; the exact search takes "
                         "at most %zu",
                         k, kMaxTourHypotheses));
}

/** What the site rules out under each truth, as masks (0: nothing, or no probe there). */
std::vector<Mask> rulesOf(const Eliminator& eliminator, const TPoint2D& site) {
    std::vector<Mask> masks;
    for (const auto& out : eliminator.ruledOutByEach(eliminator.viewsAt(site))) {
        Mask m = 0;
        if (out)
            for (size_t i : *out) m |= Mask(1) << i;
        masks.push_back(m);
    }
    return masks;
}

/** A* over (position, ruled out) from the start to everything ruled out; `at` and `rules`
 *  are the sites and what each rules out. */
std::optional<VerificationTour> search(const Eliminator& eliminator, size_t truth,
                                       std::vector<TPoint2D> at, std::vector<Mask> rules) {
    const size_t k = eliminator.hypotheses().size();
    const Mask everything = Mask((1ull << k) - 1);
    VerificationTour tour;
    {  // the sites that rule something out
        size_t kept = 0;
        for (size_t s = 0; s < at.size(); ++s)
            if (rules[s]) at[kept] = at[s], rules[kept++] = rules[s];
        at.resize(kept);
        rules.resize(kept);
    }
    tour.sites = at.size();
    const Mask first = Mask(1) << truth;
    Mask reachable = first;
    for (Mask m : rules) reachable |= m;
    if (reachable != everything) return std::nullopt;
    const size_t origin = at.size();
    at.push_back({0, 0});

    // Heuristic: each hypothesis still standing needs a site that rules it out, at least its
    // straight-line distance away; a lower bound on the travel left, so A* stays exact. A
    // position's distances are found when a state there is first taken off the queue.
    std::unordered_map<size_t, std::vector<double>> nearestRuling;
    const auto heuristic = [&](size_t p, Mask done) {
        if (done == everything) return 0.0;
        auto [it, fresh] = nearestRuling.try_emplace(p, k, INFINITY);
        if (fresh)
            for (size_t s = 0; s < rules.size(); ++s) {
                const double d = (at[s] - at[p]).norm();
                for (size_t i = 0; i < k; ++i)
                    if (rules[s] >> i & 1) it->second[i] = std::min(it->second[i], d);
            }
        double h = 0;
        for (size_t i = 0; i < k; ++i)
            if (!(done >> i & 1)) h = std::max(h, it->second[i]);
        return h;
    };

    // Travel under the truth: shortest paths inside P between the sites placed at its start,
    // one row per site the search leaves from, computed when first needed.
    const ShortestPaths paths(eliminator.triangulation());
    const TPoint2D start = eliminator.hypotheses()[truth];
    std::unordered_map<size_t, std::vector<double>> rows;
    const auto row = [&](size_t p) -> const std::vector<double>& {
        auto [it, fresh] = rows.try_emplace(p);
        if (fresh)
            for (size_t s = 0; s < rules.size(); ++s)
                it->second.push_back(paths.distance(start + at[p], start + at[s]));
        return it->second;
    };

    struct Reached {
        double travel;
        uint64_t from;
    };
    std::unordered_map<uint64_t, Reached> best;
    // Entries: estimate, travel, state, whether the estimate includes the heuristic. A state
    // enters with its travel alone (a lower bound too) and is queued again with the heuristic
    // when first taken off, so only the states reached that early pay for one.
    using Entry = std::tuple<double, double, uint64_t, bool>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    best[key(origin, first)] = {0, key(origin, first)};
    open.push({0, 0, key(origin, first), false});
    while (!open.empty()) {
        const auto [estimate, travel, state, estimated] = open.top();
        open.pop();
        if (travel > best.at(state).travel) continue;  // reached more cheaply since
        const size_t p = size_t(state >> 32);
        const Mask done = Mask(state);
        if (!estimated) {
            const double h = heuristic(p, done);
            if (h > 0) {
                open.push({travel + h, travel, state, true});
                continue;
            }
        }
        if (done == everything) {  // the goal: walk back for the probes
            tour.length = travel;
            for (uint64_t s = state; s != key(origin, first); s = best.at(s).from)
                tour.probes.push_back(at[size_t(s >> 32)]);
            std::reverse(tour.probes.begin(), tour.probes.end());
            return tour;
        }
        ++tour.expanded;
        const auto& d = row(p);
        for (size_t s = 0; s < rules.size(); ++s) {
            if (!(rules[s] & ~done)) continue;  // rules out nothing new
            const Mask next = done | rules[s];
            const double g = travel + d[s];
            const uint64_t to = key(s, next);
            if (const auto it = best.find(to); it != best.end() && it->second.travel <= g) continue;
            best[to] = {g, state};
            open.push({g, g, to, false});
        }
    }
    return std::nullopt;  // not reached: every hypothesis has a site ruling it out
}

}  // namespace

std::optional<VerificationTour> verificationTour(const Eliminator& eliminator, size_t truth,
                                                 const std::vector<TPoint2D>& sites) {
    checkSize(eliminator);
    std::vector<Mask> rules;
    for (const auto& s : sites) rules.push_back(rulesOf(eliminator, s)[truth]);
    return search(eliminator, truth, sites, std::move(rules));
}

std::vector<std::optional<VerificationTour>> verificationTours(
    const Eliminator& eliminator, const std::vector<TPoint2D>& shared,
    const std::vector<std::vector<TPoint2D>>& ownSites) {
    checkSize(eliminator);
    const size_t k = eliminator.hypotheses().size();
    std::vector<std::vector<Mask>> sharedRules(k);  // [truth][site]
    for (const auto& s : shared) {
        const auto masks = rulesOf(eliminator, s);  // the views once for every truth
        for (size_t truth = 0; truth < k; ++truth) sharedRules[truth].push_back(masks[truth]);
    }
    std::vector<std::optional<VerificationTour>> out;
    for (size_t truth = 0; truth < k; ++truth) {
        std::vector<TPoint2D> at = shared;
        std::vector<Mask> rules = sharedRules[truth];
        if (truth < ownSites.size())
            for (const auto& s : ownSites[truth]) {
                at.push_back(s);
                rules.push_back(rulesOf(eliminator, s)[truth]);
            }
        out.push_back(search(eliminator, truth, std::move(at), std::move(rules)));
    }
    return out;
}

}  // namespace mrloc::polymap
