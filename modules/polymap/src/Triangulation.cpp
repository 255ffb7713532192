#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/Triangulation.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>

namespace mrloc::polymap {

using common::inCircle;
using common::orientation;

namespace {
inline int plus1(int i) { return i == 2 ? 0 : i + 1; }
inline int plus2(int i) { return i == 0 ? 2 : i - 1; }

/** Position along the Hilbert curve of order 16 of the cell (x, y), 0 <= x, y < 2^16. */
uint64_t hilbertIndex(uint32_t x, uint32_t y) {
    uint64_t d = 0;
    for (uint32_t s = 1u << 15; s > 0; s >>= 1) {
        const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
        d += (uint64_t)s * s * ((3 * rx) ^ ry);
        if (ry == 0) {  // rotate the quadrant (only the lower bits matter from here on)
            if (rx == 1) x = 65535 - x, y = 65535 - y;
            std::swap(x, y);
        }
    }
    return d;
}
}  // namespace

Triangulation::Triangulation(const common::Polygon& P) : P_(&P) {
    const int n = (int)P.size();
    pts_ = P.vertices();
    // The enclosing triangle: far enough that P's hull edges are not its concern (only the
    // inside of P is claimed Delaunay), near enough to keep the predicates' products small.
    const TPoint2D centre = (P.min() + P.max()) * 0.5;
    const double m = std::max({P.max().x - P.min().x, P.max().y - P.min().y, 1.0}) * 30;
    pts_.push_back({centre.x - m, centre.y - m});
    pts_.push_back({centre.x + m, centre.y - m});
    pts_.push_back({centre.x, centre.y + m});
    tris_.push_back({{n, n + 1, n + 2}, {kNone, kNone, kNone}, {false, false, false}, false});
    vertexTriangle_.assign((size_t)n + 3, 0);

    // Biased randomized insertion order (Amenta, Choi and Rote 2003): a seeded shuffle keeps
    // the expected number of flips O(n) (P's own order, points along a curve, is the bad
    // case); rounds of doubling size, each sorted along a Hilbert curve, keep every walk
    // from the last point short.
    std::vector<int> order((size_t)n);
    for (int i = 0; i < n; ++i) order[(size_t)i] = i;
    std::mt19937 rng(20140301u);
    for (int i = n - 1; i > 0; --i) std::swap(order[(size_t)i], order[rng() % (uint32_t)(i + 1)]);
    const TPoint2D lo = P.min(), span = P.max() - P.min();
    const double scale = 65535.0 / std::max({span.x, span.y, 1e-300});
    std::vector<uint64_t> key((size_t)n);
    for (int i = 0; i < n; ++i)
        key[(size_t)i] = hilbertIndex((uint32_t)((pts_[(size_t)i].x - lo.x) * scale),
                                      (uint32_t)((pts_[(size_t)i].y - lo.y) * scale));
    for (size_t end = (size_t)n; end > 0;) {
        const size_t begin = end < 64 ? 0 : end / 2;
        std::sort(order.begin() + (long)begin, order.begin() + (long)end,
                  [&key](int a, int b) { return key[(size_t)a] < key[(size_t)b]; });
        end = begin;
    }
    int hint = 0;
    for (int p : order) insertPoint(p, hint);
    for (int i = 0; i < n; ++i) forceEdge(i, (int)P.next((size_t)i));  // every ring's edges
    markInside();
    makeConstrainedDelaunay();
    buildLocator();
}

int Triangulation::indexOf(int t, int v) const {
    const auto& T = tris_[(size_t)t];
    return T.v[0] == v ? 0 : T.v[1] == v ? 1 : T.v[2] == v ? 2 : -1;
}

int Triangulation::edgeTowards(int t, int u) const {
    const auto& T = tris_[(size_t)t];
    return T.neighbour[0] == u ? 0 : T.neighbour[1] == u ? 1 : T.neighbour[2] == u ? 2 : -1;
}

int Triangulation::across(int u, int t) const {
    const int j = edgeTowards(u, t);
    if (j < 0) throw Error("triangulation: neighbours disagree (internal error)");
    return j;
}

void Triangulation::relink(int t, int a, int b, int to) {
    if (t == kNone) return;
    auto& T = tris_[(size_t)t];
    for (int i = 0; i < 3; ++i)
        if ((T.from(i) == a && T.to(i) == b) || (T.from(i) == b && T.to(i) == a)) {
            T.neighbour[(size_t)i] = to;
            return;
        }
    throw Error("triangulation: neighbour link lost (internal error)");
}

Triangulation::Location Triangulation::walk(const TPoint2D& p, int start) const {
    // The stochastic visibility walk (Devillers, Pion and Teillaud 2002): cross an edge that
    // has p on its far side, trying the edges from a random one so that it cannot cycle.
    uint32_t state = 2463534242u;
    int t = start;
    const size_t limit = 8 * tris_.size() + 64;
    for (size_t step = 0; step < limit; ++step) {
        state ^= state << 13, state ^= state >> 17, state ^= state << 5;
        const auto& T = tris_[(size_t)t];
        std::array<int, 3> side{};
        int next = -2;
        const int first = (int)(state % 3);
        for (int k = 0; k < 3; ++k) {
            const int i = (first + k) % 3;
            side[(size_t)i] = orientation(pts_[(size_t)T.from(i)], pts_[(size_t)T.to(i)], p);
            if (side[(size_t)i] < 0) {
                next = T.neighbour[(size_t)i];
                break;
            }
        }
        if (next == kNone) return {};  // beyond the enclosing triangle
        if (next >= 0) {
            t = next;
            continue;
        }
        Location loc;
        loc.triangle = t;
        for (int i = 0; i < 3; ++i)
            if (side[(size_t)i] == 0) {
                if (loc.edge < 0) {
                    loc.edge = i;
                } else {  // on two edges: their shared vertex
                    loc.vertex = 3 - loc.edge - i;
                    loc.edge = -1;
                }
            }
        return loc;
    }
    throw Error("triangulation: point location did not end (internal error)");
}

void Triangulation::insertPoint(int p, int& hint) {
    const Location loc = walk(pts_[(size_t)p], hint);
    if (loc.triangle == kNone || loc.vertex >= 0)
        throw Error("triangulation: vertex " + std::to_string(p + 1) +
                    " repeats another (internal error: the polygon was validated)");
    std::vector<std::pair<int, int>> toCheck;
    if (loc.edge >= 0)
        splitEdge(loc.triangle, loc.edge, p, toCheck);
    else
        splitTriangle(loc.triangle, p, toCheck);
    legalize(toCheck);
    hint = vertexTriangle_[(size_t)p];
}

void Triangulation::splitTriangle(int t, int p, std::vector<std::pair<int, int>>& toCheck) {
    const Triangle old = tris_[(size_t)t];
    const int a = old.v[0], b = old.v[1], c = old.v[2];
    const int tb = (int)tris_.size(), tc = tb + 1;
    tris_[(size_t)t] = {
        {p, b, c}, {old.neighbour[0], tb, tc}, {old.constrained[0], false, false}, false};
    tris_.push_back(
        {{a, p, c}, {t, old.neighbour[1], tc}, {false, old.constrained[1], false}, false});
    tris_.push_back(
        {{a, b, p}, {t, tb, old.neighbour[2]}, {false, false, old.constrained[2]}, false});
    relink(old.neighbour[1], c, a, tb);
    relink(old.neighbour[2], a, b, tc);
    vertexTriangle_[(size_t)a] = tb;
    vertexTriangle_[(size_t)b] = vertexTriangle_[(size_t)c] = vertexTriangle_[(size_t)p] = t;
    toCheck.insert(toCheck.end(), {{t, 0}, {tb, 1}, {tc, 2}});
}

Triangulation::Quad Triangulation::quadAt(int t, int i) const {
    const Triangle& T = tris_[(size_t)t];
    Quad q;
    q.t = t;
    q.a = T.v[(size_t)i], q.b = T.v[(size_t)plus1(i)], q.c = T.v[(size_t)plus2(i)];
    q.u = T.neighbour[(size_t)i];
    if (q.u == kNone)
        throw Error("triangulation: an edge of the enclosing triangle (internal error)");
    const Triangle& U = tris_[(size_t)q.u];
    const int j = across(q.u, t);
    q.d = U.v[(size_t)j];
    q.tab = T.neighbour[(size_t)plus2(i)], q.tca = T.neighbour[(size_t)plus1(i)];
    q.ubd = U.neighbour[(size_t)plus1(j)], q.udc = U.neighbour[(size_t)plus2(j)];
    q.cab = T.constrained[(size_t)plus2(i)], q.cca = T.constrained[(size_t)plus1(i)];
    q.cbd = U.constrained[(size_t)plus1(j)], q.cdc = U.constrained[(size_t)plus2(j)];
    q.inside = T.inside;
    return q;
}

void Triangulation::splitEdge(int t, int e, int p, std::vector<std::pair<int, int>>& toCheck) {
    const Quad q = quadAt(t, e);
    const int u = q.u, t2 = (int)tris_.size(), t4 = t2 + 1;
    tris_[(size_t)t] = {{p, q.a, q.b}, {q.tab, t4, t2}, {q.cab, false, false}, false};
    tris_[(size_t)u] = {{p, q.d, q.c}, {q.udc, t2, t4}, {q.cdc, false, false}, false};
    tris_.push_back({{p, q.c, q.a}, {q.tca, t, u}, {q.cca, false, false}, false});
    tris_.push_back({{p, q.b, q.d}, {q.ubd, u, t}, {q.cbd, false, false}, false});
    relink(q.tca, q.c, q.a, t2);
    relink(q.ubd, q.b, q.d, t4);
    vertexTriangle_[(size_t)p] = vertexTriangle_[(size_t)q.a] = vertexTriangle_[(size_t)q.b] = t;
    vertexTriangle_[(size_t)q.c] = t2;
    vertexTriangle_[(size_t)q.d] = u;
    toCheck.insert(toCheck.end(), {{t, 0}, {t2, 0}, {u, 0}, {t4, 0}});
}

void Triangulation::flip(int t, int i) {
    const Quad q = quadAt(t, i);
    const int u = q.u;
    tris_[(size_t)t] = {{q.a, q.b, q.d}, {q.ubd, u, q.tab}, {q.cbd, false, q.cab}, q.inside};
    tris_[(size_t)u] = {{q.a, q.d, q.c}, {q.udc, q.tca, t}, {q.cdc, q.cca, false}, q.inside};
    relink(q.ubd, q.b, q.d, t);
    relink(q.tca, q.c, q.a, u);
    vertexTriangle_[(size_t)q.a] = vertexTriangle_[(size_t)q.b] = vertexTriangle_[(size_t)q.d] = t;
    vertexTriangle_[(size_t)q.c] = u;
}

void Triangulation::legalize(std::vector<std::pair<int, int>>& toCheck) {
    // Lawson: an edge whose far vertex lies inside the near triangle's circumcircle is
    // flipped; the new point stays at index 0 of both new triangles.
    while (!toCheck.empty()) {
        const auto [t, i] = toCheck.back();
        toCheck.pop_back();
        const auto& T = tris_[(size_t)t];
        const int u = T.neighbour[(size_t)i];
        if (u == kNone || T.constrained[(size_t)i]) continue;
        const int d = tris_[(size_t)u].v[(size_t)across(u, t)];
        if (inCircle(pts_[(size_t)T.v[0]], pts_[(size_t)T.v[1]], pts_[(size_t)T.v[2]],
                     pts_[(size_t)d]) > 0) {
            flip(t, i);
            toCheck.insert(toCheck.end(), {{t, 0}, {u, 0}});
        }
    }
}

std::pair<int, int> Triangulation::findEdge(int a, int b) const {
    // Counter-clockwise about a, then (for the enclosing triangle's corners, which the
    // triangles do not surround) clockwise from the start.
    const int start = vertexTriangle_[(size_t)a];
    for (const int turn : {1, 2}) {
        int t = start;
        do {
            const int k = indexOf(t, a);
            if (k < 0) throw Error("triangulation: vertex table stale (internal error)");
            if (tris_[(size_t)t].v[(size_t)plus1(k)] == b) return {t, plus2(k)};
            t = tris_[(size_t)t].neighbour[(size_t)(turn == 1 ? plus1(k) : plus2(k))];
        } while (t != start && t != kNone);
        if (t == start) break;
    }
    return {kNone, -1};
}

void Triangulation::forceEdge(int a, int b) {
    const auto mark = [this, a, b] {
        const auto [t, i] = findEdge(a, b);
        const auto [u, j] = findEdge(b, a);
        if (t == kNone || u == kNone)
            throw Error("triangulation: edge " + std::to_string(a + 1) + "-" +
                        std::to_string(b + 1) + " could not be forced (internal error)");
        tris_[(size_t)t].constrained[(size_t)i] = tris_[(size_t)u].constrained[(size_t)j] = true;
    };
    if (findEdge(a, b).first != kNone) return mark();
    const TPoint2D &A = pts_[(size_t)a], &B = pts_[(size_t)b];
    // The triangle about a whose far edge the segment a-b leaves through.
    int t = vertexTriangle_[(size_t)a], k = -1;
    for (size_t guard = 0; guard <= tris_.size(); ++guard) {
        const int ka = indexOf(t, a);
        const auto& T = tris_[(size_t)t];
        const TPoint2D &X = pts_[(size_t)T.v[(size_t)plus1(ka)]],
                       &Y = pts_[(size_t)T.v[(size_t)plus2(ka)]];
        if (orientation(A, X, B) > 0 && orientation(A, Y, B) < 0) {
            k = ka;
            break;
        }
        t = T.neighbour[(size_t)plus1(ka)];
    }
    if (k < 0) throw Error("triangulation: no way out of a vertex (internal error)");
    // Every edge the segment crosses (x right of a->b, y left).
    std::deque<std::pair<int, int>> crossing;
    int x = tris_[(size_t)t].v[(size_t)plus1(k)], y = tris_[(size_t)t].v[(size_t)plus2(k)];
    for (;;) {
        crossing.push_back({x, y});
        const auto& T = tris_[(size_t)t];
        const int i = T.from(0) == x ? 0 : T.from(1) == x ? 1 : 2;  // edge x->y of t
        const int u = T.neighbour[(size_t)i];
        const int w = tris_[(size_t)u].v[(size_t)across(u, t)];
        if (w == b) break;
        const int side = orientation(A, B, pts_[(size_t)w]);
        if (side == 0)
            throw Error("triangulation: a vertex lies on edge " + std::to_string(a + 1) + "-" +
                        std::to_string(b + 1) + " (internal error: the polygon was validated)");
        if (side > 0)
            y = w;
        else
            x = w;
        t = u;
    }
    // Sloan's recovery: flip crossing edges whose quadrilateral is convex until none is left.
    const auto crosses = [&](int p, int q) {
        const TPoint2D &P = pts_[(size_t)p], &Q = pts_[(size_t)q];
        return orientation(A, B, P) * orientation(A, B, Q) < 0 &&
               orientation(P, Q, A) * orientation(P, Q, B) < 0;
    };
    const size_t limit = 64 * (crossing.size() + 1) * (crossing.size() + 1) + 1024;
    for (size_t guard = 0; !crossing.empty(); ++guard) {
        if (guard > limit) throw Error("triangulation: edge recovery did not end (internal error)");
        const auto [p, q] = crossing.front();
        crossing.pop_front();
        const auto [s, i] = findEdge(p, q);
        if (s == kNone) throw Error("triangulation: crossing edge lost (internal error)");
        const auto& S = tris_[(size_t)s];  // (c, p, q), the edge p->q opposite c = S.v[i]
        const int c = S.v[(size_t)i];
        const int u = S.neighbour[(size_t)i];
        const int d = tris_[(size_t)u].v[(size_t)across(u, s)];
        const TPoint2D &C = pts_[(size_t)c], &D = pts_[(size_t)d];
        if (orientation(C, D, pts_[(size_t)p]) < 0 && orientation(C, D, pts_[(size_t)q]) > 0) {
            flip(s, i);
            if (crosses(c, d)) crossing.push_back({c, d});
        } else {
            crossing.push_back({p, q});
        }
    }
    mark();
}

void Triangulation::markInside() {
    // Parity of P's edges crossed from the enclosing triangle's corner (a hole's edges flip
    // it back to outside).
    std::vector<char> seen(tris_.size(), 0);
    const int start = vertexTriangle_[(size_t)P_->size()];
    std::vector<int> stack{start};
    seen[(size_t)start] = 1;
    tris_[(size_t)start].inside = false;
    insideCount_ = 0;
    while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        const auto& T = tris_[(size_t)t];
        insideCount_ += T.inside;
        for (int i = 0; i < 3; ++i) {
            const int u = T.neighbour[(size_t)i];
            if (u == kNone || seen[(size_t)u]) continue;
            seen[(size_t)u] = 1;
            tris_[(size_t)u].inside = T.inside != T.constrained[(size_t)i];
            stack.push_back(u);
        }
    }
    // Euler: n vertices on h + 1 rings give n + 2h - 2 triangles
    if (insideCount_ + 2 != P_->size() + 2 * (P_->ringCount() - 1))
        throw Error("triangulation: " + std::to_string(insideCount_) + " triangles inside a " +
                    std::to_string(P_->size()) + "-gon with " +
                    std::to_string(P_->ringCount() - 1) + " hole(s) (internal error)");
}

