#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/Visibility.h>
#include <mrpt/core/format.h>

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

RadialProfile::RadialProfile(const VisibilityPolygon& V) : V_(V) {
    const size_t n = V.size();
    std::vector<double> a(n);
    for (size_t i = 0; i < n; ++i) {
        if (V.vertices[i].norm() == 0) direct_ = true;
        a[i] = std::atan2(V.vertices[i].y, V.vertices[i].x);
    }
    if (direct_ || n < 3) {
        direct_ = true;
        return;
    }
    first_ = size_t(std::min_element(a.begin(), a.end()) - a.begin());
    angles_.reserve(n);
    for (size_t j = 0; j < n; ++j) {
        double t = a[(first_ + j) % n];
        // Counter-clockwise: never more than a rounding behind the last (radial edges).
        while (!angles_.empty() && t < angles_.back() - 1e-9) t += 2 * M_PI;
        angles_.push_back(t);
    }
}

double RadialProfile::radius(double angle) const {
    const TVector2D dir{std::cos(angle), std::sin(angle)};
    if (direct_) return V_.radius(dir);
    const size_t n = angles_.size();
    double t = angle;
    while (t < angles_.front()) t += 2 * M_PI;
    while (t >= angles_.front() + 2 * M_PI) t -= 2 * M_PI;
    // The edge from sorted vertex j - 1 to j spans t; its neighbours cover equal angles
    // (radial edges) and rounding in the sort.
    const size_t j = size_t(std::upper_bound(angles_.begin(), angles_.end(), t) - angles_.begin());
    double best = 0;
    for (long d = -3; d <= 2; ++d) {
        const size_t i = (first_ + size_t(long(j + n) + d)) % n;
        if (const auto hit =
                common::raySegmentHit(V_.vertices[i], V_.vertices[(i + 1) % n], {0, 0}, dir, 0))
            best = std::max(best, *hit);
    }
    return best;
}

std::vector<TPoint2D> VisibilityPolygon::placedAt(const TPoint2D& p) const {
    std::vector<TPoint2D> out;
    out.reserve(vertices.size());
    for (const auto& v : vertices) out.push_back(v + p);
    return out;
}

