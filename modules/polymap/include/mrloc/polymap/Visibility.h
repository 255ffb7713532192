#pragma once
// The visibility polygon V(q) of a point q in a simple polygon P: every point of P that the
// segment from q reaches without leaving P. V is star-shaped about q and is kept in the
// robot's frame: vertices relative to q, axes along the map's (the robot knows its heading,
// seed 002 sec. 1), counter-clockwise.
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/Triangulation.h>

#include <limits>
#include <vector>

namespace mrloc::polymap {

using common::TPoint2D;
using common::TVector2D;

struct VisibilityPolygon {
    std::vector<TPoint2D> vertices;  ///< relative to the viewpoint, counter-clockwise
    /** Directions closer than this (radians) are one direction: 0 for an exact polygon,
     *  about one beam step for a polygon built from a scan. */
    double angularTolerance = 1e-9;

    size_t size() const { return vertices.size(); }
    /** Edge i (vertex i to i+1) lies on a line through the viewpoint: a window (a
     *  constructed edge, seed 002 [2]) or a wall seen edge-on. */
    bool isRadial(size_t i) const;
    /** Distance from the viewpoint to the boundary along a unit direction (0 if the
     *  viewpoint is on the boundary and the direction leaves the polygon). */
    double radius(const TVector2D& dir) const;
    /** The same polygon placed with its viewpoint at p (map frame). */
    std::vector<TPoint2D> placedAt(const TPoint2D& p) const;
};

/** V's radius in many directions (a scan's beams): the vertices' angles sorted once, then
 *  each direction looks up its edge in O(log |V|) and gives VisibilityPolygon::radius's
 *  value (the same crossings, of the few edges around that angle). V must outlive this. */
class RadialProfile {
 public:
    explicit RadialProfile(const VisibilityPolygon& V);
    double radius(double angle) const;

 private:
    const VisibilityPolygon& V_;
    std::vector<double> angles_;  ///< unwrapped, from vertex first_ on, counter-clockwise
    size_t first_ = 0;
    bool direct_ = false;  ///< a vertex on the viewpoint: no angle order; every edge is tried
};

/** Exact V(q) by triangular expansion over P's triangulation (Bungiu et al., EuroCG 2014):
 *  the cost is the triangles the view passes through, not n. Exact topology (every decision
 *  is an exact orientation); the only rounding is where a window's ray meets a wall. Works
 *  for q strictly inside, on an edge or on a vertex; q within P.epsilon() of a vertex is
 *  moved onto it, and q outside by less than P.epsilon() counts as on the nearest edge.
 *  Collinear vertices of P are allowed and never corners of V. Throws mrloc::Error if q is
 *  outside P. */
VisibilityPolygon visibilityPolygon(const Triangulation& T, const TPoint2D& q);
/** The same, triangulating P first (O(n log n)): for one query; keep a Triangulation for many. */
VisibilityPolygon visibilityPolygon(const common::Polygon& P, const TPoint2D& q);

/** Symmetric Hausdorff distance between the boundaries of two visibility polygons placed at
 *  the same viewpoint, sampled every `step` along the edges (error at most step / 2). Stops
 *  at the first sample farther than `stopAbove` and returns that sample's distance: enough
 *  to decide "within stopAbove or not". */
double boundaryDistance(const VisibilityPolygon& a, const VisibilityPolygon& b, double step,
                        double stopAbove = std::numeric_limits<double>::infinity());

/** If a and b have the same number of vertices, the largest distance between corresponding
 *  ones (the best cyclic pairing), else infinity: an upper bound on the boundary distance
 *  (each edge stays within that distance of its partner), in O(|V|). */
double vertexwiseDistance(const VisibilityPolygon& a, const VisibilityPolygon& b);

}  // namespace mrloc::polymap
