#pragma once
// A simulated robot: unicycle kinematics driven towards a list of waypoints at constant
// speed with a bounded turn rate, and its sensors' options (section [robot.<name>]).
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose2D.h>

#include <string>
#include <vector>

namespace mrloc::sim {

struct RobotOptions : public mrpt::config::CLoadableOptions {
    std::string name;
    mrpt::poses::CPose2D start;                   ///< start = x y phi_deg
    std::vector<mrpt::math::TPoint2D> waypoints;  ///< waypoints = x y, x y, ... (none: stands)
    bool loop = true;                             ///< go back to the first waypoint at the end
    double speed = 0.3;                           ///< m/s
    double maxTurnRate = 1.5;                     ///< rad/s
    mrpt::math::TPoint3D receiver{0, 0, 0.3};     ///< beacon receiver on the robot (m)
    double odometryRate = 20;                     ///< Hz
    double beaconRate = 5;                        ///< Hz: most ranging epochs it asks for
    long rangingEpochs = 0;                       ///< stops asking after this many (0: never)
    double odometrySigmaXY = 0.02;                ///< per metre travelled
    double odometrySigmaPhi = 0.01;               ///< per radian turned
    double odometrySigmaPhiPerMetre = 0.005;      ///< rad per metre travelled
    /** start is a required key (false: the scenario sets it, and the key is an error). */
    bool startInSection = true;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

/** Where a receiver mounted at `onRobot` is when the robot is at `pose`. */
mrpt::math::TPoint3D receiverAt(const mrpt::poses::CPose2D& pose,
                                const mrpt::math::TPoint3D& onRobot);

/** Unicycle with a waypoint follower: turn towards the waypoint (at most maxTurnRate),
 *  drive at `speed` scaled down while the heading error is large. */
class Robot {
 public:
    explicit Robot(RobotOptions options);
    const RobotOptions& options() const { return options_; }
    const mrpt::poses::CPose2D& pose() const { return pose_; }
    /** The beacon receiver's position in the world at the current pose. */
    mrpt::math::TPoint3D receiverInWorld() const { return receiverAt(pose_, options_.receiver); }
    /** Advances by dt; returns the motion in the robot frame (for odometry). */
    mrpt::poses::CPose2D step(double dt);
    /** Replaces the route (closed-loop control by a method). */
    void setWaypoints(std::vector<mrpt::math::TPoint2D> waypoints, bool loop);

 private:
    RobotOptions options_;
    mrpt::poses::CPose2D pose_;
    size_t next_ = 0;
};

}  // namespace mrloc::sim
