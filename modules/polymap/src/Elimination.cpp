#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <queue>
#include <random>
#include <set>

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

namespace {

/** One ring of OI as Boost gives it, with the points it repeats (up to rounding) and the
 *  zero-width spikes it leaves dropped. */
std::vector<TPoint2D> cleanRing(std::vector<TPoint2D> ring, double tol) {
    for (bool changed = true; changed && ring.size() > 3;) {
        changed = false;
        for (size_t i = 0; i < ring.size() && ring.size() > 3; ++i) {
            const size_t n = ring.size();
            const TPoint2D &a = ring[(i + n - 1) % n], &b = ring[i], &c = ring[(i + 1) % n];
            const bool repeat = (b - a).norm() <= tol;
            const bool spike = std::abs(common::cross(a - b, c - b)) <= tol * (c - a).norm() &&
                               common::dot(a - b, c - b) > 0;
            if (repeat || spike) {
                ring.erase(ring.begin() + (long)i);
                changed = true;
            }
        }
    }
    return ring;
}

/** OI as a polygon (its holes too: pillars, or the walls of P's holes), for point location
 *  and shortest paths inside it. */
common::Polygon polygonOf(const OverlayRegion& oi) {
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (const auto& p : oi.outer) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double tol = 1e-8 * (hi - lo).norm();
    std::vector<std::vector<TPoint2D>> rings{cleanRing(oi.outer, tol)};
    for (const auto& h : oi.holes) {
        auto ring = cleanRing(h, tol);
        // a sliver hole (rounding where two copies' walls meet) has no area to route round
        double twiceArea = 0;
        for (size_t i = 0; i < ring.size(); ++i)
            twiceArea += common::cross(ring[i], ring[(i + 1) % ring.size()]);
        if (ring.size() >= 3 && std::abs(twiceArea) > tol * (hi - lo).norm())
            rings.push_back(std::move(ring));
    }
    return common::Polygon::fromRings(std::move(rings), "elimination: the overlay region");
}

/** p lies in T's polygon at least `radius` from its boundary: no edge of the polygon within
 *  `radius`, found by a walk over the triangles that the disk of that radius reaches (the
 *  segment to the nearest boundary point crosses only such triangles), so the cost is local. */
bool clearInside(const Triangulation& T, const TPoint2D& p, double radius) {
    const auto at = T.locate(p);
    if (at.triangle == Triangulation::kNone || !T[at.triangle].inside) return false;
    thread_local std::vector<int> reached;  // the disk is small: a few triangles
    reached.assign(1, at.triangle);
    for (size_t next = 0; next < reached.size(); ++next) {
        const auto& tri = T[reached[next]];
        for (int i = 0; i < 3; ++i) {
            if (common::distanceToSegment(p, T.point(tri.from(i)), T.point(tri.to(i))) >= radius)
                continue;
            if (tri.constrained[i]) return false;
            const int u = tri.neighbour[i];
            if (u != Triangulation::kNone && T[u].inside &&
                std::find(reached.begin(), reached.end(), u) == reached.end())
                reached.push_back(u);
        }
    }
    return true;
}

/** No wall of V is seen edge-on: its line passing nearer than `clearance` to the viewpoint
 *  beside the wall (not facing it), where a scanner's beams graze it and the sensed V is not
 *  worth comparing. */
bool wellConditioned(const VisibilityPolygon& V, double clearance) {
    const size_t n = V.size();
    for (size_t i = 0; i < n; ++i) {
        if (V.isRadial(i)) continue;  // a window: not a wall
        const TPoint2D &a = V.vertices[i], &b = V.vertices[(i + 1) % n];
        const TVector2D ab = b - a;
        const double length = ab.norm();
        if (length == 0 || std::abs(common::cross(a, b)) / length >= clearance) continue;
        const double foot = -common::dot(a, ab) / (length * length);  // viewpoint's foot
        if (foot < 0 || foot > 1) return false;
    }
    return true;
}

/** How far `range`, seen along `angle`, is from V's boundary: along the beam itself, or,
 *  when that is over `tolerance`, the best of it and half a beam step either side (a beam
 *  next to a window's end sees the wall on its other side). */
double radialMismatch(const RadialProfile& V, double angle, double range, double step,
                      double tolerance) {
    const auto off = [&](double d) { return std::abs(range - V.radius(angle + d)); };
    const double e = off(0);
    return e > tolerance ? std::min({e, off(-0.5 * step), off(0.5 * step)}) : e;
}

}  // namespace

