#pragma once
// Shortest paths inside P (seed 002's travel, elimination's "nearest candidate by travel"):
// the geodesic between two points of P, and its length.
//
// The triangles of a simple polygon's triangulation form a tree (their dual graph), so the
// triangles a shortest path crosses are the tree path between the two end triangles (the
// sleeve); the funnel algorithm (Lee and Preparata 1984, in the form of Mononen's "simple
// stupid funnel") pulls the path taut through the sleeve's edges. Cost: the sleeve's
// length, O(n) at worst, with exact orientations for every turn.
#include <mrloc/polymap/Triangulation.h>

#include <vector>

namespace mrloc::polymap {

struct GeodesicPath {
    std::vector<TPoint2D> points;  ///< from the start to the goal; inner points are P's vertices
    double length = 0;             ///< m
};

class ShortestPaths {
 public:
    /** Roots the tree of T's inside triangles; T must outlive this. */
    explicit ShortestPaths(const Triangulation& T);
    /** The shortest path inside P (boundary included) from a to b. Throws mrloc::Error if
     *  either is outside P (by more than P.epsilon()). */
    GeodesicPath path(const TPoint2D& a, const TPoint2D& b) const;
    double distance(const TPoint2D& a, const TPoint2D& b) const { return path(a, b).length; }

 private:
    /** The inside triangles from s to t along the tree. */
    std::vector<int> sleeve(int s, int t) const;

    const Triangulation& T_;
    std::vector<int> parent_, depth_;
};

}  // namespace mrloc::polymap
