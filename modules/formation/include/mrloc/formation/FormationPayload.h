#pragma once
// The formation method in the simulator (sim::Payload): robots f1 .. fN march in triangles
// while robot "dr" drives the route by dead reckoning (seed 003 sec. 5). Each step:
//   command   the moving robot turns towards the next point of its real path and drives to
//             it (a unicycle: turn on the spot, then straight), and at the vertex turns to
//             face away from the anchor (its rear camera on it, as Algorithm 1 leaves it);
//             the beacons stand; "dr" follows the route;
//   sense     at the start and at each arrival, the robot's obstacle scan in the world's
//             OctoMap (<robot>.obstacles); at each arrival, <robot>.arrived; every
//             dr_period, the dead-reckoning robot's heading and wheel speed readings and its
//             estimate (dr.deadreckoning, a CObservationOdometry);
//   onObservation  the team's on-board logic (Team) plans the next move.
// Error-model mode: a move ends where the carry model and the paper's per-step errors put it
// (moveEnd), among the real beacons. Pixel mode: the moving robot's front and rear cameras
// render the others (their tags) at every decision, AprilTag 3 finds the tags
// (<robot>.front, <robot>.rear: CObservationBearingRange, one bearing per tag), and
// CameraMove decides the next maneuvers, executed with their relative errors; a move whose
// beacons left the view ends where the robot stands, with the message
// "formation: <robot> lost the beacons".
#include <mrloc/formation/CameraMove.h>
#include <mrloc/formation/DeadReckoning.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/FormationScene.h>
#include <mrloc/formation/Team.h>
#include <mrloc/sim/Payload.h>

#include <deque>
#include <memory>
#include <optional>

namespace mrloc::formation {

/** The team's options from [formation]: names f1 .. fN on the strip, the route, in the
 *  world frame. */
TeamOptions teamOptions(const FormationConfig& config);

/** The dead-reckoning robot's reading as written to the rawlog: the estimate and the
 *  sensed heading in `odometry`, the sensed speed in `velocityLocal.vx`. */
inline const std::string kDeadReckoningLabel = "dr.deadreckoning";

class FormationPayload : public sim::Payload {
 public:
    /** Fleet order: f1 .. fN, then dr. Throws mrloc::Error if dr_period is not a whole
     *  number of simulation steps. */
    FormationPayload(const FormationConfig& config, double dt);
    void command(sim::Step& step) override;
    void sense(sim::Step& step) override;
    void onObservation(const mrpt::obs::CObservation::Ptr& obs) override;

 private:
    void startMove(sim::Step& step);
    void steer(sim::Step& step);
    void readDeadReckoning(sim::Step& step);
    /** How far the moving robot must turn to face away from the real anchor (rad). */
    double headingError(const sim::Step& step) const;
    void emitScan(sim::Step& step, size_t robot);
    void arrive(sim::Step& step);
    void startCameraMove(sim::Step& step);
    /** The front maneuver's share of this step, ordered to the moving robot. */
    void executeManeuver(sim::Step& step);
    /** A frame of the moving robot's camera, its tags written and decided on. */
    void cameraFrame(sim::Step& step);
    void enqueue(const std::vector<Maneuver>& maneuvers, mrpt::random::CRandomGenerator& rng);

    FormationConfig config_;
    Team team_;
    size_t robots_;               ///< formation robots; the dead-reckoning robot is next
    bool driving_ = false;        ///< the current move is under way in the world
    std::vector<TPoint2D> path_;  ///< its real path (Algorithm 2 among the real beacons)
    size_t leg_ = 0;              ///< the point of path_ it drives to
    long drEvery_ = 1;            ///< steps per dead-reckoning period
    std::optional<DeadReckoner> deadReckoner_;
    TPoint2D drLast_;      ///< where the dead-reckoning robot was at its last reading
    bool drDone_ = false;  ///< it reached the destination: its run ended
    double drTravelled_ = 0, drRouteLength_ = 0;  ///< m, truly driven and the route's length
    // pixel mode
    std::unique_ptr<sim::PinholeCamera> camera_;
    std::optional<CameraModel> lens_;
    std::optional<FormationScene> scene_;  ///< every formation robot, built once
    std::optional<CameraMove> cameraMove_;
    std::deque<Maneuver> maneuvers_;  ///< to execute, real amounts (errors drawn)
};

}  // namespace mrloc::formation
