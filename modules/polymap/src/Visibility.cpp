#include <mrloc/common/Error.h>
#include <mrloc/polymap/Visibility.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mrloc::polymap {

using common::cross;
using common::dot;

bool VisibilityPolygon::isRadial(size_t i) const {
    const TPoint2D& a = vertices[i];
    const TPoint2D& b = vertices[(i + 1) % vertices.size()];
    const double la = a.norm(), lb = b.norm();
    if (la == 0 || lb == 0) return true;  // an edge from the viewpoint itself
    return std::abs(cross(a, b)) <= std::max(angularTolerance, 1e-12) * la * lb;
}

double VisibilityPolygon::radius(const TVector2D& dir) const {
    double best = 0;  // star-shaped about the origin: the farthest crossing is the boundary
    for (size_t i = 0; i < vertices.size(); ++i)
        if (const auto t = common::raySegmentHit(vertices[i], vertices[(i + 1) % vertices.size()],
                                                 {0, 0}, dir, 0))
            best = std::max(best, *t);
    return best;
}

std::vector<TPoint2D> VisibilityPolygon::placedAt(const TPoint2D& p) const {
    std::vector<TPoint2D> out;
    out.reserve(vertices.size());
    for (const auto& v : vertices) out.push_back(v + p);
    return out;
}

namespace {

/** Counter-clockwise order of directions starting at angle -pi (exact for exact input). */
bool angleLess(const TVector2D& a, const TVector2D& b) {
    const auto half = [](const TVector2D& d) { return d.y < 0 || (d.y == 0 && d.x < 0) ? 0 : 1; };
    const int ha = half(a), hb = half(b);
    if (ha != hb) return ha < hb;
    return cross(a, b) > 0;
}

/** Where q sits in P: strictly inside, on the edge `edge`, or on the vertex `vertex`. */
struct Seat {
    std::optional<size_t> vertex, edge;
};

Seat seatOf(const common::Polygon& P, TPoint2D& q) {
    const double eps = P.epsilon();
    for (size_t i = 0; i < P.size(); ++i)
        if ((P[i] - q).norm() <= eps) {
            q = P[i];  // snap, so that directions along its edges are exact
            return {i, std::nullopt};
        }
    switch (P.locate(q)) {
        case common::Polygon::Where::Inside:
            return {};
        case common::Polygon::Where::Boundary:
            return {std::nullopt, P.closestBoundaryPoint(q).second};
        default:
            break;
    }
    throw Error(
        mrpt::format("visibility polygon: the viewpoint (%.9g %.9g) is outside the map", q.x, q.y));
}

/** Does a ray from q along m start into P's interior? */
bool entersInterior(const common::Polygon& P, const Seat& seat, const TVector2D& m) {
    if (seat.edge) {
        const size_t e = *seat.edge;
        return cross(P[P.next(e)] - P[e], m) > 0;
    }
    if (seat.vertex) {
        const size_t i = *seat.vertex;
        const double leftOfOut = cross(P[P.next(i)] - P[i], m);
        const double leftOfIn = cross(P[i] - P[P.prev(i)], m);
        return P.isReflex(i) ? (leftOfOut > 0 || leftOfIn > 0) : (leftOfOut > 0 && leftOfIn > 0);
    }
    return true;
}

/** One direction from the viewpoint, up to rounding. */
bool sameDirection(const TVector2D& a, const TVector2D& b) {
    return dot(a, b) > 0 && std::abs(cross(a, b)) <= 1e-12 * a.norm() * b.norm();
}

struct Direction {
    TVector2D d;                  ///< towards the first vertex of the group
    std::vector<size_t> members;  ///< P's vertices in this direction
};

}  // namespace