namespace {

using common::orientation;
using Tri = Triangulation;

/** Where the viewpoint sits: the fan of triangle edges around it, counter-clockwise, and
 *  for a viewpoint on P's boundary the P edges it leaves along and comes back along. */
struct Seat {
    TPoint2D q;                            ///< the viewpoint (snapped onto a vertex)
    std::vector<std::pair<int, int>> fan;  ///< (triangle, edge) seen first
    int firstEdge = -1, lastEdge = -1;     ///< P edges through q (boundary seats only)
};

/** The P edge, inside triangle t's edge i, that lies on P's boundary: the free space lies
 *  left of every ring's edges (holes run clockwise), so the edge runs from vertex from(i) to
 *  P.next(from(i)). */
int polygonEdge(const Tri& T, int t, int i) { return T[t].from(i); }

/** Fan of the inside triangles about vertex w, counter-clockwise, from P's edge w -> w+1 round
 *  to edge w-1 -> w. */
Seat vertexSeat(const Tri& T, int w) {
    std::vector<int> around;
    const int start = T.triangleAt(w);
    int t = start;
    do {
        around.push_back(t);
        t = T[t].neighbour[(size_t)((T.indexOf(t, w) + 1) % 3)];
    } while (t != start);
    const size_t m = around.size();
    size_t first = 0;
    while (!(T[around[first]].inside && !T[around[(first + m - 1) % m]].inside)) ++first;
    Seat seat;
    seat.q = T.point(w);
    for (size_t k = 0; k < m && T[around[(first + k) % m]].inside; ++k) {
        const int tri = around[(first + k) % m];
        seat.fan.push_back({tri, T.indexOf(tri, w)});
    }
    seat.firstEdge = w;
    seat.lastEdge = (int)T.polygon().prev((size_t)w);
    return seat;
}

/** Fan about a point on edge e of inside triangle t (and of its neighbour, unless e is P's). */
Seat edgeSeat(const Tri& T, const TPoint2D& q, int t, int e) {
    Seat seat;
    seat.q = q;
    seat.fan = {{t, (e + 1) % 3}, {t, (e + 2) % 3}};
    if (T[t].constrained[(size_t)e]) {
        seat.firstEdge = seat.lastEdge = polygonEdge(T, t, e);
    } else {
        const int u = T[t].neighbour[(size_t)e], j = T.edgeTowards(u, t);
        seat.fan.push_back({u, (j + 1) % 3});
        seat.fan.push_back({u, (j + 2) % 3});
    }
    return seat;
}

Seat seatOf(const Tri& T, const TPoint2D& q) {
    const auto loc = T.locateInside(q, "visibility polygon: the viewpoint");
    const auto& tri = T[loc.triangle];
    if (loc.vertex >= 0) return vertexSeat(T, tri.v[(size_t)loc.vertex]);
    for (int k = 0; k < 3; ++k)  // within P's tolerance of a vertex: on it
        if ((T.point(tri.v[(size_t)k]) - q).norm() <= T.polygon().epsilon())
            return vertexSeat(T, tri.v[(size_t)k]);
    if (loc.edge >= 0) return edgeSeat(T, q, loc.triangle, loc.edge);
    return {q, {{loc.triangle, 0}, {loc.triangle, 1}, {loc.triangle, 2}}, -1, -1};
}

/** Where the ray from q through d meets segment a-b: an endpoint exactly when the ray passes
 *  through it, else the intersection of the two lines, kept on the segment. */
TPoint2D hit(const TPoint2D& q, const TPoint2D& d, const TPoint2D& a, const TPoint2D& b) {
    const TVector2D r = d - q;
    if (orientation(q, d, a) == 0 && dot(a - q, r) > 0) return a;
    if (orientation(q, d, b) == 0 && dot(b - q, r) > 0) return b;
    const TVector2D e = b - a;
    const double s = std::clamp(cross(q - a, r) / cross(e, r), 0.0, 1.0);
    return a + e * s;
}

/** Two P edges on one line, in one direction (their shared vertex is no corner). */
bool straightOn(const common::Polygon& P, int e, int f) {
    if (e == f) return true;
    const TPoint2D &a = P[(size_t)e], &b = P[P.next((size_t)e)];
    const TPoint2D &c = P[(size_t)f], &d = P[P.next((size_t)f)];
    return orientation(a, b, c) == 0 && orientation(a, b, d) == 0 && dot(b - a, d - c) > 0;
}

}  // namespace

VisibilityPolygon visibilityPolygon(const Triangulation& T, const TPoint2D& viewpoint) {
    // Triangular expansion (Bungiu, Hemmer, Hershberger, Huang and Kroller, EuroCG 2014): the
    // view through each edge of the viewpoint's triangle is a cone bounded by rays through
    // the edge's ends; it is carried into the next triangle, split where that triangle's far
    // vertex lies strictly inside it, and stops at P's edges, each giving one visible piece.
    // Depth first, right part before left, so the pieces come out counter-clockwise.
    const Seat seat = seatOf(T, viewpoint);
    const TPoint2D& q = seat.q;
    struct Cone {
        int tri, edge;
        TPoint2D right, left;
    };
    std::vector<Cone> stack;
    for (auto it = seat.fan.rbegin(); it != seat.fan.rend(); ++it)
        stack.push_back({it->first, it->second, T.point(T[it->first].from(it->second)),
                         T.point(T[it->first].to(it->second))});
    std::vector<TPoint2D> boundary;
    std::vector<int> support;  // the P edge under boundary[k] -> boundary[k+1] (-1: window)
    while (!stack.empty()) {
        const Cone c = stack.back();
        stack.pop_back();
        const auto& tri = T[c.tri];
        const TPoint2D &x = T.point(tri.from(c.edge)), &y = T.point(tri.to(c.edge));
        if (tri.constrained[(size_t)c.edge]) {
            const TPoint2D a = hit(q, c.right, x, y), b = hit(q, c.left, x, y);
            if (a == b) continue;
            if (!boundary.empty() && boundary.back() == a) {
                support.back() = polygonEdge(T, c.tri, c.edge);
            } else {
                boundary.push_back(a);
                support.push_back(polygonEdge(T, c.tri, c.edge));
            }
            boundary.push_back(b);
            support.push_back(-1);
            continue;
        }
        const int u = tri.neighbour[(size_t)c.edge], j = T.edgeTowards(u, c.tri);
        const TPoint2D& w = T.point(T[u].v[(size_t)j]);
        const int rightEdge = (j + 1) % 3, leftEdge = (j + 2) % 3;  // x->w and w->y
        if (orientation(q, c.right, w) <= 0) {
            stack.push_back({u, leftEdge, c.right, c.left});
        } else if (orientation(q, c.left, w) >= 0) {
            stack.push_back({u, rightEdge, c.right, c.left});
        } else {
            stack.push_back({u, leftEdge, w, c.left});
            stack.push_back({u, rightEdge, c.right, w});
        }
    }
    if (seat.firstEdge >= 0) {  // on the boundary: q itself is a corner of V
        boundary.insert(boundary.begin(), q);
        support.insert(support.begin(), seat.firstEdge);
        support.back() = seat.lastEdge;
    } else if (boundary.size() > 1 && boundary.front() == boundary.back()) {
        boundary.pop_back();
        support.pop_back();
    }
    // A vertex between two pieces of one straight wall is no corner: dropped, decided on P's
    // edges (exact), not on the computed points.
    const auto& P = T.polygon();
    const size_t m = boundary.size();
    VisibilityPolygon V;
    V.vertices.reserve(m);
    for (size_t k = 0; k < m; ++k) {
        const int before = support[(k + m - 1) % m], after = support[k];
        if (m > 3 && before >= 0 && after >= 0 && straightOn(P, before, after)) continue;
        V.vertices.push_back(boundary[k] - q);
    }
    return V;
}

