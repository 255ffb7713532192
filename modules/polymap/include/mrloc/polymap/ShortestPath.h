#pragma once
// Shortest paths inside P (seed 002's travel, elimination's "nearest candidate by travel"):
// the geodesic between two points of P, and its length.
//
// The triangles of a simple polygon's triangulation form a tree (their dual graph), so the
// triangles a shortest path crosses are the tree path between the two end triangles (the
// sleeve); the funnel algorithm (Lee and Preparata 1984, in the form of Mononen's "simple
// stupid funnel") pulls the path taut through the sleeve's edges. Cost: the sleeve's
// length, O(n) at worst, with exact orientations for every turn.
//
// With holes the dual graph has cycles and no sleeve is unique. The shortest path then bends
// only at reflex vertices, on lines tangent to the boundary there (Lozano-Perez and Wesley
// 1979; de Berg et al., Computational Geometry, ch. 15): the graph of mutually visible
// reflex vertices joined by such tangent lines (the reduced visibility graph) is built once,
// visibility read off each vertex's visibility polygon; a query joins a and b to the reflex
// vertices they see (their own visibility polygons) and runs Dijkstra. A source's distances
// are kept for the next query from it (the elimination asks from one point to many).
#include <mrloc/polymap/Triangulation.h>
#include <mrloc/polymap/Visibility.h>

#include <memory>
#include <mutex>
#include <vector>

namespace mrloc::polymap {

struct GeodesicPath {
    std::vector<TPoint2D> points;  ///< from the start to the goal; inner points are P's vertices
    double length = 0;             ///< m
};

class ShortestPaths {
 public:
    /** Roots the tree of T's inside triangles, or, if P has holes, builds the reduced
     *  visibility graph of its reflex vertices; T must outlive this. */
    explicit ShortestPaths(const Triangulation& T);
    ~ShortestPaths();
    /** The shortest path inside P (boundary included) from a to b. Throws mrloc::Error if
     *  either is outside P (by more than P.epsilon()). */
    GeodesicPath path(const TPoint2D& a, const TPoint2D& b) const;
    double distance(const TPoint2D& a, const TPoint2D& b) const { return path(a, b).length; }

 private:
    /** The inside triangles from s to t along the tree. */
    std::vector<int> sleeve(int s, int t) const;
    /** With holes: Dijkstra over the reduced visibility graph. */
    GeodesicPath graphPath(const TPoint2D& a, const TPoint2D& b) const;
    void buildVisibilityGraph();

    const Triangulation& T_;
    std::vector<int> parent_, depth_;
    // holes: the reflex vertices (P's indices), and per one of them its tangent neighbours
    struct Link {
        int to;  ///< index in reflex_
        double length;
    };
    std::vector<size_t> reflex_;
    std::vector<std::vector<Link>> links_;
    struct Source;  // a query's start: what it sees and its distances to every reflex vertex
    mutable std::mutex sourceMutex_;
    mutable std::shared_ptr<const Source> lastSource_;
};

}  // namespace mrloc::polymap