double beamMismatch(const ScanBeams& beams, const VisibilityPolygon& V, double quantile) {
    const RadialProfile profile(V);
    std::vector<double> error(beams.range.size());
    for (size_t b = 0; b < error.size(); ++b)
        error[b] = beams.noReturn[b]
                       ? std::max(0.0, beams.range[b] - profile.radius(beams.angle[b]))
                       : radialMismatch(profile, beams.angle[b], beams.range[b], beams.step, 0);
    if (error.empty()) return 0;
    const size_t k = std::min(error.size() - 1, size_t(quantile * double(error.size())));
    std::nth_element(error.begin(), error.begin() + long(k), error.end());
    return error[k];
}

namespace {

/** Over 2 % of `beams` directions see ranges differing by more than `margin`, ranges beyond
 *  `maxRange` being one (the scanner sees no return there). */
bool beamsTellApart(const VisibilityPolygon& a, const VisibilityPolygon& b, int beams,
                    double margin, double maxRange) {
    const double step = 2 * M_PI / beams;
    const RadialProfile pa(a), pb(b);
    int differ = 0;
    for (int k = 0; k < beams; ++k) {
        const double t = k * step, ra = pa.radius(t);
        const bool beyond = ra >= maxRange && pb.radius(t) >= maxRange;
        differ += !beyond && radialMismatch(pb, t, ra, step, margin) > margin;
        if (differ * 50 > beams) return true;
    }
    return false;
}

}  // namespace

/** OI of the live hypotheses, as a polygon, triangulated, with its shortest paths. */
struct Eliminator::Region {
    OverlayRegion oi;
    common::Polygon polygon;
    Triangulation triangles;
    ShortestPaths paths;

    explicit Region(const common::Polygon& P, const std::vector<TPoint2D>& positions)
        : oi(overlayRegion(P, positions)),  // seed 002 steps 4-6
          polygon(polygonOf(oi)),
          triangles(polygon),
          paths(triangles) {}
    Region(const Region&) = delete;  // triangles and paths refer to the members above
    Region& operator=(const Region&) = delete;

    /** p lies inside OI, `clearance` from its boundary (up to rounding: window probes sit
     *  at it). */
    bool clear(const TPoint2D& p, double clearance) const {
        return clearInside(triangles, p, std::max(clearance * (1 - 1e-9), polygon.epsilon()));
    }

    /** The candidate nearest to `at` by travel inside OI, `clearance` from its boundary,
     *  that passes `test`, with that travel; candidates are tested nearest first (ties:
     *  lower index first), and `tested` counts them. The straight line bounds the travel from
     * below, so geodesics are computed only for the candidates whose straight distance is below the
     * answer's travel. */
    template <typename Test>
    std::optional<std::pair<double, size_t>> nearest(const TPoint2D& at,
                                                     const std::vector<TPoint2D>& found,
                                                     double clearance, Test test,
                                                     size_t* tested = nullptr) const {
        using Entry = std::pair<double, size_t>;
        std::vector<Entry> straight;  // a min-heap: only the near ones are ever taken off
        straight.reserve(found.size());
        for (size_t c = 0; c < found.size(); ++c) straight.push_back({(found[c] - at).norm(), c});
        std::make_heap(straight.begin(), straight.end(), std::greater<>());
        std::priority_queue<Entry, std::vector<Entry>, std::greater<>> byTravel;
        while (!straight.empty() || !byTravel.empty()) {
            if (!straight.empty() &&
                (byTravel.empty() || straight.front().first <= byTravel.top().first)) {
                const size_t c = straight.front().second;
                std::pop_heap(straight.begin(), straight.end(), std::greater<>());
                straight.pop_back();
                if (clear(found[c], clearance)) byTravel.push({paths.distance(at, found[c]), c});
                continue;
            }
            const auto [travel, c] = byTravel.top();
            byTravel.pop();
            if (tested) ++*tested;
            if (test(found[c])) return std::make_pair(travel, c);
        }
        return std::nullopt;
    }
};

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

