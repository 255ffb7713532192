#include <mrloc/common/Error.h>
#include <mrloc/polymap/Hypotheses.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace mrloc::polymap {

namespace {

double angleOf(const TVector2D& d) { return std::atan2(d.y, d.x); }

double angleGap(double a, double b) { return std::abs(std::remainder(a - b, 2 * M_PI)); }

long long cellKey(long long ix, long long iy) { return ix * 73856093LL ^ iy * 19349663LL; }

}  // namespace

HypothesisGenerator::HypothesisGenerator(const common::Polygon& map, HypothesisOptions options)
    : map_(map), triangulation_(map), options_(options) {
    if (!(options_.tolerance > 0) || !(options_.angleTolerance > 0))
        throw Error("hypothesis generation: tolerance and angle tolerance must be positive");
    const size_t n = map_.size();
    inAngle_.resize(n);
    outAngle_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        inAngle_[i] = angleOf(map_[i] - map_[map_.prev(i)]);
        outAngle_[i] = angleOf(map_[map_.next(i)] - map_[i]);
    }
    cell_ = std::max(4 * options_.tolerance, 1e-6);
    for (size_t i = 0; i < n; ++i)
        grid_[cellKey((long long)std::floor(map_[i].x / cell_),
                      (long long)std::floor(map_[i].y / cell_))]
            .push_back(i);
}

std::vector<HypothesisGenerator::Feature> HypothesisGenerator::featuresOf(
    const VisibilityPolygon& V) const {
    std::vector<Feature> corners, windowEnds;
    const size_t n = V.size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (size_t i = 0; i < n; ++i) {
        const size_t prev = (i + n - 1) % n, next = (i + 1) % n;
        const TPoint2D& p = V.vertices[i];
        if (p.norm() <= options_.tolerance) continue;  // the viewpoint itself, on a wall
        // An edge shorter than twice the tolerance gives no reliable direction (from a
        // scan it is often a corner's rounding): its ends are not features.
        const double minEdge = 2 * options_.tolerance;
        if ((p - V.vertices[prev]).norm() < minEdge || (V.vertices[next] - p).norm() < minEdge)
            continue;
        const bool radialIn = V.isRadial(prev), radialOut = V.isRadial(i);
        const double in = angleOf(p - V.vertices[prev]), out = angleOf(V.vertices[next] - p);
        if (!radialIn && !radialOut) {
            if (angleGap(in, out) > options_.angleTolerance) corners.push_back({p, in, out});
        } else if (!radialIn && radialOut && V.vertices[next].norm() > p.norm()) {
            windowEnds.push_back({p, in, nan});  // a window (or a wall seen edge-on) leaves
        } else if (radialIn && !radialOut && V.vertices[prev].norm() > p.norm()) {
            windowEnds.push_back({p, nan, out});  // one arrives
        }
    }
    return corners.empty() ? windowEnds : corners;
}

bool HypothesisGenerator::matches(const Feature& f, size_t j) const {
    const double tol = options_.angleTolerance;
    if (!std::isnan(f.inAngle) && angleGap(f.inAngle, inAngle_[j]) > tol) return false;
    if (!std::isnan(f.outAngle) && angleGap(f.outAngle, outAngle_[j]) > tol) return false;
    // A half-seen vertex is usually reflex (a window leaves it), but not when the radial
    // edge is a wall through the viewpoint, seen edge-on: no convexity test.
    return true;
}

std::optional<size_t> HypothesisGenerator::vertexNear(const TPoint2D& p, const Feature& f) const {
    const long long cx = (long long)std::floor(p.x / cell_),
                    cy = (long long)std::floor(p.y / cell_);
    std::optional<size_t> best;
    double bestDist = options_.tolerance;
    for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy) {
            const auto it = grid_.find(cellKey(cx + dx, cy + dy));
            if (it == grid_.end()) continue;
            for (size_t j : it->second)
                if (const double d = (map_[j] - p).norm(); d <= bestDist && matches(f, j))
                    best = j, bestDist = d;
        }
    return best;
}

std::vector<TPoint2D> HypothesisGenerator::consensusPlaces(const std::vector<Feature>& features,
                                                           const std::vector<bool>& inMap) const {
    const size_t inCount = size_t(std::count(inMap.begin(), inMap.end(), true));
    const size_t need = std::min<size_t>(inCount, 3);
    struct Place {
        size_t landed;
        TPoint2D at;
    };
    // anchors: the features the map has, the rarest first (their guesses are the likeliest
    // to be right, and the cap below then leaves out the commonest)
    std::vector<std::vector<size_t>> anchors;
    for (size_t a = 0; a < features.size(); ++a) {
        if (!inMap[a]) continue;
        anchors.emplace_back(1, a);
        for (size_t j = 0; j < map_.size(); ++j)
            if (matches(features[a], j)) anchors.back().push_back(j);
    }
    std::stable_sort(anchors.begin(), anchors.end(),
                     [](const auto& x, const auto& y) { return x.size() < y.size(); });
    std::vector<Place> places;
    std::unordered_set<long long> tried;  // guesses by cells of the tolerance
    const double cell = std::max(options_.tolerance, 1e-6);
    for (const auto& anchor : anchors) {
        const size_t a = anchor.front();
        for (size_t m = 1; m < anchor.size() && tried.size() < kConsensusGuesses; ++m) {
            const TPoint2D guess = map_[anchor[m]] - features[a].at;
            if (!tried.insert(cellKey(std::llround(guess.x / cell), std::llround(guess.y / cell)))
                     .second)
                continue;
            TVector2D sum{0, 0};
            size_t landed = 0;
            for (size_t k = 0; k < features.size(); ++k) {
                if (!inMap[k]) continue;
                if (const auto v = vertexNear(guess + features[k].at, features[k]))
                    sum += map_[*v] - features[k].at, ++landed;
            }
            if (landed >= need) places.push_back({landed, sum * (1.0 / double(landed))});
        }
    }
    // the best supported first; one place per tolerance; at most kConsensusPlaces verified
    std::stable_sort(places.begin(), places.end(),
                     [](const Place& a, const Place& b) { return a.landed > b.landed; });
    std::vector<TPoint2D> out;
    for (const auto& p : places) {
        if (out.size() == kConsensusPlaces) break;
        if (std::none_of(out.begin(), out.end(), [&](const TPoint2D& q) {
                return (q - p.at).norm() <= options_.tolerance;
            }))
            out.push_back(p.at);
    }
    return out;
}

