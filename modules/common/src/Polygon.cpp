#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/common/Polygon.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

namespace mrloc::common {

double distanceToSegment(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b) {
    return (p - closestOnSegment(p, a, b)).norm();
}

TPoint2D closestOnSegment(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b) {
    const TVector2D ab = b - a;
    const double len2 = dot(ab, ab);
    if (len2 == 0) return a;
    const double s = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
    return a + ab * s;
}

namespace {

std::string vertexName(size_t i, const std::vector<TPoint2D>& v) {
    return mrpt::format("vertex %zu (%g %g)", i + 1, v[i].x, v[i].y);
}

/** Closed segments a-b and c-d share a point (within eps). */
bool segmentsTouch(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, const TPoint2D& d,
                   double eps) {
    const TVector2D ab = b - a, cd = d - c;
    const double d1 = cross(ab, c - a), d2 = cross(ab, d - a);
    const double d3 = cross(cd, a - c), d4 = cross(cd, b - c);
    const double lab = ab.norm(), lcd = cd.norm();
    const auto side = [eps](double c, double len) {
        return c > eps * len ? 1 : (c < -eps * len ? -1 : 0);
    };
    const int s1 = side(d1, lab), s2 = side(d2, lab), s3 = side(d3, lcd), s4 = side(d4, lcd);
    if (s1 * s2 < 0 && s3 * s4 < 0) return true;  // proper crossing
    // Touching or collinear overlap: some endpoint lies on the other segment.
    return distanceToSegment(c, a, b) <= eps || distanceToSegment(d, a, b) <= eps ||
           distanceToSegment(a, c, d) <= eps || distanceToSegment(b, c, d) <= eps;
}

/** Two vertices within eps of each other, if any: O(n log n) after sorting by x. */
std::optional<std::pair<size_t, size_t>> repeatedVertex(const std::vector<TPoint2D>& v,
                                                        double eps) {
    std::vector<size_t> order(v.size());
    for (size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return v[a].x < v[b].x || (v[a].x == v[b].x && a < b); });
    for (size_t k = 0; k < order.size(); ++k)
        for (size_t m = k + 1; m < order.size() && v[order[m]].x - v[order[k]].x <= eps; ++m)
            if ((v[order[k]] - v[order[m]]).norm() <= eps)
                return std::make_pair(std::min(order[k], order[m]), std::max(order[k], order[m]));
    return std::nullopt;
}

/** The first touching pair by testing all pairs: only when the sweep's order broke, which
 *  two crossing edges cause (the sweep then need not have met them side by side). */
template <class Touch>
std::optional<std::pair<size_t, size_t>> everyPair(size_t n, const Touch& touch) {
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            if (touch(i, j)) return std::make_pair(i, j);
    return std::nullopt;
}

bool lexLess(const TPoint2D& a, const TPoint2D& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

/** Two non-adjacent edges (edge i runs from v[i] to v[next[i]]) that cross or touch (within
 *  eps), if any: the Shamos-Hoey sweep
 *  (Shamos and Hoey, "Geometric intersection problems", FOCS 1976), O(n log n), ordering the
 *  sweep's edges with exact orientations. Edges closer than eps without touching are found
 *  where the sweep holds them side by side. */
std::optional<std::pair<size_t, size_t>> touchingEdges(const std::vector<TPoint2D>& v,
                                                       const std::vector<size_t>& next,
                                                       double eps) {
    const size_t n = v.size();
    struct Edge {
        TPoint2D left, right;
    };
    std::vector<Edge> edges(n);
    for (size_t i = 0; i < n; ++i) {
        const TPoint2D &a = v[i], &b = v[next[i]];
        edges[i] = lexLess(a, b) ? Edge{a, b} : Edge{b, a};
    }
    // s below t where the sweep meets both; valid while no two edges of the set cross.
    const auto below = [&edges](size_t s, size_t t) {
        if (s == t) return false;
        const Edge &S = edges[s], &T = edges[t];
        if (!lexLess(S.left, T.left)) {  // S starts later: where is its start against T?
            if (const int o = orientation(T.left, T.right, S.left)) return o < 0;
            if (const int o = orientation(T.left, T.right, S.right)) return o < 0;
        } else {
            if (const int o = orientation(S.left, S.right, T.left)) return o > 0;
            if (const int o = orientation(S.left, S.right, T.right)) return o > 0;
        }
        return s < t;
    };
    std::set<size_t, decltype(below)> status(below);
    const auto adjacent = [&next](size_t i, size_t j) { return next[i] == j || next[j] == i; };
    const auto touch = [&](size_t i, size_t j) {
        return !adjacent(i, j) &&
               segmentsTouch(edges[i].left, edges[i].right, edges[j].left, edges[j].right, eps);
    };
    // Events: removals before insertions at one point, so an edge through a vertex meets
    // the edges leaving it.
    struct Event {
        TPoint2D at;
        bool insert;
        size_t edge;
    };
    std::vector<Event> events;
    events.reserve(2 * n);
    for (size_t i = 0; i < n; ++i) {
        events.push_back({edges[i].left, true, i});
        events.push_back({edges[i].right, false, i});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        if (lexLess(a.at, b.at)) return true;
        if (lexLess(b.at, a.at)) return false;
        if (a.insert != b.insert) return !a.insert;
        return a.edge < b.edge;
    });
    for (const auto& e : events) {
        if (e.insert) {
            const auto it = status.insert(e.edge).first;
            if (it != status.begin() && touch(*std::prev(it), e.edge))
                return std::make_pair(*std::prev(it), e.edge);
            if (std::next(it) != status.end() && touch(*std::next(it), e.edge))
                return std::make_pair(*std::next(it), e.edge);
        } else {
            const auto it = status.find(e.edge);
            if (it == status.end()) return everyPair(edges.size(), touch);  // order broke
            if (it != status.begin() && std::next(it) != status.end() &&
                touch(*std::prev(it), *std::next(it)))
                return std::make_pair(*std::prev(it), *std::next(it));
            status.erase(it);
        }
    }
    return std::nullopt;
}

}  // namespace

