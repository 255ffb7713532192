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

namespace mrloc::framesync {

struct MatchOptions {
    double maxBearing = 20 * M_PI / 180;  ///< rad (seed 004 sec. 5.1)
    double maxDistance = 0.5;             ///< m (50 cm, seed 004 sec. 5.1)
    double minOverlap = 0.3;              ///< m the segments must share after the redefinition
};

struct Redefinition {
    mrpt::poses::CPose2D correction;  ///< new frame = correction (+) old frame
    double rotation = 0;              ///< rad, about the robot's position
    double shift = 0;                 ///< m, along the reference wall's normal
    double overlap = 0;               ///< m the two segments share after it
};

/** Rotation by `rotation` about `centre`, then a shift along `normal` (a unit vector). */
mrpt::poses::CPose2D redefinitionTransform(const TPoint2D& centre, double rotation,
                                           const TPoint2D& normal, double shift);

/** The redefinition that puts `own` on `reference`, seen from the robot at `robot` (its
 *  own frame), if the walls pass the three tests. */
std::optional<Redefinition> matchWalls(const Wall& own, const Wall& reference,
                                       const TPoint2D& robot, const MatchOptions& options);

/** Length two collinear-ish segments share, measured along `reference`'s direction
 *  (negative: the gap between them). */
double overlapAlong(const Wall& reference, const Wall& other);

}  // namespace mrloc::framesync