VisibilityPolygon visibilityPolygon(const common::Polygon& P, const TPoint2D& viewpoint) {
    TPoint2D q = viewpoint;
    const Seat seat = seatOf(P, q);
    const double eps = P.epsilon();

    // Directions of P's vertices around q, grouped when collinear and on the same side.
    std::vector<size_t> order;
    for (size_t i = 0; i < P.size(); ++i)
        if (!(seat.vertex && *seat.vertex == i)) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return angleLess(P[a] - q, P[b] - q); });
    std::vector<Direction> dirs;
    for (size_t i : order) {
        const TVector2D d = P[i] - q;
        if (!dirs.empty()) {
            const TVector2D& last = dirs.back().d;
            if (sameDirection(last, d)) {
                dirs.back().members.push_back(i);
                continue;
            }
        }
        dirs.push_back({d, {i}});
    }
    if (dirs.size() > 1) {  // the first and last groups may be one direction (angle -pi)
        const TVector2D &a = dirs.front().d, &b = dirs.back().d;
        if (sameDirection(a, b)) {
            dirs.front().members.insert(dirs.front().members.end(), dirs.back().members.begin(),
                                        dirs.back().members.end());
            dirs.pop_back();
        }
    }
    const size_t m = dirs.size();
    if (m < 2) throw Error("visibility polygon: degenerate map around the viewpoint");

    // The wedges each edge spans as seen from q: a wedge's ray is cast against those edges
    // only, which keeps the sweep near-linear unless many long edges cross many wedges.
    std::vector<size_t> groupOf(P.size(), m);
    for (size_t k = 0; k < m; ++k)
        for (size_t i : dirs[k].members) groupOf[i] = k;
    std::vector<std::vector<size_t>> spanning(m);
    for (size_t e = 0; e < P.size(); ++e) {
        const size_t ga = groupOf[e], gb = groupOf[P.next(e)];
        if (ga == m || gb == m) continue;  // an edge from q itself
        const double c = cross(P[e] - q, P[P.next(e)] - q);
        if (c == 0) continue;  // seen edge-on
        for (size_t k = c > 0 ? ga : gb, to = c > 0 ? gb : ga; k != to; k = (k + 1) % m)
            spanning[k].push_back(e);
    }

    // Nearest edge in each open wedge (dirs[k], dirs[k+1]); none if the wedge leaves P.
    std::vector<std::optional<size_t>> wedgeEdge(m);
    for (size_t k = 0; k < m; ++k) {
        const TVector2D& a = dirs[k].d;
        const TVector2D& b = dirs[(k + 1) % m].d;
        TVector2D mid;
        if (cross(a, b) > 0)
            mid = a * (1 / a.norm()) + b * (1 / b.norm());
        else
            mid = TVector2D(-a.y, a.x);  // the wedge spans half a turn or more
        mid = mid * (1 / mid.norm());
        if (!entersInterior(P, seat, mid)) continue;
        auto hit = P.rayCastEdge(q, mid, eps, spanning[k]);
        if (!hit) hit = P.rayCastEdge(q, mid, eps);  // only if rounding misfiled an edge
        if (!hit) throw Error("visibility polygon: a ray from the viewpoint left the map");
        wedgeEdge[k] = hit->second;
    }

    // Where edge e meets the ray along direction k: a vertex of the group exactly, else the
    // intersection of the ray with the edge's line.
    const auto pointOn = [&](size_t e, size_t k) -> TPoint2D {
        for (size_t i : dirs[k].members)
            if (i == e || i == P.next(e)) return P[i];
        const TPoint2D& a = P[e];
        const TVector2D ev = P[P.next(e)] - a, d = dirs[k].d;
        const double denom = cross(d, ev);
        if (denom == 0) return (P[e] - q).norm() < (P[P.next(e)] - q).norm() ? P[e] : P[P.next(e)];
        return q + d * (cross(a - q, ev) / denom);
    };

    std::vector<TPoint2D> boundary;
    const auto emit = [&](const TPoint2D& p) {
        if (boundary.empty() || (boundary.back() - p).norm() > eps) boundary.push_back(p);
    };
    for (size_t k = 0; k < m; ++k) {
        const auto& arriving = wedgeEdge[(k + m - 1) % m];
        const auto& leaving = wedgeEdge[k];
        emit(arriving ? pointOn(*arriving, k) : q);
        emit(leaving ? pointOn(*leaving, k) : q);
    }
    while (boundary.size() > 1 && (boundary.front() - boundary.back()).norm() <= eps)
        boundary.pop_back();

    // Drop vertices that lie on the straight line through their neighbours.
    VisibilityPolygon V;
    bool changed = true;
    while (changed && boundary.size() > 3) {
        changed = false;
        for (size_t i = 0; i < boundary.size() && boundary.size() > 3; ++i) {
            const size_t n = boundary.size();
            const TPoint2D &a = boundary[(i + n - 1) % n], &b = boundary[i],
                           &c = boundary[(i + 1) % n];
            const TVector2D ab = b - a, bc = c - b;
            if (std::abs(cross(ab, bc)) <= eps * (c - a).norm() && dot(ab, bc) > 0) {
                boundary.erase(boundary.begin() + (long)i);
                changed = true;
                --i;
            }
        }
    }
    V.vertices.reserve(boundary.size());
    for (const auto& p : boundary) V.vertices.push_back(p - q);
    return V;
}

namespace {

double directedDistance(const VisibilityPolygon& a, const VisibilityPolygon& b, double step) {
    double worst = 0;
    const size_t na = a.size(), nb = b.size();
    for (size_t i = 0; i < na; ++i) {
        const TPoint2D& p0 = a.vertices[i];
        const TPoint2D& p1 = a.vertices[(i + 1) % na];
        const int samples = std::max(1, (int)std::ceil((p1 - p0).norm() / step));
        for (int s = 0; s < samples; ++s) {
            const TPoint2D p = p0 + (p1 - p0) * ((double)s / samples);
            double nearest = std::numeric_limits<double>::infinity();
            for (size_t j = 0; j < nb && nearest > worst; ++j)
                nearest = std::min(
                    nearest, common::distanceToSegment(p, b.vertices[j], b.vertices[(j + 1) % nb]));
            worst = std::max(worst, nearest);
        }
    }
    return worst;
}

}  // namespace

double boundaryDistance(const VisibilityPolygon& a, const VisibilityPolygon& b, double step) {
    if (a.size() < 3 || b.size() < 3) return std::numeric_limits<double>::infinity();
    return std::max(directedDistance(a, b, step), directedDistance(b, a, step));
}

}  // namespace mrloc::polymap