VisibilityPolygon visibilityPolygon(const common::Polygon& P, const TPoint2D& q) {
    return visibilityPolygon(Triangulation(P), q);
}

namespace {

double directedDistance(const VisibilityPolygon& a, const VisibilityPolygon& b, double step,
                        double stopAbove) {
    double worst = 0;
    const size_t na = a.size(), nb = b.size();
    const auto sample = [&](const TPoint2D& p) {
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < nb && nearest > worst; ++j)
            nearest = std::min(
                nearest, common::distanceToSegment(p, b.vertices[j], b.vertices[(j + 1) % nb]));
        worst = std::max(worst, nearest);
        return worst > stopAbove;
    };
    // The vertices first: two views that differ mostly differ at a corner, so a caller that
    // only asks "within stopAbove?" rarely needs the samples between.
    for (size_t i = 0; i < na; ++i)
        if (sample(a.vertices[i])) return worst;
    for (size_t i = 0; i < na; ++i) {
        const TPoint2D& p0 = a.vertices[i];
        const TPoint2D& p1 = a.vertices[(i + 1) % na];
        const int samples = std::max(1, (int)std::ceil((p1 - p0).norm() / step));
        for (int s = 1; s < samples; ++s)
            if (sample(p0 + (p1 - p0) * ((double)s / samples))) return worst;
    }
    return worst;
}

}  // namespace

double boundaryDistance(const VisibilityPolygon& a, const VisibilityPolygon& b, double step,
                        double stopAbove) {
    if (a.size() < 3 || b.size() < 3) return std::numeric_limits<double>::infinity();
    const double ab = directedDistance(a, b, step, stopAbove);
    return ab > stopAbove ? ab : std::max(ab, directedDistance(b, a, step, stopAbove));
}

double vertexwiseDistance(const VisibilityPolygon& a, const VisibilityPolygon& b) {
    const size_t n = a.size();
    if (n == 0 || b.size() != n) return std::numeric_limits<double>::infinity();
    size_t shift = 0;  // pair a[0] with its nearest vertex of b
    for (size_t j = 1; j < n; ++j)
        if ((b.vertices[j] - a.vertices[0]).norm() < (b.vertices[shift] - a.vertices[0]).norm())
            shift = j;
    double worst = 0;
    for (size_t i = 0; i < n; ++i)
        worst = std::max(worst, (b.vertices[(i + shift) % n] - a.vertices[i]).norm());
    return worst;
}

}  // namespace mrloc::polymap
