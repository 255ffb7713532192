#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace mrloc::polymap {

using common::orientation;

namespace {

/** The line from `from` through P's vertex v does not cut into the free space at v: both
 *  of v's neighbours lie on one side of it (or on it). Only such lines can carry a taut path
 *  bending at v. */
bool tangentAt(const common::Polygon& P, size_t v, const TPoint2D& from) {
    const int a = orientation(from, P[v], P[P.prev(v)]), b = orientation(from, P[v], P[P.next(v)]);
    return a * b >= 0;
}

/** q is seen from V's viewpoint o (boundary included, up to the rounding of V's corners). */
bool sees(const RadialProfile& V, const TPoint2D& o, const TPoint2D& q, double tol) {
    const TVector2D d = q - o;
    const double length = d.norm();
    return length <= tol || V.radius(std::atan2(d.y, d.x)) >= length - tol;
}

}  // namespace

struct ShortestPaths::Source {
    Source(const TPoint2D& a, VisibilityPolygon v) : at(a), view(std::move(v)), seen(view) {}
    Source(const Source&) = delete;  // seen refers to view
    Source& operator=(const Source&) = delete;

    TPoint2D at;
    VisibilityPolygon view;
    RadialProfile seen;            ///< view's radius by direction: sorted once, asked per goal
    std::vector<double> distance;  ///< per reflex vertex (infinity: unreachable)
    std::vector<int> previous;     ///< per reflex vertex: the one before it, or -1 (from at)
};

ShortestPaths::~ShortestPaths() = default;

ShortestPaths::ShortestPaths(const Triangulation& T) : T_(T) {
    if (T.polygon().hasHoles()) {
        buildVisibilityGraph();
        return;
    }
    const size_t count = T.triangles().size();
    parent_.assign(count, Triangulation::kNone);
    depth_.assign(count, -1);
    int root = Triangulation::kNone;
    for (size_t t = 0; t < count && root == Triangulation::kNone; ++t)
        if (T[(int)t].inside) root = (int)t;
    std::vector<int> stack{root};
    depth_[(size_t)root] = 0;
    while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const int u = T[t].neighbour[(size_t)i];
            if (T[t].constrained[(size_t)i] || depth_[(size_t)u] >= 0) continue;
            parent_[(size_t)u] = t;
            depth_[(size_t)u] = depth_[(size_t)t] + 1;
            stack.push_back(u);
        }
    }
}

std::vector<int> ShortestPaths::sleeve(int s, int t) const {
    std::vector<int> fromS, fromT;
    while (depth_[(size_t)s] > depth_[(size_t)t]) fromS.push_back(s), s = parent_[(size_t)s];
    while (depth_[(size_t)t] > depth_[(size_t)s]) fromT.push_back(t), t = parent_[(size_t)t];
    while (s != t) {
        fromS.push_back(s), s = parent_[(size_t)s];
        fromT.push_back(t), t = parent_[(size_t)t];
    }
    fromS.push_back(s);  // the common ancestor
    fromS.insert(fromS.end(), fromT.rbegin(), fromT.rend());
    return fromS;
}

void ShortestPaths::buildVisibilityGraph() {
    const auto& P = T_.polygon();
    const double tol = 1e3 * P.epsilon();
    for (size_t v = 0; v < P.size(); ++v)
        if (P.isReflex(v)) reflex_.push_back(v);
    links_.resize(reflex_.size());
    for (size_t i = 0; i < reflex_.size(); ++i) {
        const TPoint2D& u = P[reflex_[i]];
        const VisibilityPolygon V = visibilityPolygon(T_, u);
        const RadialProfile profile(V);
        for (size_t j = i + 1; j < reflex_.size(); ++j) {
            const TPoint2D& w = P[reflex_[j]];
            if (!tangentAt(P, reflex_[i], w) || !tangentAt(P, reflex_[j], u)) continue;
            // an edge of P joins two vertices that see each other
            const bool edge = P.next(reflex_[i]) == reflex_[j] || P.next(reflex_[j]) == reflex_[i];
            if (!edge && !sees(profile, u, w, tol)) continue;
            const double length = (w - u).norm();
            links_[i].push_back({(int)j, length});
            links_[j].push_back({(int)i, length});
        }
    }
}

