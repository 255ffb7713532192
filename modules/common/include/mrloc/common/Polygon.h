#pragma once
// A simple polygon without holes: a floor plan. Shared by the simulator (walls a scanner
// sees), the polygon-map method (visibility, hypotheses) and the report (drawing).
//
// Vertices are kept counter-clockwise (interior on the left of every edge). Predicates use
// one length tolerance, epsilon() = 1e-9 x the bounding-box diagonal, so integer and
// half-integer maps behave exactly and points computed as differences of vertices (where
// hypotheses sit) are recognised as lying on an edge or a vertex.
#include <mrpt/math/TPoint2D.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

using mrpt::math::TPoint2D;
using mrpt::math::TVector2D;

/** z of the cross product a x b. */
inline double cross(const TVector2D& a, const TVector2D& b) { return a.x * b.y - a.y * b.x; }
inline double dot(const TVector2D& a, const TVector2D& b) { return a.x * b.x + a.y * b.y; }
/** Distance from p to the segment a-b. */
double distanceToSegment(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b);
/** Distance t along o + t * dir to segment a-b, if the ray meets it with t > tMin (a
 *  segment parallel to the ray is never met: its ends are, through its neighbours). */
std::optional<double> raySegmentHit(const TPoint2D& a, const TPoint2D& b, const TPoint2D& o,
                                    const TVector2D& dir, double tMin);
/** The point of segment a-b nearest to p. */
TPoint2D closestOnSegment(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b);

class Polygon {
 public:
    enum class Where { Outside, Inside, Boundary };

    /** Upper bounds (doc/errors.md): the maps mrloc is built and measured for (star5000,
     *  steps maps to n = 5000) are well inside; coordinates beyond kMaxCoordinate (m) leave
     *  too few bits for the tolerances. */
    static constexpr size_t kMaxVertices = 20000;
    static constexpr double kMaxCoordinate = 1e6;

    /** Validates (3 to kMaxVertices finite vertices within kMaxCoordinate, none repeated,
     *  no zero-width spike, no two edges crossing or touching; O(n log n), a sweep on exact
     *  orientations) and reorients clockwise input. `what` names the source
     *  in errors, e.g. "maps/x.poly". Throws mrloc::Error. */
    static Polygon fromVertices(std::vector<TPoint2D> vertices, const std::string& what);
    /** A .poly file: one "x y" vertex per line; '#' starts a comment. A blank line after the
     *  vertices ends the ring: another ring after it (a hole) is refused here, since a simple
     *  polygon has none (polymap/WallMap.h reads rings). */
    static Polygon load(const std::string& path);
    /** A .poly file's rings as written (one "x y" per line, '#' comments, a blank line after
     *  vertices ends a ring), not validated; each with the line of its first vertex. At most
     *  maxVertices in all and maxRings; throws mrloc::Error naming the file and line. */
    struct Ring {
        std::vector<TPoint2D> vertices;
        int firstLine = 0;
    };
    static std::vector<Ring> readRings(const std::string& path, size_t maxVertices,
                                       size_t maxRings);
    /** Writes the .poly text (atomically: temporary name, then rename). */
    void save(const std::string& path, const std::string& comment = "") const;

    size_t size() const { return v_.size(); }
    const TPoint2D& operator[](size_t i) const { return v_[i]; }
    const std::vector<TPoint2D>& vertices() const { return v_; }
    size_t next(size_t i) const { return i + 1 == v_.size() ? 0 : i + 1; }
    size_t prev(size_t i) const { return i == 0 ? v_.size() - 1 : i - 1; }
    /** True if the interior angle at vertex i exceeds 180 degrees. */
    bool isReflex(size_t i) const;

    double area() const;
    TPoint2D min() const { return min_; }
    TPoint2D max() const { return max_; }
    /** Length tolerance of the predicates (see above). */
    double epsilon() const { return eps_; }

    /** Inside, outside, or within `tol` of the boundary (tol < 0: epsilon()). */
    Where locate(const TPoint2D& p, double tol = -1) const;
    bool contains(const TPoint2D& p, double tol = -1) const {
        return locate(p, tol) != Where::Outside;
    }
    /** The boundary point nearest to p, and the edge (from vertex i to i+1) it lies on. */
    std::pair<TPoint2D, size_t> closestBoundaryPoint(const TPoint2D& p) const;

    /** Distance t along origin + t * dir (dir of unit length) to the first boundary point
     *  with t > tMin, or nothing if the ray meets no edge there. */
    std::optional<double> rayCast(const TPoint2D& origin, const TVector2D& dir,
                                  double tMin = 0) const;
    /** Index of the edge (i, i+1) that rayCast met, with the distance. */
    std::optional<std::pair<double, size_t>> rayCastEdge(const TPoint2D& origin,
                                                         const TVector2D& dir,
                                                         double tMin = 0) const;
    /** The same among some edges only (edge i runs from vertex i to i+1). */
    std::optional<std::pair<double, size_t>> rayCastEdge(const TPoint2D& origin,
                                                         const TVector2D& dir, double tMin,
                                                         const std::vector<size_t>& edges) const;

 private:
    std::vector<TPoint2D> v_;
    TPoint2D min_, max_;
    double eps_ = 0;
};

}  // namespace mrloc::common