void Triangulation::makeConstrainedDelaunay() {
    // Lawson's flips restricted to the inside: when no edge between two inside triangles
    // has its far vertex inside the near circumcircle, the triangulation of P is
    // constrained Delaunay.
    std::vector<std::pair<int, int>> edges;
    for (int t = 0; t < (int)tris_.size(); ++t)
        for (int i = 0; i < 3; ++i) {
            const auto& T = tris_[(size_t)t];
            if (T.inside && !T.constrained[(size_t)i] && T.neighbour[(size_t)i] > t)
                edges.push_back({T.from(i), T.to(i)});
        }
    while (!edges.empty()) {
        const auto [p, q] = edges.back();
        edges.pop_back();
        const auto [t, i] = findEdge(p, q);
        if (t == kNone) continue;  // flipped away meanwhile
        const auto& T = tris_[(size_t)t];
        if (!T.inside || T.constrained[(size_t)i]) continue;
        const int u = T.neighbour[(size_t)i];
        const int c = T.v[(size_t)i], d = tris_[(size_t)u].v[(size_t)across(u, t)];
        if (inCircle(pts_[(size_t)T.v[0]], pts_[(size_t)T.v[1]], pts_[(size_t)T.v[2]],
                     pts_[(size_t)d]) <= 0)
            continue;
        flip(t, i);  // now (c, p, d) and (c, d, q)
        edges.insert(edges.end(), {{p, d}, {d, q}, {q, c}, {c, p}});
    }
}

