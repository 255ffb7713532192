#pragma once
// The constrained Delaunay triangulation (CDT) of a polygon P, holes allowed, built once per map:
// the structure that visibility (triangular expansion), shortest paths (the funnel) and
// point location walk on.
//
// Built on exact predicates (common/ExactPredicates.h): P's vertices are inserted in a
// seeded random order into a Delaunay triangulation of a large enclosing triangle (Lawson's
// flips, a walk from the last triangle to locate), P's edges are then forced in by flipping
// the edges that cross them (Sloan 1993), the triangles inside P are marked, and the edges
// between two of them are flipped until every one is locally Delaunay, which makes the
// triangulation of P constrained Delaunay. No Steiner points: P's n vertices give n - 2
// triangles inside (n + 2h - 2 with h holes, whose inside is found by the same parity). The
// triangles outside P (up to the enclosing triangle) are kept, so that a walk reaches any point;
// they are flagged.
#include <mrloc/common/Polygon.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mrloc::polymap {

using common::TPoint2D;

class Triangulation {
 public:
    static constexpr int kNone = -1;

    struct Triangle {
        std::array<int, 3> v;             ///< vertices, counter-clockwise
        std::array<int, 3> neighbour;     ///< across the edge opposite v[i] (kNone: none)
        std::array<bool, 3> constrained;  ///< that edge is an edge of P
        bool inside = false;              ///< the triangle lies in P
        /** Edge i runs from v[i+1] to v[i+2] (indices mod 3). */
        int from(int i) const { return v[(i + 1) % 3]; }
        int to(int i) const { return v[(i + 2) % 3]; }
    };

    /** Where a point lies: in `triangle` (kNone: outside the enclosing triangle), strictly
     *  inside it, on its edge `edge`, or on its vertex `vertex` (indices 0-2, or -1). */
    struct Location {
        int triangle = kNone;
        int edge = -1;
        int vertex = -1;
    };

    /** P must outlive the triangulation (vertex i of the triangulation is P's vertex i). */
    explicit Triangulation(const common::Polygon& P);

    const common::Polygon& polygon() const { return *P_; }
    const std::vector<Triangle>& triangles() const { return tris_; }
    const Triangle& operator[](int t) const { return tris_[(size_t)t]; }
    /** Vertex coordinates: P's n vertices, then the enclosing triangle's 3. */
    const TPoint2D& point(int v) const { return pts_[(size_t)v]; }
    size_t insideCount() const { return insideCount_; }

    /** Exact point location by a walk from a grid hint. */
    Location locate(const TPoint2D& p) const;
    /** Location in a triangle inside P; a point outside P by at most P.epsilon() (an edge
     *  midpoint, a difference of coordinates) is put on the nearest edge of P (`edge` set,
     *  the point itself not moved). Throws mrloc::Error "<what> (x y) is outside the map". */
    Location locateInside(const TPoint2D& p, const std::string& what) const;
    /** One triangle (inside or outside P) with vertex v. */
    int triangleAt(int v) const { return vertexTriangle_[(size_t)v]; }
    /** Index (0-2) of vertex v in triangle t, or -1. */
    int indexOf(int t, int v) const;
    /** Index of the edge of triangle t that neighbour u shares, or -1. */
    int edgeTowards(int t, int u) const;

 private:
    /** Triangle t = (a, b, c) and its neighbour u = (d, c, b) across the edge b-c opposite
     *  a = t.v[i]: the four outer neighbours (t_ab across a-b, ...) and their flags. Splitting
     *  the edge and flipping it both rebuild the two triangles from this. */
    struct Quad {
        int t = kNone, u = kNone, a = 0, b = 0, c = 0, d = 0;
        int tab = kNone, tca = kNone, ubd = kNone, udc = kNone;
        bool cab = false, cca = false, cbd = false, cdc = false, inside = false;
    };
    Quad quadAt(int t, int i) const;

    void insertPoint(int p, int& hint);
    void splitTriangle(int t, int p, std::vector<std::pair<int, int>>& toCheck);
    void splitEdge(int t, int e, int p, std::vector<std::pair<int, int>>& toCheck);
    /** Flips the edge opposite v[i] of triangle t; afterwards t and its old neighbour hold
     *  v[i] at index 0. */
    void flip(int t, int i);
    void legalize(std::vector<std::pair<int, int>>& toCheck);
    void relink(int t, int a, int b, int to);
    /** edgeTowards(u, t), which must exist. */
    int across(int u, int t) const;
    void forceEdge(int a, int b);
    /** The triangle with directed edge a->b, and that edge's index, or {kNone, -1}. */
    std::pair<int, int> findEdge(int a, int b) const;
    void markInside();
    void makeConstrainedDelaunay();
    void buildLocator();
    Location walk(const TPoint2D& p, int start) const;

    const common::Polygon* P_;
    std::vector<TPoint2D> pts_;
    std::vector<Triangle> tris_;
    std::vector<int> vertexTriangle_;
    size_t insideCount_ = 0;
    // Point location hints: a grid over P's bounding box, each cell holding the triangle
    // that contains its centre.
    TPoint2D gridMin_;
    double cellSize_ = 1;
    int gridW_ = 1, gridH_ = 1;
    std::vector<int> gridHint_;
};

}  // namespace mrloc::polymap
