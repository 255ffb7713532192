#pragma once
// Matching two robots' walls and redefining a frame (seed 004 secs. 4.3-4.4). A robot's own
// wall and a reference wall (another robot's, in that robot's frame) are one wall if
//   - their bearings differ by less than a threshold (20 degrees in the paper),
//   - the distances from the robot to each differ by less than a threshold (50 cm),
//   - the two segments overlap once the frame is redefined.
// The redefinition rotates the frame about the robot's current position by the bearing
// difference (as if the robot's heading changed), then moves it along the reference
// wall's normal by the difference of the distances: the own wall then lies on the
// reference's line. One wall fixes the bearing and one direction; a wall of another
// direction fixes the third degree of freedom.
#include <mrloc/framesync/Wall.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <optional>
#include <vector>

namespace mrloc::framesync {

struct MatchOptions {
    double maxBearing = 20 * M_PI / 180;  ///< rad (seed 004 sec. 5.1)
    double maxDistance = 0.5;             ///< m (50 cm, seed 004 sec. 5.1)
    double minOverlap = 0.3;              ///< m the segments must share after the redefinition
    /** Seed 004 sec. 3's general transform, when no wall passes the local tests: frames that
     *  differ by any rotation and shift (generalMatch). Off: the paper's sec. 4.3 alone. */
    bool general = false;
    size_t generalSupport = 3;  ///< own walls a general transform must put on the others'
    double cornerAngle = 30 * M_PI / 180;    ///< rad: two walls at least this far from parallel
    double generalBearing = 5 * M_PI / 180;  ///< rad: how well a general transform must align
    double generalDistance = 0.15;           ///< m: normals and lines
};

struct Redefinition {
    mrpt::poses::CPose2D correction;  ///< new frame = correction (+) old frame
    double rotation = 0;              ///< rad, about the robot's position
    double shift = 0;                 ///< m, along the reference wall's normal
    double overlap = 0;               ///< m the two segments share after it
    size_t support = 1;               ///< own walls the redefinition puts on reference walls
};

/** Rotation by `rotation` about `centre`, then a shift along `normal` (a unit vector). */
mrpt::poses::CPose2D redefinitionTransform(const TPoint2D& centre, double rotation,
                                           const TPoint2D& normal, double shift);

/** The redefinition that puts `own` on `reference`, seen from the robot at `robot` (its
 *  own frame), if the walls pass the three tests. */
std::optional<Redefinition> matchWalls(const Wall& own, const Wall& reference,
                                       const TPoint2D& robot, const MatchOptions& options);

/** Seed 004 sec. 3: the transform T from the own frame to the reference's from one landmark
 *  both measured in full (a position and a direction). A wall gives only its bearing and its
 *  line, so the landmark here is a corner: two walls at least `cornerAngle` from parallel,
 *  whose lines meet at a point, with the two normals as the direction. Every pair of own
 *  walls against every pair of reference walls at the same angle proposes T (the rotation
 *  from the normals, the shift from the corners); the T that puts the most own walls on a
 *  reference wall (bearing within `generalBearing`, line within `generalDistance`, segments
 *  sharing `minOverlap`) wins, if at least `generalSupport` of them. `ownWall` and
 *  `referenceWall` say which walls made the winning corner (their first walls). */
std::optional<Redefinition> generalMatch(const std::vector<const Wall*>& own,
                                         const std::vector<const Wall*>& reference,
                                         const MatchOptions& options, size_t* ownWall = nullptr,
                                         size_t* referenceWall = nullptr);

/** Length two collinear-ish segments share, measured along `reference`'s direction
 *  (negative: the gap between them). */
double overlapAlong(const Wall& reference, const Wall& other);

}  // namespace mrloc::framesync