void Triangulation::buildLocator() {
    const TPoint2D size = P_->max() - P_->min();
    const int cells = std::max(1, (int)std::sqrt((double)P_->size()));
    cellSize_ = std::max(std::max(size.x, size.y) / cells, 1e-300);
    gridMin_ = P_->min();
    gridW_ = std::max(1, (int)std::ceil(size.x / cellSize_));
    gridH_ = std::max(1, (int)std::ceil(size.y / cellSize_));
    gridHint_.assign((size_t)gridW_ * (size_t)gridH_, 0);
    int hint = vertexTriangle_[0];
    for (int row = 0; row < gridH_; ++row)
        for (int k = 0; k < gridW_; ++k) {
            const int col = row % 2 ? gridW_ - 1 - k : k;  // snake: each walk starts near
            const TPoint2D centre{gridMin_.x + (col + 0.5) * cellSize_,
                                  gridMin_.y + (row + 0.5) * cellSize_};
            hint = walk(centre, hint).triangle;
            gridHint_[(size_t)row * (size_t)gridW_ + (size_t)col] = hint;
        }
}

Triangulation::Location Triangulation::locate(const TPoint2D& p) const {
    const int col = std::clamp((int)std::floor((p.x - gridMin_.x) / cellSize_), 0, gridW_ - 1);
    const int row = std::clamp((int)std::floor((p.y - gridMin_.y) / cellSize_), 0, gridH_ - 1);
    return walk(p, gridHint_[(size_t)row * (size_t)gridW_ + (size_t)col]);
}