Polygon Polygon::fromVertices(std::vector<TPoint2D> v, const std::string& what) {
    const size_t n = v.size();
    if (n < 3)
        throw Error(what + ": a polygon needs at least 3 vertices, got " + std::to_string(n));
    if (n > kMaxVertices)
        throw Error(what + ": " + std::to_string(n) + " vertices, more than the " +
                    std::to_string(kMaxVertices) + " mrloc takes");
    Polygon P;
    P.min_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    P.max_ = -P.min_;
    for (size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y))
            throw Error(what + ": vertex " + std::to_string(i + 1) + " is not a finite number");
        if (std::abs(v[i].x) > kMaxCoordinate || std::abs(v[i].y) > kMaxCoordinate)
            throw Error(what + ": vertex " + std::to_string(i + 1) + " lies beyond " +
                        std::to_string(int(kMaxCoordinate)) + " m of the origin");
        P.min_ = {std::min(P.min_.x, v[i].x), std::min(P.min_.y, v[i].y)};
        P.max_ = {std::max(P.max_.x, v[i].x), std::max(P.max_.y, v[i].y)};
    }
    P.eps_ = 1e-9 * std::max((P.max_ - P.min_).norm(), 1e-300);
    const double eps = P.eps_;
    if (const auto repeat = repeatedVertex(v, eps))
        throw Error(what + ": " + vertexName(repeat->first, v) + " repeats " +
                    vertexName(repeat->second, v));
    double twiceArea = 0;
    for (size_t i = 0; i < n; ++i) twiceArea += cross(v[i], v[(i + 1) % n]);
    if (std::abs(twiceArea) <= eps * (P.max_ - P.min_).norm())
        throw Error(what + ": the polygon has no area (all vertices on one line?)");
    if (twiceArea < 0) std::reverse(v.begin(), v.end());  // clockwise input: reorient
    for (size_t i = 0; i < n; ++i) {
        const TPoint2D &a = v[(i + n - 1) % n], &b = v[i], &c = v[(i + 1) % n];
        const TVector2D ba = a - b, bc = c - b;
        if (std::abs(cross(ba, bc)) <= eps * std::max(ba.norm(), bc.norm()) && dot(ba, bc) > 0)
            throw Error(what + ": " + vertexName(i, v) +
                        " is a collinear duplicate: its two edges overlap (a zero-width spike)");
    }
    std::vector<size_t> next(n);
    for (size_t i = 0; i < n; ++i) next[i] = (i + 1) % n;
    if (const auto meet = touchingEdges(v, next, eps)) {
        const size_t i = std::min(meet->first, meet->second),
                     j = std::max(meet->first, meet->second);
        throw Error(what + mrpt::format(": the polygon intersects itself: edge %zu-%zu "
                                        "meets edge %zu-%zu",
                                        i + 1, i + 2, j + 1, (j + 1) % n + 1));
    }
    P.v_ = std::move(v);
    P.setSingleRing();
    return P;
}

void Polygon::setSingleRing() {
    ringStart_ = {0, v_.size()};
    ring_.assign(v_.size(), 0);
}