namespace {

/** The critical chords of a polygon (Dudek-Romanik-Whitesides 1998): what a point sees
 *  changes only where its sight line to a vertex grazes a reflex vertex, i.e. across the
 *  chord that extends the line from vertex v through reflex vertex r into the polygon. */
template <class Chord>
std::vector<Chord> criticalChords(const common::Polygon& poly, const Triangulation& T) {
    std::vector<Chord> out;
    const auto& R = poly.vertices();
    const size_t m = R.size();
    const double eps = poly.epsilon();
    for (size_t r = 0; r < m; ++r) {
        if (!poly.isReflex(r)) continue;
        // What r sees: the vertices v it sees and, past r, where each chord ends.
        const VisibilityPolygon Vr = visibilityPolygon(T, R[r]);
        for (size_t v = 0; v < m; ++v) {
            if (v == r) continue;
            const TVector2D toV = R[v] - R[r];
            const bool adjacent = v == poly.next(r) || r == poly.next(v);
            if (!adjacent && Vr.radius(toV * (1 / toV.norm())) < toV.norm() - eps)
                continue;  // v hidden from r
            const TVector2D d = toV * (-1 / toV.norm());
            const double hit = Vr.radius(d);
            if (hit <= 1e3 * eps) continue;  // the extension leaves the polygon at once
            out.push_back({R[r], d, hit});
        }
    }
    return out;
}

/** Points along a chord (every `spacing`, at most perChord), both sides of it at the
 *  clearance, moved by `shift`. The nearest point of a cell lies on its boundary. */
void sampleSegment(const TPoint2D& from, const TVector2D& d, double length, double spacing,
                   int perChord, double clearance, const TVector2D& shift,
                   std::vector<TPoint2D>& out) {
    const TVector2D normal{-d.y, d.x};
    const int samples = std::clamp((int)std::ceil(length / spacing), 1, perChord);
    for (int k = 0; k < samples; ++k) {
        const TPoint2D on = from + d * (length * (k + 0.5) / samples) + shift;
        for (const double side : {-1.0, 1.0})
            out.push_back(on + normal * (side * std::max(clearance, 1e-6)));
    }
}

bool inBox(const TPoint2D& p, const common::Polygon& box) {
    return p.x >= box.min().x && p.y >= box.min().y && p.x <= box.max().x && p.y <= box.max().y;
}

}  // namespace

struct Eliminator::ChordCache {
    std::once_flag once;
    std::vector<Chord> chords;
};

const std::vector<Eliminator::Chord>& Eliminator::mapChords() const {
    std::call_once(chords_->once, [this] { chords_->chords = criticalChords<Chord>(P_, T_); });
    return chords_->chords;
}

std::vector<TPoint2D> Eliminator::chordCandidates(const Region& region, double chordSpacing,
                                                  int perChord) const {
    // Algorithm 1 (Dudek-Romanik-Whitesides): the decomposition's cells are bounded by OI's
    // critical chords and OI's edges, and the nearest point of a cell lies on its boundary:
    // candidates are points along every chord, on both sides of it (cleared when reached:
    // see nearest()).
    std::vector<TPoint2D> out;
    for (const auto& c : criticalChords<Chord>(region.polygon, region.triangles))
        sampleSegment(c.from, c.d, c.length, chordSpacing, perChord, options_.clearance, {0, 0},
                      out);
    return out;
}

