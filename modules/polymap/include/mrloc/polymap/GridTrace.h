#pragma once
// MRPT's maps as polygon maps: a .gridmap(.gz) (a serialized COccupancyGridMap2D) or a
// .simplemap(.gz) (poses and scans, from which MRPT builds the occupancy grid) traced into
// polygon rings with OpenCV (doc/polymap.md, "Maps from MRPT"):
//  - a cell is occupied when its free probability is below `occupied` (MRPT's grids start at
//    0.5, unknown), free above `free`;
//  - occupied blobs smaller than `speckCells` are dropped (a person, a chair leg seen once);
//  - each blob's boundary is traced (cv::findContours, every ring: walls with rooms inside
//    them have inner boundaries) and simplified (cv::approxPolyDP) within `simplify` metres;
//  - the rings are the walls a beam stops at; the free cells, `clearance` from any wall, are
//    where the scanner may stand.
#include <mrloc/polymap/WallMap.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPose2D.h>

#include <string>

namespace mrpt::config {
class CConfigFileBase;
}

namespace mrloc::polymap {

struct GridTraceOptions {
    double resolution = 0.05;  ///< m: the grid built from a simplemap (a .gridmap has its own)
    double occupied = 0.4;     ///< free probability below which a cell is a wall
    double free = 0.6;         ///< free probability above which a cell is free space
    int speckCells = 4;        ///< occupied blobs of fewer cells are dropped
    double simplify = 0;       ///< m; 0: half a cell (the contour's own quantization)
    double clearance = 0.15;   ///< m from a wall where the scanner may stand
    /** m; traceFreeSpace only: free space narrower than this is closed (a morphological
     *  opening by a square this wide, in whole cells, odd): a mapping run's laser-fan fringes
     *  and slits no robot passes. 0: none. */
    double open = 0;
    /** For a simplemap: MRPT's insertion options section of an INI (pf-localization's
     *  MetricMap_occupancyGrid_00_insertOpts), if any. */
    const mrpt::config::CConfigFileBase* insertOptions = nullptr;
    std::string insertSection;
};

/** What tracing found, for the report. */
struct TraceStats {
    int gridWidth = 0, gridHeight = 0;
    double resolution = 0;
    size_t specksDropped = 0;
    size_t contourPoints = 0;  ///< before simplification
    double simplify = 0;       ///< the tolerance used (m)
};

/** Bound on a grid's cells (doc/errors.md): 8000 x 8000 at any resolution. */
inline constexpr double kMaxGridCells = 64e6;

/** True for the names the grid loader takes: .gridmap, .simplemap, each optionally .gz. */
bool isMrptMapFile(const std::string& path);

/** Loads a .gridmap(.gz) or builds the grid of a .simplemap(.gz). The file is first read in a
 *  child process (common::probeFile): a corrupt or hostile file is one line, never a crash.
 *  Throws mrloc::Error naming the file. */
mrpt::maps::COccupancyGridMap2D loadGridMap(const std::string& path,
                                            const GridTraceOptions& options);

/** Traces `grid` into a WallMap (rings = the walls' boundaries, every one a hole in the free
 *  space). */
WallMap traceGrid(const mrpt::maps::COccupancyGridMap2D& grid, const GridTraceOptions& options,
                  const std::string& description, TraceStats* stats = nullptr);

/** m: how much the exact pipeline simplifies a traced map unless `trace_simplify` says. A
 *  traced staircase's steps would each be a corner the hypothesis generation matches, and
 *  corners closer than the scan's tolerance (0.1 m) cannot be told apart; measured on
 *  localization_demo, 12 random starts: the truth among the hypotheses from 3 starts at
 *  0.07 m, 5 at 0.1, 8 at 0.15, 9 at 0.2, 8 at 0.3 (doc/polymap.md). */
inline constexpr double kExactTraceSimplify = 0.2;

/** m: the free space narrower than this that the exact pipeline closes unless `trace_open`
 *  says (GridTraceOptions::open): twice the scanner's default clearance. A mapping run's
 *  laser fan leaves rays of free cells into unknown space, each a pair of corners the
 *  hypothesis generation would match; measured on malaga-cs-fac-building, 12 random starts
 *  (doc/polymap.md): the truth among the hypotheses from none without it. */
inline constexpr double kExactTraceOpen = 0.3;

/** The free space of `grid` around `inside` as rings the exact pipeline takes
 *  (common::Polygon::fromRings: the outer ring first, then holes), traced along the cells'
 *  edges rather than their centres (doc/polymap.md, "Traced maps in the exact pipeline"):
 *  - the free cells (free probability above `free`), opened by a square at least `open`
 *    wide (free space narrower than it closed: laser-fan rays, slits), 4-connected to the
 *    cell at `inside` are the region (a robot does not pass between two cells that touch at
 *    a corner alone);
 *  - its boundary runs along cell edges, region on the left; where the boundary meets itself
 *    at a cell corner (two region cells touching diagonally: a pinch vertex) it turns to stay
 *    around its own cell, and each of the two passes cuts that cell's corner a quarter cell
 *    from it: a pinch vertex becomes two on each pass, the passes half a cell apart (the
 *    area given up: a 32nd of a cell per pass);
 *  - holes of fewer than `speckCells` cells (slivers below the grid's resolution: a chair leg,
 *    a speck of noise) are dropped;
 *  - each ring is simplified within `simplify` (0: half a cell) by Douglas-Peucker, the
 *    tolerance halved until the rings validate (a simplification may make two rings touch);
 *    unsimplified, the rings are valid by construction.
 *  Throws mrloc::Error if `inside` is not on a free cell or is in free space narrower than
 *  `open`, or if the region is too large. */
std::vector<std::vector<TPoint2D>> traceFreeSpace(const mrpt::maps::COccupancyGridMap2D& grid,
                                                  const GridTraceOptions& options,
                                                  const TPoint2D& inside,
                                                  const std::string& description);

/** What a map picture shows besides the map. */
struct MapOverlay {
    std::vector<mrpt::math::TPose2D> hypotheses;  ///< drawn as arrows
    struct Path {
        std::string label;
        std::vector<TPoint2D> points;
    };
    std::vector<Path> paths;
    bool cropToOverlay = false;  ///< the box around the overlay, not the whole map
};

/** The map as a picture (PNG): the grid in grey (if any), where the scanner may stand tinted,
 *  the rings and the overlay in the palette's colours; axes in metres (the map's frame) and
 *  the legend in a panel beside the map (report::framePicture). */
void renderMap(const mrpt::maps::COccupancyGridMap2D* grid, const WallMap& map,
               const MapOverlay& overlay, const std::string& pngPath, const std::string& title);

}  // namespace mrloc::polymap
