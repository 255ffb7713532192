#pragma once
// A building's map as a scanner sees it: the free space as polygon rings (an outer ring and
// the holes inside it: pillars, furniture, other rooms' walls), the walls a beam stops at,
// and where a robot may stand. Built from a .poly file (rings separated by blank lines) or
// traced from an MRPT occupancy grid (GridTrace.h). The scan localizer (ScanLocalizer.h)
// works on it; the exact pipeline (triangulation, visibility, elimination) on simple polygons.
#include <mrloc/common/Polygon.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mrloc::polymap {

using common::TPoint2D;
using common::TVector2D;

struct WallSegment {
    TPoint2D a, b;
};

/** Segments bucketed on a uniform grid; a ray walks the cells it crosses in order (Amanatides
 *  and Woo 1987) and stops at the first cell holding a hit, so a cast costs the cells up to
 *  the first wall, not the map's size. */
class RayCaster {
 public:
    RayCaster() = default;
    RayCaster(std::vector<WallSegment> walls, double cellSize);
    /** Distance from `origin` along direction `angle` (rad) to the first wall, or `maxRange`
     *  if none is nearer. */
    double cast(const TPoint2D& origin, double angle, double maxRange) const;
    const std::vector<WallSegment>& walls() const { return walls_; }

 private:
    std::vector<WallSegment> walls_;
    TPoint2D min_{0, 0};
    double cell_ = 1;
    int nx_ = 0, ny_ = 0;
    std::vector<uint32_t> start_, items_;  ///< CSR: cell c's segments are items_[start_[c]..]
};

/** Cells of the map's box: where the robot's scanner may stand (free, clear of walls). */
struct FreeCells {
    TPoint2D min{0, 0};
    double resolution = 0.1;
    int width = 0, height = 0;
    std::vector<uint8_t> free;  ///< row-major, 1 = the scanner may stand at the cell's centre
    bool at(const TPoint2D& p) const;
    size_t count() const;
};

struct WallMap {
    /** The free space: rings[0] an outer ring, then holes, each closed implicitly; a traced
     *  map may have several outer rings (separate free regions): `outer[i]` says which. */
    std::vector<std::vector<TPoint2D>> rings;
    std::vector<bool> outer;
    RayCaster caster;
    FreeCells freeCells;
    std::string description;  ///< where it came from, for the report
    TPoint2D min{0, 0}, max{0, 0};
};

/** Bounds of a map (doc/errors.md): rings and vertices in a .poly or traced from a grid. */
inline constexpr size_t kMaxRings = 20000;
inline constexpr size_t kMaxWallVertices = 400000;

/** Reads a .poly file of one or more rings separated by blank lines: the first ring is the
 *  outer boundary, the others holes inside it. Each ring is validated as a simple polygon
 *  (common::Polygon), each hole must lie inside the outer ring, and no two rings may cross or
 *  touch (the same sweep, over all edges). Throws mrloc::Error naming the file and line. */
std::vector<std::vector<TPoint2D>> loadPolyRings(const std::string& path);
/** Writes rings as .poly text (blank line between rings), atomically. */
void savePolyRings(const std::string& path, const std::vector<std::vector<TPoint2D>>& rings,
                   const std::string& comment);

/** A WallMap of free-space rings (the first outer, the rest holes): every ring edge is a wall;
 *  the free cells are those inside the outer ring and outside every hole, at least
 *  `clearance` from a wall, on a grid of `resolution`. */
WallMap wallMapOfRings(std::vector<std::vector<TPoint2D>> rings, double resolution,
                       double clearance, const std::string& description);

}  // namespace mrloc::polymap
