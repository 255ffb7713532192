#pragma once
// Equilateral-triangle formations (Kang, Kwon, Bae and Kim, "Monocular Vision-Based Swarm
// Robot Localization Using Equilateral Triangular Formations", Machines 13(8):667, 2025;
// seed 003 sections 2-3). N >= 4 robots stand on the vertices of a triangular lattice of side
// s. One robot moves at a time: three others, an equilateral triangle, stand still as
// beacons, and the moving robot goes to the reflection of one beacon across the side the
// other two form, so that it and those two form a new equilateral triangle.
//
// The planner works on the positions the robots believe they have (the ideal lattice,
// since every move is meant to build a perfect triangle); where a robot really ends up is
// the business of the motion (March.h's VertexErrorModel, or the camera path of
// AlgorithmOne.h).
#include <mrpt/math/TPoint2D.h>

#include <array>
#include <optional>
#include <vector>

namespace mrloc::formation {

using mrpt::math::TPoint2D;

/** A round obstacle; its safety zone reaches `margin` (FormationOptions) beyond it. */
struct Obstacle {
    TPoint2D centre;
    double radius = 0;  ///< m
};

struct FormationOptions {
    double side = 1.5;          ///< m, the triangles' side (seed 003: 1.5 m)
    double safetyMargin = 0.3;  ///< m, the safety zone beyond an obstacle (seed 003 fig. 6)
};

/** One step of the march (seed 003 sec. 3). */
struct Move {
    size_t robot = 0;              ///< the moving robot
    std::array<size_t, 2> base{};  ///< the two beacons the new triangle shares
    size_t anchor = 0;           ///< the beacon reflected: the far vertex of the beacons' triangle
    TPoint2D target;             ///< the target vertex (believed frame): base[0] + base[1] - anchor
    std::vector<TPoint2D> path;  ///< Algorithm 2: two midpoints between beacons, then the target
};

/** The N-robot starting strip of seed 003 fig. 7: robot 2i at (0.75 + 1.5 i, 0), robot
 *  2i + 1 at (1.5 i, 1.30) for side 1.5 (the paper's four robots for N = 4). */
std::vector<TPoint2D> initialStrip(size_t robots, double side);

/** Seed 003 Algorithm 2: the path from `from` to `target` through the beacons' triangle:
 *  the midpoint of its sides nearest the robot, the midpoint nearest the target, the
 *  target (repeated midpoints are kept once). */
std::vector<TPoint2D> innerPath(const std::array<TPoint2D, 3>& beacons, const TPoint2D& from,
                                const TPoint2D& target);

/** The heading a move leaves its robot with: facing away from the anchor, its rear camera
 *  on it (seed 003 Algorithm 1, step 1), in the believed frame. */
double arrivalHeading(const Move& move, const std::vector<TPoint2D>& believed);

/** The path from `from` along `path` passes within `margin` of no obstacle. */
bool clearOf(const TPoint2D& from, const std::vector<TPoint2D>& path,
             const std::vector<Obstacle>& obstacles, double margin);

/** The next move toward `destination` (seed 003 sec. 3): the robot farthest from it moves,
 *  to the candidate vertex nearest it whose path stays out of every safety zone, else the
 *  next nearest; if none is clear the next farthest robot tries, and so on. A candidate must
 *  be nearer the destination than its robot (else a blocked robot and the next could swap
 *  places for ever: a choice of ours, doc/formation.md). A candidate is
 *  the reflection of a beacon across the side of two others, three robots standing on an
 *  equilateral triangle of side s (within 1 % of s); it must be free (no robot within s / 2)
 *  and leave every robot on at least one triangle (the formation stays one piece). Nothing
 *  if no robot can move. */
std::optional<Move> nextMove(const std::vector<TPoint2D>& believed, const TPoint2D& destination,
                             const std::vector<Obstacle>& obstacles,
                             const FormationOptions& options);

/** Seed 003's march along a route, one move at a time: the waypoint the formation heads for
 *  and the next move towards it. The team's on-board logic (Team) and the error-model march
 *  (March) both plan through it, so that both take the same moves from the same beliefs. */
class RoutePlanner {
 public:
    enum class Outcome { Move, Arrived, Stuck };
    /** Throws mrloc::Error for an empty route. */
    RoutePlanner(std::vector<TPoint2D> route, FormationOptions options, size_t maxMoves);
    /** Skips the waypoints a believed vertex is within side / sqrt(3) of (every point is
     *  that near a lattice vertex), then plans the next move towards the first one left.
     *  Throws mrloc::Error naming maxMoves once that many moves have been planned. */
    Outcome plan(const std::vector<TPoint2D>& believed, const std::vector<Obstacle>& obstacles);
    /** The move the last plan() returned Outcome::Move with. */
    const std::optional<Move>& move() const { return move_; }
    size_t planned() const { return planned_; }

 private:
    std::vector<TPoint2D> route_;
    FormationOptions options_;
    size_t maxMoves_;
    size_t next_ = 0;  ///< the first waypoint not reached
    size_t planned_ = 0;
    std::optional<Move> move_;
};

}  // namespace mrloc::formation