std::vector<TPoint2D> Eliminator::mapChordCandidates(const std::vector<size_t>& live,
                                                     const Region& region, double chordSpacing,
                                                     int perChord) const {
    std::vector<TPoint2D> out, chord;
    for (const auto& c : mapChords())
        for (size_t i : live) {
            chord.clear();
            sampleSegment(c.from, c.d, c.length, chordSpacing, perChord, options_.clearance,
                          hypotheses_[i] * -1.0, chord);
            for (const auto& p : chord)
                if (inBox(p, region.polygon)) out.push_back(p);
        }
    return out;
}

std::vector<TPoint2D> Eliminator::mapWindowCandidates(const std::vector<size_t>& live,
                                                      const Region& region,
                                                      const TPoint2D& from) const {
    // The windows of what the robot would see in the map under each live hypothesis, from
    // where it stands and from algorithm 4's middles, where the window itself may lie beyond
    // OI (a corridor seen from OI's edge): points along each window, and along the way from
    // the viewpoint towards its middle (walking up to a window shows what is behind it).
    std::vector<TPoint2D> viewpoints{from}, out;
    const auto middles = windowCandidates(region, from);
    viewpoints.insert(viewpoints.end(), middles.begin(), middles.end());
    const double spacing = std::max(options_.clearance, 1e-3);
    for (const auto& vp : viewpoints)
        for (size_t i : live) {
            VisibilityPolygon V;
            try {
                V = viewOf(i, vp);
            } catch (const Error&) {  // vp off the map under this hypothesis (by rounding)
                continue;
            }
            for (size_t e = 0; e < V.size(); ++e) {
                if (!V.isRadial(e)) continue;
                const TPoint2D a = V.vertices[e], b = V.vertices[(e + 1) % V.size()];
                const double length = (b - a).norm();
                if (!(length > 0)) continue;
                std::vector<TPoint2D> window;
                sampleSegment(a, (b - a) * (1 / length), length, spacing, 32, options_.clearance,
                              vp, window);
                const TVector2D toMiddle = (a + b) * 0.5;
                const double reach = toMiddle.norm();
                if (reach > 0)
                    sampleSegment({0, 0}, toMiddle * (1 / reach), reach, spacing, 32,
                                  options_.clearance, vp, window);
                for (const auto& p : window)
                    if (inBox(p, region.polygon)) out.push_back(p);
            }
        }
    return out;
}

std::vector<TPoint2D> Eliminator::windowCandidates(const Region& region,
                                                   const TPoint2D& from) const {
    // Algorithm 4, step 6: the middle points of windows [4] in OI. A window (Koenig, Mitchell,
    // Mudgal and Tovey 2009; Guibas, Motwani and Raghavan 1997) is an edge of a visibility
    // polygon that is not on the boundary: the robot would see more through it. The robot's
    // view inside OI from `from` gives the first windows; from a window's middle the robot
    // sees the windows behind it, and so on breadth first, until the candidates reach every
    // part of OI it can walk into (at most kWindowViews views). Middles closer than the
    // clearance are one.
    const double merge = std::max(options_.clearance, 1e-6 * (P_.max() - P_.min()).norm());
    std::vector<TPoint2D> out;
    std::set<std::pair<long, long>> taken;  // middles, by cells of the merge size
    std::vector<TPoint2D> viewpoints{from};
    for (size_t next = 0; next < viewpoints.size() && next < kWindowViews; ++next) {
        VisibilityPolygon V;
        try {
            V = visibilityPolygon(region.triangles, viewpoints[next]);
        } catch (const Error&) {  // the robot off OI (by rounding)
            continue;
        }
        for (size_t i = 0; i < V.size(); ++i) {
            if (!V.isRadial(i)) continue;  // a wall
            const TPoint2D m =
                viewpoints[next] + (V.vertices[i] + V.vertices[(i + 1) % V.size()]) * 0.5;
            // a wall seen edge-on lies on OI's boundary; a window in a gap narrower than the
            // clearance has no middle the robot may stand on
            if (!region.clear(m, options_.clearance)) continue;
            if (!taken.insert({std::lround(m.x / merge), std::lround(m.y / merge)}).second)
                continue;
            out.push_back(m);
            viewpoints.push_back(m);
        }
    }
    return out;
}