Triangulation::Location Triangulation::locateInside(const TPoint2D& p,
                                                    const std::string& what) const {
    const Location loc = locate(p);
    if (loc.triangle != kNone && tris_[(size_t)loc.triangle].inside) return loc;
    // Outside: the nearest edge of P within eps, searched among the outside triangles
    // within eps of p.
    const double eps = P_->epsilon();
    double best = eps;
    Location found;
    if (loc.triangle != kNone) {
        std::vector<int> stack{loc.triangle}, seen{loc.triangle};
        while (!stack.empty()) {
            const int t = stack.back();
            stack.pop_back();
            const auto& T = tris_[(size_t)t];
            for (int i = 0; i < 3; ++i) {
                const double d =
                    common::distanceToSegment(p, pts_[(size_t)T.from(i)], pts_[(size_t)T.to(i)]);
                const int u = T.neighbour[(size_t)i];
                if (d > eps || u == kNone) continue;
                if (T.constrained[(size_t)i]) {
                    if (d <= best) best = d, found = {u, edgeTowards(u, t), -1};
                } else if (std::find(seen.begin(), seen.end(), u) == seen.end()) {
                    seen.push_back(u);
                    stack.push_back(u);
                }
            }
        }
    }
    if (found.triangle == kNone)
        throw Error(mrpt::format("%s (%.9g %.9g) is outside the map", what.c_str(), p.x, p.y));
    return found;
}

}  // namespace mrloc::polymap
