#pragma once
// A simulated robot: a unicycle that a method steers each step (waypoints, stop, go, turn,
// drive), with optional actuation noise, and its options (section [robot.<name>]).
#include <mrloc/common/KeyTable.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::sim {

/** How near a waypoint the follower stops, for a robot of `speed` (m/s) at step `dt` (s): a
 *  step's travel, at least 2 cm (m). Methods that search for a robot at its goal (polymap's
 *  probes) take their radius from here, not a constant of their own. */
double arrivalRadius(double speed, double dt);

struct RobotOptions : public mrpt::config::CLoadableOptions {
    std::string name;
    mrpt::poses::CPose2D start;                   ///< start = x y phi_deg
    std::vector<mrpt::math::TPoint2D> waypoints;  ///< waypoints = x y, x y, ... (none: stands)
    bool loop = true;                             ///< go back to the first waypoint at the end
    double speed = 0.3;                           ///< m/s
    double maxTurnRate = 1.5;                     ///< rad/s
    double odometryRate = 20;                     ///< Hz
    double odometrySigmaXY = 0.02;                ///< per metre travelled
    double odometrySigmaPhi = 0.01;               ///< per radian turned
    double odometrySigmaPhiPerMetre = 0.005;      ///< rad per metre travelled
    /** Systematic odometry errors, fixed for a run (the drift of a real base): the wheel
     *  radius error scales every distance by (1 + scale error); the heading drifts by
     *  heading drift (rad) per metre driven (unequal wheels). Each is drawn once at the
     *  start, N(value, sigma), when its sigma is positive. */
    double odometryScaleError = 0;         ///< odometry_scale_error (relative)
    double odometryScaleErrorSigma = 0;    ///< odometry_scale_error_sigma (relative)
    double odometryHeadingDrift = 0;       ///< odometry_heading_drift (deg/m in the INI; rad/m)
    double odometryHeadingDriftSigma = 0;  ///< odometry_heading_drift_sigma (deg/m; rad/m)
    double actuationSigmaV = 0;  ///< relative noise on the commanded speed (0: none drawn)
    double actuationSigmaW = 0;  ///< rad/s noise on the commanded turn rate (0: none drawn)
    /** start is a required key (false: the scenario sets it, and the key is an error). */
    bool startInSection = true;
    /** Keys of [robot.<name>] that the method reads and writes itself (a beacon receiver's
     *  mounting, say): accepted here, not read. */
    std::vector<std::string> methodKeys;

    /** The simulator's keys of [robot.<name>], declared once (loading, effective.ini,
     *  doc/ini.md); a method's own keys are in its table of the same section. */
    static const common::KeyTable<RobotOptions>& keys();
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

/** Unicycle. By default a waypoint follower: turn towards the waypoint (at most
 *  maxTurnRate), drive at `speed` scaled down while the heading error is large. A method's
 *  on-board part may instead stop it, let it go again, or command a speed and turn rate. */
class Robot {
 public:
    explicit Robot(RobotOptions options);
    const RobotOptions& options() const { return options_; }
    const mrpt::poses::CPose2D& pose() const { return pose_; }
    /** Advances by dt; returns the motion in the robot frame (for odometry). Draws from
     *  rng only when the options ask for actuation noise. */
    mrpt::poses::CPose2D step(double dt, mrpt::random::CRandomGenerator& rng);

    /** How near a waypoint counts as reached at step length dt (m): sim::arrivalRadius. */
    double arrivalRadius(double dt) const;
    /** Replaces the route and follows it (ends a drive() command). */
    void setWaypoints(std::vector<mrpt::math::TPoint2D> waypoints, bool loop);
    /** Stands still until go(); the simulator then neither moves it nor reads its wheels. */
    void stop() { halted_ = true; }
    void go() { halted_ = false; }
    bool halted() const { return halted_; }
    /** Drives at v (m/s) turning at w (rad/s) until the next command; v is capped at the
     *  robot's speed and w at its max_turn_rate. */
    void drive(double v, double w);
    /** Turns on the spot at w (rad/s). */
    void turn(double w) { drive(0, w); }

 private:
    /** This step's commanded distance (m) and turn (rad): from the waypoints or the last
     *  drive(). */
    std::pair<double, double> command(double dt);

    RobotOptions options_;
    mrpt::poses::CPose2D pose_;
    size_t next_ = 0;
    bool halted_ = false;
    std::optional<std::pair<double, double>> velocity_;  ///< drive() command, if any
};

}  // namespace mrloc::sim