std::vector<Hypothesis> HypothesisGenerator::generate(const VisibilityPolygon& V,
                                                      HypothesisStats* stats,
                                                      const Verify& secondChance) const {
    if (V.size() < 3)
        throw Error(
            "hypothesis generation: the scan's visibility polygon has fewer than 3 "
            "corners (a scan too noisy for [polymap] tolerance and angle_tolerance? "
            "see scan_range_sigma)");
    const std::vector<Feature> features = featuresOf(V);
    if (features.empty())
        throw Error(
            "hypothesis generation: the visibility polygon has no corner and no window "
            "end to match against the map");
    // The anchor: the feature that the fewest map vertices match. A feature that no vertex of
    // the map matches is not a corner of the map: a scan lost a wall too short to see (a
    // step seen edge-on) and two walls that do not meet in P met in V. It can neither anchor
    // nor be required to land on a vertex; the comparison of V with V(p) below still judges
    // the whole view.
    std::vector<size_t> bestMatches;
    std::vector<bool> inMap(features.size(), false);
    size_t anchor = features.size();
    for (size_t f = 0; f < features.size(); ++f) {
        std::vector<size_t> m;
        for (size_t j = 0; j < map_.size(); ++j)
            if (matches(features[f], j)) m.push_back(j);
        inMap[f] = !m.empty();
        if (inMap[f] && (anchor == features.size() || m.size() < bestMatches.size()))
            bestMatches = std::move(m), anchor = f;
    }
    HypothesisStats st;
    st.features = features.size();
    st.proposed = bestMatches.size();
    if (anchor == features.size()) {  // no feature is the map's: no place fits
        if (stats) *stats = st;
        return {};
    }

    TPoint2D lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    TPoint2D hi = -lo;
    for (const auto& p : V.vertices)
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    const double step = std::max(options_.tolerance / 4, (hi - lo).norm() / 500);

    std::vector<Hypothesis> H;
    // Step 4: p in P (noise may push it out by up to the tolerance), then V(p) against V.
    const auto verify = [&](TPoint2D p) {
        if (const auto loc = triangulation_.locate(p);
            loc.triangle == Triangulation::kNone || !triangulation_[loc.triangle].inside) {
            if (map_.locate(p, options_.tolerance) == common::Polygon::Where::Outside) return;
            p = map_.closestBoundaryPoint(p).first;
        }
        ++st.verified;
        // Vertex by vertex when V and V(p) pair up (an exact or clean V: O(|V|)), else the
        // sampled boundary distance (O(|V|^2), for a scan's V whose corners differ).
        const VisibilityPolygon Vp = visibilityPolygon(triangulation_, p);
        double mismatch = vertexwiseDistance(V, Vp);
        if (mismatch > options_.tolerance) mismatch = boundaryDistance(V, Vp, step);
        if (mismatch <= options_.tolerance)
            H.push_back({p, {0, 0}, mismatch});
        else if (const auto second = secondChance ? secondChance(p, Vp) : std::nullopt)
            H.push_back({p, {0, 0}, *second});
    };
    for (size_t j : bestMatches) {
        const TPoint2D guess = map_[j] - features[anchor].at;
        // Every feature must land on a matching vertex; their mean offset refines the guess.
        TVector2D sum{0, 0};
        bool all = true;
        for (size_t k = 0; k < features.size(); ++k) {
            if (!inMap[k]) continue;
            const auto& f = features[k];
            const auto v = vertexNear(guess + f.at, f);
            if (!v) {
                all = false;
                break;
            }
            sum += map_[*v] - f.at;
        }
        if (all) verify(sum * (1.0 / double(std::count(inMap.begin(), inMap.end(), true))));
    }
    if (H.empty() && secondChance) {
        // None where every feature lands: a traced building's view has corners of its own
        // (a laser fan's fringe, a wall the trace bent) that anchor a wrong place or land on
        // no vertex at the true one. A consensus instead: every feature anchors in turn, and
        // the places where the most features land on matching vertices are verified as above.
        const auto places = consensusPlaces(features, inMap);
        st.proposed += places.size();
        for (const auto& p : places) verify(p);
    }
    std::sort(H.begin(), H.end(), [](const Hypothesis& a, const Hypothesis& b) {
        return a.point.x < b.point.x || (a.point.x == b.point.x && a.point.y < b.point.y);
    });
    for (auto& h : H) h.translation = h.point - H.front().point;
    if (stats) *stats = st;
    return H;
}

}  // namespace mrloc::polymap
