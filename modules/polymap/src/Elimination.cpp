#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace mrloc::polymap {

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

/** OI as a simple polygon, for point location and shortest paths inside it: Boost's ring
 *  with the points it repeats (up to rounding) and the zero-width spikes it leaves dropped. */
common::Polygon polygonOf(const OverlayRegion& oi) {
    if (!oi.holes.empty())
        throw Error(
            mrpt::format("elimination: the overlay region has %zu hole(s), which the "
                         "shortest paths (in a simple polygon) cannot route around",
                         oi.holes.size()));
    std::vector<TPoint2D> ring = oi.outer;
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (const auto& p : ring) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double tol = 1e-8 * (hi - lo).norm();
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
    return common::Polygon::fromVertices(ring, "elimination: the overlay region");
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
double radialMismatch(const VisibilityPolygon& V, double angle, double range, double step,
                      double tolerance) {
    const auto off = [&](double d) {
        return std::abs(range - V.radius({std::cos(angle + d), std::sin(angle + d)}));
    };
    const double e = off(0);
    return e > tolerance ? std::min({e, off(-0.5 * step), off(0.5 * step)}) : e;
}

/** Over 2 % of `beams` directions see ranges differing by more than `margin`. */
bool beamsTellApart(const VisibilityPolygon& a, const VisibilityPolygon& b, int beams,
                    double margin) {
    const double step = 2 * M_PI / beams;
    int differ = 0;
    for (int k = 0; k < beams; ++k) {
        const double t = k * step;
        differ += radialMismatch(b, t, a.radius({std::cos(t), std::sin(t)}), step, margin) > margin;
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

    /** Candidate indices, nearest first by travel inside OI from `at`. */
    std::vector<std::pair<double, size_t>> byTravel(const TPoint2D& at,
                                                    const std::vector<TPoint2D>& found) const {
        std::vector<std::pair<double, size_t>> order;
        order.reserve(found.size());
        for (size_t c = 0; c < found.size(); ++c)
            order.push_back({paths.distance(at, found[c]), c});
        std::sort(order.begin(), order.end());
        return order;
    }
};

std::vector<TPoint2D> Eliminator::positionsOf(const std::vector<size_t>& live) const {
    std::vector<TPoint2D> out;
    for (size_t i : live) out.push_back(hypotheses_[i]);
    return out;
}

Eliminator::Eliminator(const common::Polygon& P, std::vector<TPoint2D> hypotheses,
                       EliminationOptions options)
    : P_(P), T_(P), hypotheses_(std::move(hypotheses)), options_(options) {
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
    return boundaryDistance(a, b, std::max(tolerance / 4, extent / 250)) <= tolerance;
}

std::vector<TPoint2D> Eliminator::candidates(const std::vector<size_t>& live,
                                             const OverlayRegion& oi,
                                             const common::Polygon& oiPolygon, size_t step,
                                             ProbeStrategy strategy, double chordSpacing,
                                             int perChord) const {
    std::vector<TPoint2D> out;
    const double clearance = options_.clearance;
    // Inside OI, `clearance` from its boundary (up to rounding: window probes sit at it).
    const auto inOI = [&oiPolygon, clearance](const TPoint2D& c) {
        return oiPolygon.locate(c) == common::Polygon::Where::Inside &&
               (clearance == 0 ||
                (oiPolygon.closestBoundaryPoint(c).first - c).norm() >= clearance * (1 - 1e-9));
    };
    switch (strategy) {
        case ProbeStrategy::VisibilityCells: {
            // Algorithm 1 (Dudek-Romanik-Whitesides): what a point of OI sees changes only
            // where its sight line to a vertex grazes a reflex vertex, i.e. across the chord
            // that extends the line from vertex v through reflex vertex r into OI. The
            // decomposition's cells are bounded by these chords and OI's edges, and the
            // nearest point of a cell lies on its boundary: candidates are points along
            // every chord (every chordSpacing, at most perChord), on both sides of it.
            const auto& R = oiPolygon.vertices();
            const size_t m = R.size();
            const double eps = oiPolygon.epsilon();
            const auto sees = [&](size_t a, size_t b) {  // segment R[a]-R[b] inside OI
                for (size_t e = 0; e < m; ++e) {
                    const size_t f = (e + 1) % m;
                    if (e == a || e == b || f == a || f == b) continue;
                    if (common::distanceToSegment(R[e], R[a], R[b]) <= eps) return false;
                    const int o1 = common::orientation(R[a], R[b], R[e]);
                    const int o2 = common::orientation(R[a], R[b], R[f]);
                    const int o3 = common::orientation(R[e], R[f], R[a]);
                    const int o4 = common::orientation(R[e], R[f], R[b]);
                    if (o1 * o2 < 0 && o3 * o4 < 0) return false;
                }
                return oiPolygon.locate((R[a] + R[b]) * 0.5) != common::Polygon::Where::Outside;
            };
            for (size_t r = 0; r < m; ++r) {
                if (!oiPolygon.isReflex(r)) continue;
                for (size_t v = 0; v < m; ++v) {
                    if (v == r || !sees(r, v)) continue;
                    const TVector2D d = (R[r] - R[v]) * (1 / (R[r] - R[v]).norm());
                    if (oiPolygon.locate(R[r] + d * (1e3 * eps)) != common::Polygon::Where::Inside)
                        continue;  // the extension leaves OI at once: no chord
                    const auto hit = oiPolygon.rayCast(R[r], d, 1e3 * eps);
                    if (!hit) continue;
                    const TVector2D normal{-d.y, d.x};
                    const int samples =
                        std::clamp((int)std::ceil(*hit / chordSpacing), 1, perChord);
                    for (int k = 0; k < samples; ++k) {
                        const TPoint2D on = R[r] + d * (*hit * (k + 0.5) / samples);
                        for (const double side : {-1.0, 1.0}) {
                            const TPoint2D c = on + normal * (side * std::max(clearance, 1e-6));
                            if (inOI(c)) out.push_back(c);
                        }
                    }
                }
            }
            break;
        }
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
                    if (inOI(p - origin)) out.push_back(p - origin);
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
            std::uniform_real_distribution<double> ux(oiPolygon.min().x, oiPolygon.max().x);
            std::uniform_real_distribution<double> uy(oiPolygon.min().y, oiPolygon.max().y);
            const size_t want = (size_t)options_.randomPoints;
            for (size_t tries = 0; out.size() < want && tries < 1000 * want; ++tries) {
                const TPoint2D p{ux(rng), uy(rng)};
                if (inOI(p)) out.push_back(p);
            }
            break;
        }
        case ProbeStrategy::Windows: {
            // Algorithm 4, step 6: midpoints of OI's windows, edges that are a wall of some
            // live copies but not of all (a wall of all tells nothing).
            const double onWall = 1e-7 * (P_.max() - P_.min()).norm();
            const size_t m = oi.outer.size();
            for (size_t e = 0; e < m; ++e) {
                const TPoint2D mid = (oi.outer[e] + oi.outer[(e + 1) % m]) * 0.5;
                size_t walls = 0;
                for (size_t i : live)
                    walls += (P_.closestBoundaryPoint(hypotheses_[i] + mid).first -
                              (hypotheses_[i] + mid))
                                 .norm() <= onWall;
                if (walls == 0 || walls == live.size()) continue;
                // Stand off the window, inwards (OI is counter-clockwise: its inside is left).
                const TVector2D along = oi.outer[(e + 1) % m] - oi.outer[e];
                const TVector2D inwards = TVector2D{-along.y, along.x} * (1 / along.norm());
                const TPoint2D probe = mid + inwards * std::max(clearance, 1e-6 * along.norm());
                if (inOI(probe)) out.push_back(probe);
            }
            break;
        }
    }
    return out;
}

bool Eliminator::separates(const std::vector<size_t>& live, const TPoint2D& at) const {
    const double extent = (P_.max() - P_.min()).norm();
    std::vector<VisibilityPolygon> views;
    for (size_t i : live) views.push_back(viewOf(i, at));
    bool differ = false;
    for (size_t k = 1; k < views.size() && !differ; ++k)
        differ = options_.sensorBeams > 0
                     // identical views first (cheap), then the beams
                     ? vertexwiseDistance(views.front(), views[k]) > 1e-9 * extent &&
                           beamsTellApart(views.front(), views[k], options_.sensorBeams,
                                          2 * options_.rangeTolerance)
                     : !sameView(views.front(), views[k], 2 * options_.tolerance);
    return differ && std::all_of(views.begin(), views.end(), [this](const auto& V) {
               return wellConditioned(V, options_.clearance);
           });
}

std::optional<Probe> Eliminator::chooseProbe(const std::vector<size_t>& live,
                                             const TPoint2D& at) const {
    if (live.size() < 2) return std::nullopt;
    const Region region(P_, positionsOf(live));
    const auto found = candidates(live, region.oi, region.polygon, hypotheses_.size() - live.size(),
                                  options_.strategy, std::max(options_.clearance, 1e-3), 32);
    Probe probe;
    probe.candidates = found.size();
    probe.oiArea = region.oi.area;
    // Nearest first by travel inside OI; the first that separates is the probe (step 7).
    for (const auto& [distance, c] : region.byTravel(at, found)) {
        ++probe.tested;
        if (!separates(live, found[c])) continue;
        probe.at = found[c];
        probe.path = region.paths.path(at, found[c]);
        return probe;
    }
    return std::nullopt;
}

std::pair<std::vector<TPoint2D>, OverlayRegion> Eliminator::candidatesAndRegion(
    const std::vector<size_t>& live) const {
    const Region region(P_, positionsOf(live));
    return {candidates(live, region.oi, region.polygon, hypotheses_.size() - live.size(),
                       options_.strategy, std::max(options_.clearance, 1e-3), 32),
            region.oi};
}

std::optional<double> Eliminator::firstSeparation(const std::vector<size_t>& live,
                                                  const TPoint2D& at, double spacing) const {
    if (live.size() < 2) return std::nullopt;
    const Region region(P_, positionsOf(live));
    std::vector<TPoint2D> found;
    for (const auto strategy : {ProbeStrategy::VisibilityCells, ProbeStrategy::Randomized,
                                ProbeStrategy::Triangulation, ProbeStrategy::Windows}) {
        const auto more =
            candidates(live, region.oi, region.polygon, 0, strategy, spacing, 1 << 20);
        found.insert(found.end(), more.begin(), more.end());
    }
    for (const auto& [distance, c] : region.byTravel(at, found))
        if (separates(live, found[c])) return distance;
    return std::nullopt;
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
    const ScanBeams beams = beamsOf(scan, heading);
    const size_t n = beams.range.size();
    // How badly the view at displacement x explains the beams: the beams that disagree, and
    // the sum of their errors capped at 4 tolerances (a score to refine the position by).
    const auto fit = [&](size_t i, const TPoint2D& x) {
        VisibilityPolygon V;
        try {
            V = viewOf(i, x);
        } catch (const Error&) {
            return std::make_pair(n, double(INFINITY));  // x outside P under this hypothesis
        }
        size_t disagree = 0;
        double score = 0;
        for (size_t b = 0; b < n; ++b) {
            const double e =
                radialMismatch(V, beams.angle[b], beams.range[b], beams.step, rangeTolerance);
            disagree += e > rangeTolerance;
            score += std::min(e, 4 * rangeTolerance);
        }
        return std::make_pair(disagree, score);
    };
    std::vector<size_t> out;
    for (size_t i : live) {  // seed 002 step 9, on the beams
        auto [disagree, score] = fit(i, at);
        // Where the robot stopped, if not on the probe: 7 x 7 grids, each a sixth of the last
        // around its best point (1 cm, then 1.7 mm, then 0.3 mm for a 3 cm radius).
        TPoint2D best = at;
        for (double cell = searchRadius / 3; cell > 2e-4; cell /= 6) {
            const TPoint2D centre = best;
            for (int gx = -3; gx <= 3; ++gx)
                for (int gy = -3; gy <= 3; ++gy) {
                    const TPoint2D x = centre + TPoint2D{double(gx), double(gy)} * cell;
                    if (gx == 0 && gy == 0) continue;
                    const auto [d, sc] = fit(i, x);
                    if (sc < score) disagree = d, score = sc, best = x;
                }
        }
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
    live_ = eliminator_.consistentWithScan(live_, plan_->at, scan, heading_, o.rangeTolerance,
                                           arrivalRadius_, &refined);
    stops_.emplace_back();
    for (size_t k = 0; k < live_.size(); ++k) stops_.back()[live_[k]] = refined[k];
    visited_.push_back(*plan_);
    plan_.reset();
    if (live_.size() > 1) plan_ = eliminator_.chooseProbe(live_, visited_.back().at);
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
