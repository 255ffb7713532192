#pragma once
// A floor plan: a simple polygon, or one with holes (pillars, furniture, other rooms' walls).
// Shared by the simulator (walls a scanner sees), the polygon-map method (visibility,
// hypotheses) and the report (drawing).
//
// The rings' vertices are stored one ring after the other, the outer ring first and
// counter-clockwise, each hole clockwise: the free space lies on the left of every edge, and
// edge i runs from vertex i to next(i) within its ring. Predicates use
// one length tolerance, epsilon() = 1e-9 x the bounding-box diagonal, so integer and
// half-integer maps behave exactly and points computed as differences of vertices (where
// hypotheses sit) are recognised as lying on an edge or a vertex.
#include <mrpt/math/TPoint2D.h>

#include <cstdint>
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
    /** A polygon with holes: rings[0] the outer boundary, the others holes. Each ring is
     *  validated as fromVertices does (and named "ring k" in errors); each hole must lie
     *  inside the outer ring and outside every other hole, and no two rings may cross or
     *  touch (the same O(n log n) sweep, over all rings' edges). Reorients the rings (outer
     *  counter-clockwise, holes clockwise). At most `maxVertices` in all. `ringLines`, if
     *  given, names each ring's first line in errors ("ring 2 (line 6)"). Throws mrloc::Error. */
    static Polygon fromRings(std::vector<std::vector<TPoint2D>> rings, const std::string& what,
                             size_t maxVertices = kMaxVertices,
                             const std::vector<int>& ringLines = {});
    /** A .poly file: one "x y" vertex per line; '#' starts a comment. A blank line after the
     *  vertices ends a ring; the first ring is the outer boundary, the others holes. */
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
    /** Writes the .poly text, a blank line between rings (atomically: temporary name, then
     *  rename). */
    void save(const std::string& path, const std::string& comment = "") const;

    size_t size() const { return v_.size(); }
    const TPoint2D& operator[](size_t i) const { return v_[i]; }
    const std::vector<TPoint2D>& vertices() const { return v_; }
    /** The next and previous vertex along i's ring. */
    size_t next(size_t i) const {
        const size_t r = ring_[i];
        return i + 1 == ringStart_[r + 1] ? ringStart_[r] : i + 1;
    }
    size_t prev(size_t i) const {
        const size_t r = ring_[i];
        return i == ringStart_[r] ? ringStart_[r + 1] - 1 : i - 1;
    }
    /** Rings: 1 for a simple polygon; ring 0 is the outer boundary, the others holes. */
    size_t ringCount() const { return ringStart_.size() - 1; }
    bool hasHoles() const { return ringCount() > 1; }
    /** The ring vertex i belongs to, and the vertex range [ringBegin(r), ringEnd(r)). */
    size_t ringOf(size_t i) const { return ring_[i]; }
    size_t ringBegin(size_t r) const { return ringStart_[r]; }
    size_t ringEnd(size_t r) const { return ringStart_[r + 1]; }
    /** Ring r's vertices, in stored order (holes clockwise). */
    std::vector<TPoint2D> ringVertices(size_t r) const {
        return {v_.begin() + long(ringStart_[r]), v_.begin() + long(ringStart_[r + 1])};
    }
    /** True if the interior angle at vertex i exceeds 180 degrees. */
    bool isReflex(size_t i) const;

    /** The free area: the outer ring's less the holes'. */
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
    void setSingleRing();

    std::vector<TPoint2D> v_;
    std::vector<size_t> ringStart_{0, 0};  ///< ring r is [ringStart_[r], ringStart_[r + 1])
    std::vector<uint32_t> ring_;           ///< per vertex, its ring
    TPoint2D min_, max_;
    double eps_ = 0;
};

}  // namespace mrloc::common