std::vector<TPoint2D> Eliminator::candidates(const std::vector<size_t>& live, const Region& region,
                                             const TPoint2D& from, size_t step,
                                             ProbeStrategy strategy, double chordSpacing,
                                             int perChord) const {
    std::vector<TPoint2D> out;
    const double clearance = options_.clearance;
    switch (strategy) {
        case ProbeStrategy::VisibilityCells:
            return chordCandidates(region, chordSpacing, perChord);
        case ProbeStrategy::Windows:
            return windowCandidates(region, from);
        case ProbeStrategy::Triangulation: {
            // seed 002 algorithm 3, step 7: edge midpoints and centroids of the map's
            // triangles, placed at the origin hypothesis.
            const TPoint2D origin = hypotheses_[live.front()];
            for (int t = 0; t < (int)T_.triangles().size(); ++t) {
                const auto& tri = T_[t];
                if (!tri.inside) continue;
                const TPoint2D &a = T_.point(tri.v[0]), &b = T_.point(tri.v[1]),
                               &c = T_.point(tri.v[2]);
                for (const TPoint2D p :
                     {(a + b + c) * (1.0 / 3), (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5})
                    if (region.clear(p - origin, clearance)) out.push_back(p - origin);
            }
            std::sort(out.begin(), out.end(), [](const TPoint2D& a, const TPoint2D& b) {
                return a.x < b.x || (a.x == b.x && a.y < b.y);
            });
            out.erase(std::unique(out.begin(), out.end()), out.end());  // shared edges
            break;
        }
        case ProbeStrategy::Randomized: {
            // Algorithm 2 (Rao-Dudek-Whitesides): X uniform points of OI, seeded per step.
            std::mt19937 rng(options_.seed * 2654435761u + (uint32_t)step);
            std::uniform_real_distribution<double> ux(region.polygon.min().x,
                                                      region.polygon.max().x);
            std::uniform_real_distribution<double> uy(region.polygon.min().y,
                                                      region.polygon.max().y);
            const size_t want = (size_t)options_.randomPoints;
            for (size_t tries = 0; out.size() < want && tries < 1000 * want; ++tries) {
                const TPoint2D p{ux(rng), uy(rng)};
                if (region.clear(p, clearance)) out.push_back(p);
            }
            break;
        }
    }
    return out;
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

std::vector<TPoint2D> Eliminator::everyCandidate(const std::vector<size_t>& live,
                                                 const Region& region, const TPoint2D& at,
                                                 double spacing, int perChord) const {
    std::vector<TPoint2D> out;
    for (const auto strategy : {ProbeStrategy::VisibilityCells, ProbeStrategy::Randomized,
                                ProbeStrategy::Triangulation, ProbeStrategy::Windows}) {
        const auto more = candidates(live, region, at, 0, strategy, spacing, perChord);
        out.insert(out.end(), more.begin(), more.end());
    }
    for (const auto& more : {mapChordCandidates(live, region, spacing, perChord),
                             mapWindowCandidates(live, region, at)})
        out.insert(out.end(), more.begin(), more.end());
    return out;
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
        run.travel += probe->path.length;
        at = probe->at;
        run.probes.push_back(*probe);
    }
    return run;
}

}  // namespace mrloc::polymap
