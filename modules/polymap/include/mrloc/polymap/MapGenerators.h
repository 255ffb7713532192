#pragma once
// Self-similar polygon maps: the "steps" family of seed 002 (sec. 3, figs. 2-5) and rooms
// repeated along a corridor. Each generator also returns the self-similar sites: points
// that see congruent visibility polygons, which are the hypotheses a robot standing at any
// one of them must find.
#include <mrloc/common/Polygon.h>
#include <mrpt/random/RandomGenerators.h>

#include <string>
#include <vector>

namespace mrloc::polymap {

struct GeneratedMap {
    common::Polygon polygon;
    std::vector<common::TPoint2D> sites;  ///< congruent viewpoints, in the paper's order
    std::string description;
};

/** A staircase corridor of `steps` identical steps; each step's ceiling carries
 *  `branchesPerStep` identical branches, a corridor with three bends ending in a dead end.
 *  n = steps * (4 + 10 * branchesPerStep) + 4 (an entrance alcove on the left end), k =
 *  steps * branchesPerStep sites (one deep in each branch, which sees only its branch):
 *  3 steps give the paper's n = 76, k = 6, 6 steps n = 148, k = 12. */
struct StepsMapOptions {
    int steps = 6;
    int branchesPerStep = 2;
    double stepWidth = 16, stepRise = 2, corridorHeight = 4;  ///< m
    double branchWidth = 1, branchLeg = 2;  ///< a branch's width and the length of each leg
    /** m: with stepRise >= corridorHeight, the width of the vertical shaft joining a step's
     *  right end to the next step's floor (unused otherwise). */
    double shaftWidth = 1;
};
GeneratedMap stepsMap(const StepsMapOptions& options);

/** How the copies of the room are joined (an office floor's usual arrangements). */
enum class RoomsLayout {
    Side,      ///< side by side above one corridor, each through a neck
    Row,       ///< in a row, each joined to the next by a Z-shaped passage
    Mirrored,  ///< on both sides of the corridor, those below mirror images of those above
};
inline constexpr RoomsLayout kRoomsLayouts[] = {RoomsLayout::Side, RoomsLayout::Row,
                                                RoomsLayout::Mirrored};
std::string roomsLayoutName(RoomsLayout layout);
/** Parses a name of roomsLayoutName(); throws mrloc::Error naming the valid ones. */
RoomsLayout roomsLayoutFromName(const std::string& name);

/** `rooms` copies of one random room (a skyline of `roomSteps` random heights).
 *  - Side: above a corridor, each joined to it by a neck. Corridor margins are wide enough
 *    that nobody in a room sees a corridor end; `rightMargin` > 0 lengthens the right one
 *    (an asymmetric join). n = 4 + rooms * (6 + 2 * roomSteps).
 *  - Mirrored: the same, and below the corridor each room's mirror image facing it (the
 *    mirror images are not congruent to the rooms: the sites are the upper rooms').
 *  - Row: rooms joined wall to wall by passages of width min(neckWidth, (roomHeightMin -
 *    0.5) / 3), each with a jog no sight line passes, so every room (the two ends too, which
 *    have a dead-end passage) looks the same from inside; only a walk through a passage
 *    tells them apart.
 *  Coordinates are multiples of 1/8 m. The site is a random point of the room, the same in
 *  every copy. */
struct RoomsMapOptions {
    RoomsLayout layout = RoomsLayout::Side;
    int rooms = 4;
    int roomSteps = 4;
    double roomWidth = 6, roomHeightMin = 2, roomHeightMax = 5;  ///< m
    double neckWidth = 1, neckLength = 1.5, corridorHeight = 2.5, roomGap = 1.5;
    double rightMargin = 0;  ///< extra length of the corridor's right end (m)
    /** > 0: a square pillar of this side (m) in every room, the same spot in each copy (a
     *  hole in the map): at half room_height_min above the floor, a quarter of the room's
     *  width from the wall farther from the site. */
    double pillar = 0;
};
GeneratedMap roomsMap(const RoomsMapOptions& options, mrpt::random::CRandomGenerator& rng);

/** A hall with pillars: a width x height rectangle (m) holding columns x rows pillars, each a
 *  random star-shaped polygon of `pillarVertices` vertices (radii 0.2-0.45 of the spacing,
 *  angles evenly spread and jittered)
 *  on a jittered grid: n = 4 + columns * rows * pillarVertices, one hole per pillar. The
 *  site is the hall's corner nearest the origin, 0.1 of a spacing in. For benches and tests
 *  of maps with many holes. */
GeneratedMap pillarHall(int columns, int rows, int pillarVertices, double spacing,
                        mrpt::random::CRandomGenerator& rng);

/** A random star-shaped simple polygon of n vertices around the origin, radii in
 *  [rMin, rMax] (no self-similarity in general). */
common::Polygon randomStarPolygon(int n, double rMin, double rMax,
                                  mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::polymap
