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
//   the lattice fit (ours, beyond the paper; N >= 5): where Algorithm 1 has converged and the
//     rear camera sees more robots than the three beacons, the robot fits its pose to every
//     tag in view (bearings, Gauss-Newton on the believed lattice) and drives to the vertex
//     by that fit, so that the new vertex sits on the lattice of all the robots it sees
//     rather than on the reflection of one anchor.
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
    /** The lattice fit after Algorithm 1 (ours; doc/formation.md): needs this many robots'
     *  tags in the rear frame (the three beacons and at least one more), at most
     *  `latticeFits` corrections, stops within `latticeFitTolerance` of the vertex. */
    bool latticeFit = false;
    size_t latticeFitRobots = 4;
    int latticeFits = 3;
    double latticeFitTolerance = 0.003;  ///< m
};

/** A robot's pose fitted to the tags its rear camera sees (the lattice fit). */
struct LatticeFit {
    mrpt::poses::CPose2D pose;  ///< the robot's centre and heading, believed frame
    size_t robots = 0;          ///< robots whose tags were used
    double rms = 0;             ///< px, the bearings' residual
};

/** Fits the pose of a robot whose rear camera (on its back face, at the tags' height) saw
 *  `tags`, to the believed poses of the robots they belong to (bearings only: each tag
 *  centre's column; Gauss-Newton from `start`; the tag with the largest residual dropped
 *  while any is over 4 px). Tags of `self` or of no robot in `believed` are ignored; nothing
 *  if fewer than `minRobots` robots remain or the fit fails. */
std::optional<LatticeFit> fitToLattice(const std::vector<MarkerSighting>& tags,
                                       const std::vector<mrpt::poses::CPose2D>& believed,
                                       size_t self, const mrpt::poses::CPose2D& start,
                                       const mrpt::img::TCamera& k, const MarkerOptions& markers,
                                       size_t minRobots);

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
    enum class Phase { Gate, FaceAway, AlgorithmOne, LatticeFit, Done, Lost };
    std::vector<Maneuver> order(std::vector<Maneuver> maneuvers);  ///< and move the belief
    std::vector<Maneuver> towards(const TPoint2D& p);              ///< a turn to face p
    std::vector<Maneuver> gatePassed();
    /** The camera lost the beacons: on to the target and round, by the belief alone. */
    std::vector<Maneuver> finishBlind();
    /** Algorithm 1 has converged with these tags in view: the lattice fit's correction, or
     *  nothing more to do (the move is done). */
    std::vector<Maneuver> fitStep(const std::vector<MarkerSighting>& tags);
    std::optional<MarkerSighting> largestTag(size_t robot,
                                             const std::vector<MarkerSighting>& tags) const;

    Move move_;
    CameraMoveOptions o_;
    std::vector<std::array<size_t, 2>> gates_;  ///< the beacon pair of each gate
    std::vector<TPoint2D> gatePoints_;
    TPoint2D anchor_;
    std::vector<mrpt::poses::CPose2D> believed_;  ///< every robot's believed pose
    size_t gate_ = 0;
    Phase phase_ = Phase::Gate;
    TPoint2D at_;     ///< believed position
    double heading_;  ///< believed heading (rad)
    std::optional<AlgorithmOneController> algorithmOne_;
    int frames_ = 0, blindGates_ = 0, recoveries_ = 0, scans_ = 0, algorithmOneFrames_ = 0;
    int latticeFits_ = 0;  ///< corrections by the lattice fit so far
};

}  // namespace mrloc::formation