Polygon Polygon::fromRings(std::vector<std::vector<TPoint2D>> rings, const std::string& what,
                           size_t maxVertices, const std::vector<int>& ringLines) {
    if (rings.empty()) throw Error(what + ": no vertices");
    if (rings.size() == 1) return fromVertices(std::move(rings[0]), what);
    size_t total = 0;
    for (const auto& r : rings) total += r.size();
    if (total > maxVertices)
        throw Error(what + ": " + std::to_string(total) + " vertices, more than the " +
                    std::to_string(maxVertices) + " mrloc takes");
    const auto ringName = [&ringLines](size_t r) {
        return r < ringLines.size() ? mrpt::format("ring %zu (line %d)", r + 1, ringLines[r])
                                    : mrpt::format("ring %zu", r + 1);
    };
    // each ring on its own: finite, bounded, simple, with area (and counter-clockwise)
    std::vector<Polygon> parts;
    for (size_t r = 0; r < rings.size(); ++r)
        parts.push_back(fromVertices(std::move(rings[r]), what + " (" + ringName(r) + ")"));
    Polygon P;
    P.min_ = parts[0].min_;
    P.max_ = parts[0].max_;
    P.eps_ = parts[0].eps_;
    P.ringStart_ = {0};
    for (size_t r = 0; r < parts.size(); ++r) {
        auto ring = parts[r].v_;
        if (r > 0) std::reverse(ring.begin(), ring.end());  // holes clockwise: free space left
        P.v_.insert(P.v_.end(), ring.begin(), ring.end());
        P.ring_.insert(P.ring_.end(), ring.size(), uint32_t(r));
        P.ringStart_.push_back(P.v_.size());
    }
    // every hole inside the outer ring and outside the other holes (tested at one vertex:
    // the sweep below then rules out any crossing); boxes first, so the cost stays near n
    for (size_t r = 1; r < parts.size(); ++r) {
        const TPoint2D& at = parts[r].v_[0];
        if (parts[0].locate(at) != Where::Inside)
            throw Error(what + ": " + ringName(r) +
                        mrpt::format(", a hole, is not inside the outer ring (ring 1) at its "
                                     "vertex (%g %g)",
                                     at.x, at.y));
        for (size_t q = 1; q < parts.size(); ++q) {
            const auto& h = parts[q];
            if (q == r || at.x < h.min_.x || at.y < h.min_.y || at.x > h.max_.x || at.y > h.max_.y)
                continue;
            if (h.locate(at) == Where::Inside)
                throw Error(what + ": " + ringName(r) + ", a hole, lies inside " + ringName(q) +
                            ", another hole");
        }
    }
    // Two rings through one point: the sweep below misses it where one ring's edges all end
    // there and the other's all begin there (they are never side by side in its status).
    if (const auto repeat = repeatedVertex(P.v_, P.eps_)) {
        const TPoint2D& at = P.v_[repeat->first];
        throw Error(what + ": two rings cross or touch: " + ringName(P.ring_[repeat->second]) +
                    " and " + ringName(P.ring_[repeat->first]) +
                    mrpt::format(" share the vertex (%g %g)", at.x, at.y));
    }
    std::vector<size_t> next(P.v_.size());
    for (size_t i = 0; i < next.size(); ++i) next[i] = P.next(i);
    if (const auto meet = touchingEdges(P.v_, next, P.eps_)) {
        const auto name = [&P, &ringName](size_t e) {
            return ringName(P.ring_[e]) + mrpt::format(" edge (%g %g)-(%g %g)", P.v_[e].x,
                                                       P.v_[e].y, P.v_[P.next(e)].x,
                                                       P.v_[P.next(e)].y);
        };
        throw Error(what + ": two rings cross or touch: " + name(meet->first) + " meets " +
                    name(meet->second));
    }
    return P;
}

std::vector<Polygon::Ring> Polygon::readRings(const std::string& path, size_t maxVertices,
                                              size_t maxRings) {
    checkReadableFile(path, "polygon map", 64u << 20);  // not a FIFO, a device or a folder
    std::ifstream in(path);
    if (!in) throw Error("polygon map " + path + ": cannot open the file");
    std::vector<Ring> rings(1);
    size_t vertices = 0;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const bool blank = line.find_first_not_of(" \t\r") == std::string::npos;
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream ls(line);
        std::string first;
        if (!(ls >> first)) {
            // a blank line (not a comment line) after vertices ends a ring
            if (blank && !rings.back().vertices.empty()) {
                if (rings.size() >= maxRings)
                    throw Error(path + ":" + std::to_string(lineNo) + ": more than the " +
                                std::to_string(maxRings) + " rings mrloc takes");
                rings.emplace_back();
            }
            continue;
        }
        ls.clear();
        ls.str(line);
        double x, y;
        std::string rest;
        if (!(ls >> x >> y) || (ls >> rest))
            throw Error(path + ":" + std::to_string(lineNo) + ": expected \"x y\", got \"" + line +
                        "\"");
        if (rings.back().vertices.empty()) rings.back().firstLine = lineNo;
        rings.back().vertices.push_back({x, y});
        if (++vertices > maxVertices)
            throw Error(path + ":" + std::to_string(lineNo) + ": more than the " +
                        std::to_string(maxVertices) + " vertices mrloc takes");
    }
    if (in.bad()) throw Error("polygon map " + path + ": read error");
    if (rings.back().vertices.empty()) rings.pop_back();
    return rings;
}