GeodesicPath ShortestPaths::graphPath(const TPoint2D& a, const TPoint2D& b) const {
    const auto& P = T_.polygon();
    const double tol = 1e3 * P.epsilon();
    T_.locateInside(a, "shortest path: the start");
    T_.locateInside(b, "shortest path: the goal");
    std::shared_ptr<const Source> source;
    {
        std::lock_guard<std::mutex> lock(sourceMutex_);
        if (lastSource_ && lastSource_->at == a) source = lastSource_;
    }
    if (!source) {
        auto s = std::make_shared<Source>(a, visibilityPolygon(T_, a));
        const size_t m = reflex_.size();
        s->distance.assign(m, std::numeric_limits<double>::infinity());
        s->previous.assign(m, -1);
        using Entry = std::pair<double, int>;
        std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
        for (size_t i = 0; i < m; ++i) {
            const TPoint2D& r = P[reflex_[i]];
            // no tangency asked of a query's own legs: a on an edge (a midpoint, off its line
            // by rounding) would lose the edge's own ends
            if (sees(s->seen, a, r, tol)) {
                s->distance[i] = (r - a).norm();
                queue.push({s->distance[i], (int)i});
            }
        }
        while (!queue.empty()) {
            const auto [d, i] = queue.top();
            queue.pop();
            if (d > s->distance[(size_t)i]) continue;
            for (const auto& link : links_[(size_t)i])
                if (d + link.length < s->distance[(size_t)link.to]) {
                    s->distance[(size_t)link.to] = d + link.length;
                    s->previous[(size_t)link.to] = i;
                    queue.push({d + link.length, link.to});
                }
        }
        source = s;
        std::lock_guard<std::mutex> lock(sourceMutex_);
        lastSource_ = source;
    }
    GeodesicPath out;
    if (sees(source->seen, a, b, tol)) {
        out.points = {a, b};
        if (a == b) out.points.pop_back();
        out.length = (b - a).norm();
        return out;
    }
    const VisibilityPolygon Vb = visibilityPolygon(T_, b);
    const RadialProfile fromB(Vb);
    double best = std::numeric_limits<double>::infinity();
    int last = -1;
    for (size_t i = 0; i < reflex_.size(); ++i) {
        const TPoint2D& r = P[reflex_[i]];
        if (!std::isfinite(source->distance[i])) continue;
        const double d = source->distance[i] + (b - r).norm();
        if (d < best && sees(fromB, b, r, tol)) best = d, last = (int)i;
    }
    if (last < 0)  // P's free space is connected: only rounding can leave b unreached
        throw Error(
            mrpt::format("shortest path: no path from (%g %g) to (%g %g)", a.x, a.y, b.x, b.y));
    out.points.push_back(b);
    for (int i = last; i >= 0; i = source->previous[(size_t)i])
        out.points.push_back(P[reflex_[(size_t)i]]);
    out.points.push_back(a);
    std::reverse(out.points.begin(), out.points.end());
    out.length = best;
    return out;
}

GeodesicPath ShortestPaths::path(const TPoint2D& a, const TPoint2D& b) const {
    if (T_.polygon().hasHoles()) return graphPath(a, b);
    const auto la = T_.locateInside(a, "shortest path: the start");
    const auto lb = T_.locateInside(b, "shortest path: the goal");
    const std::vector<int> triangles = sleeve(la.triangle, lb.triangle);
    // The portals: the edges the sleeve crosses, as (left, right) seen walking along it.
    std::vector<std::pair<TPoint2D, TPoint2D>> portals{{a, a}};
    for (size_t k = 0; k + 1 < triangles.size(); ++k) {
        const int i = T_.edgeTowards(triangles[k], triangles[k + 1]);
        const auto& tri = T_[triangles[k]];
        portals.push_back({T_.point(tri.to(i)), T_.point(tri.from(i))});
    }
    portals.push_back({b, b});

    // The funnel: an apex and the left and right chains' last points; a portal end that
    // narrows the funnel moves its side, one that crosses the other side makes that side's
    // point a corner of the path and the new apex.
    GeodesicPath out;
    out.points.push_back(a);
    // A restart from a corner can meet it again (portals sharing that vertex): once is enough.
    const auto corner = [&out](const TPoint2D& p) {
        if (out.points.back() != p) out.points.push_back(p);
    };
    TPoint2D apex = a, left = a, right = a;
    size_t apexAt = 0, leftAt = 0, rightAt = 0;
    for (size_t i = 1; i < portals.size(); ++i) {
        const auto& [l, r] = portals[i];
        if (orientation(apex, right, r) >= 0) {
            if (apex == right || orientation(apex, left, r) < 0) {
                right = r, rightAt = i;
            } else {
                corner(left);
                apex = right = left, apexAt = rightAt = leftAt;
                i = apexAt;
                continue;
            }
        }
        if (orientation(apex, left, l) <= 0) {
            if (apex == left || orientation(apex, right, l) > 0) {
                left = l, leftAt = i;
            } else {
                corner(right);
                apex = left = right, apexAt = leftAt = rightAt;
                i = apexAt;
                continue;
            }
        }
    }
    if (out.points.back() != b) out.points.push_back(b);
    for (size_t k = 0; k + 1 < out.points.size(); ++k)
        out.length += (out.points[k + 1] - out.points[k]).norm();
    return out;
}

}  // namespace mrloc::polymap
