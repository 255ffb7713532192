#pragma once
// One move of seed 003 from the moving robot's cameras alone (the pixel mode): the three
// steps of sec. 2 and fig. 3, frame by frame.
//   approaching and inner triangle (front camera): for each gate of Algorithm 2's path (the
//     midpoint between two beacons), turn towards it, centre the two beacons' tags about the
//     image centre, drive to within `gateStop` of it (its distance from the tags' lateral
//     pixel distance), centre again, drive through. A gate whose two beacons are not both in
//     view (the inner triangle's second gate, seen from the first at 60 degrees) is driven
//     by the believed geometry.
//   building the triangle (rear camera): face away from the anchor (its tag at the rear
//     image's centre), drive out the triangle's height, then Algorithm 1
//     (AlgorithmOneController) until its three conditions hold.
// The controller tracks where it believes the robot is (the maneuvers it ordered, exactly
// done) to know where to look; what it steers by is the tags. A beacon it misses it
// re-acquires: the anchor after facing away by turning to either side, a beacon in Algorithm
// 1 by small steps along its heading and then by backing away from the beacons; Algorithm
// 1's tolerance doubles every 20 of its frames, so that a robot dithering about the vertex
// stops there. Only when a beacon stays lost does it finish the move by the belief alone (to
// the target, then facing away from the anchor), and says so.
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/Formation.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::formation {

struct CameraMoveOptions {
    double side = 1.5;                 ///< m
    MarkerOptions markers;             ///< the robots' tags
    AlgorithmOneOptions algorithmOne;  ///< tolerance, noise, camera height
    mrpt::img::TCamera intrinsics;     ///< both cameras'
    double gateStop = 0.8;             ///< m before a gate to centre again
    double gateTolerance = 3;          ///< px, the gate's centring
    int maxFrames = 200;               ///< a move that needs more is lost
};

class CameraMove {
 public:
    enum class Camera { Front, Rear };

    /** `believed`: every robot's believed position; `headings`: their believed headings
     *  (the beacons' tags' sides; the mover's heading to start from). */
    CameraMove(const Move& move, const std::vector<TPoint2D>& believed,
               const std::vector<double>& headings, const CameraMoveOptions& options);
    /** The maneuvers before the first frame: a turn towards the first gate. */
    std::vector<Maneuver> start();
    /** The camera of the next frame; nothing once the move is over. */
    std::optional<Camera> camera() const;
    /** The maneuvers after a frame with these tags (empty once the move is over). */
    std::vector<Maneuver> decide(const std::vector<MarkerSighting>& tags);
    bool converged() const { return phase_ == Phase::Done; }
    /** The beacons were lost on the way: the move was finished by the believed geometry. */
    bool lost() const { return phase_ == Phase::Lost; }
    int frames() const { return frames_; }
    int blindGates() const { return blindGates_; }  ///< gates driven by the believed geometry

 private:
    enum class Phase { Gate, FaceAway, AlgorithmOne, Done, Lost };
    std::vector<Maneuver> order(std::vector<Maneuver> maneuvers);  ///< and move the belief
    std::vector<Maneuver> towards(const TPoint2D& p);              ///< a turn to face p
    std::vector<Maneuver> gatePassed();
    /** The camera lost the beacons: on to the target and round, by the belief alone. */
    std::vector<Maneuver> finishBlind();
    std::optional<MarkerSighting> largestTag(size_t robot,
                                             const std::vector<MarkerSighting>& tags) const;

    Move move_;
    CameraMoveOptions o_;
    std::vector<std::array<size_t, 2>> gates_;  ///< the beacon pair of each gate
    std::vector<TPoint2D> gatePoints_;
    TPoint2D anchor_;
    size_t gate_ = 0;
    Phase phase_ = Phase::Gate;
    TPoint2D at_;     ///< believed position
    double heading_;  ///< believed heading (rad)
    std::optional<AlgorithmOneController> algorithmOne_;
    int frames_ = 0, blindGates_ = 0, recoveries_ = 0, scans_ = 0, algorithmOneFrames_ = 0;
};

}  // namespace mrloc::formation