Polygon Polygon::load(const std::string& path) {
    auto rings = readRings(path, kMaxVertices, kMaxVertices / 3);
    if (rings.size() <= 1)
        return fromVertices(rings.empty() ? std::vector<TPoint2D>{} : std::move(rings[0].vertices),
                            path);
    std::vector<std::vector<TPoint2D>> vertices;
    std::vector<int> lines;
    for (auto& r : rings) {
        vertices.push_back(std::move(r.vertices));
        lines.push_back(r.firstLine);
    }
    return fromRings(std::move(vertices), path, kMaxVertices, lines);
}

void Polygon::save(const std::string& path, const std::string& comment) const {
    std::ostringstream out;
    if (hasHoles())
        out << "# polygon map, " << v_.size() << " vertices in " << ringCount()
            << " rings: the outer boundary, then holes, separated by a blank line\n";
    else
        out << "# polygon map, " << v_.size() << " vertices, counter-clockwise\n";
    if (!comment.empty()) out << "# " << comment << "\n";
    out.precision(17);
    for (size_t i = 0; i < v_.size(); ++i) {
        if (i > 0 && ring_[i] != ring_[i - 1]) out << "\n";
        out << v_[i].x << " " << v_[i].y << "\n";
    }
    writeFileAtomically(path, out.str());
}

bool Polygon::isReflex(size_t i) const {
    return cross(v_[i] - v_[prev(i)], v_[next(i)] - v_[i]) < 0;
}

double Polygon::area() const {
    double a = 0;
    for (size_t i = 0; i < v_.size(); ++i) a += cross(v_[i], v_[next(i)]);
    return 0.5 * a;
}

Polygon::Where Polygon::locate(const TPoint2D& p, double tol) const {
    if (tol < 0) tol = eps_;
    bool inside = false;
    for (size_t i = 0; i < v_.size(); ++i) {  // even-odd over every ring's edges
        const TPoint2D &a = v_[prev(i)], &b = v_[i];
        if (distanceToSegment(p, a, b) <= tol) return Where::Boundary;
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside ? Where::Inside : Where::Outside;
}

std::pair<TPoint2D, size_t> Polygon::closestBoundaryPoint(const TPoint2D& p) const {
    std::pair<TPoint2D, size_t> best{v_[0], 0};
    double bestDist = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < v_.size(); ++i) {
        const TPoint2D c = closestOnSegment(p, v_[i], v_[next(i)]);
        if (const double d = (p - c).norm(); d < bestDist) best = {c, i}, bestDist = d;
    }
    return best;
}

std::optional<double> raySegmentHit(const TPoint2D& a, const TPoint2D& b, const TPoint2D& o,
                                    const TVector2D& dir, double tMin) {
    const TVector2D e = b - a;
    const double denom = cross(dir, e);
    if (denom == 0) return std::nullopt;  // parallel: its ends are met through the neighbours
    const TVector2D ao = a - o;
    const double s = cross(ao, dir) / denom;
    if (s < -1e-12 || s > 1 + 1e-12) return std::nullopt;
    const double t = cross(ao, e) / denom;
    if (t > tMin) return t;
    return std::nullopt;
}

std::optional<std::pair<double, size_t>> Polygon::rayCastEdge(const TPoint2D& o,
                                                              const TVector2D& dir,
                                                              double tMin) const {
    std::optional<std::pair<double, size_t>> best;
    for (size_t i = 0; i < v_.size(); ++i)
        if (const auto t = raySegmentHit(v_[i], v_[next(i)], o, dir, tMin);
            t && (!best || *t < best->first))
            best = std::make_pair(*t, i);
    return best;
}

std::optional<std::pair<double, size_t>> Polygon::rayCastEdge(
    const TPoint2D& o, const TVector2D& dir, double tMin, const std::vector<size_t>& edges) const {
    std::optional<std::pair<double, size_t>> best;
    for (size_t i : edges)
        if (const auto t = raySegmentHit(v_[i], v_[next(i)], o, dir, tMin);
            t && (!best || *t < best->first))
            best = std::make_pair(*t, i);
    return best;
}

std::optional<double> Polygon::rayCast(const TPoint2D& o, const TVector2D& dir, double tMin) const {
    if (const auto hit = rayCastEdge(o, dir, tMin)) return hit->first;
    return std::nullopt;
}

}  // namespace mrloc::common
