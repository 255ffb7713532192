#pragma once
// The formation method's localizer: the team's on-board logic (Team) run again on the
// rawlog's obstacle scans and arrival messages, and the dead-reckoning robot's estimate
// integrated again from its sensed heading and speed. Its estimates: each formation robot
// at the start and at each vertex it reached (where the team believes it: seed 003 can
// only tell a robot's position when a triangle is built), and the dead-reckoning robot at
// every reading.
#include <mrloc/common/Localizer.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/Team.h>
#include <mrpt/poses/CPose2D.h>

#include <map>
#include <optional>
#include <utility>

namespace mrloc::formation {

class FormationLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    /** Each formation robot's believed pose over the whole log: held where it stood (seed
     *  003 moves one robot at a time, and a robot reports each arrival), then moved to the
     *  vertex it reached; the dead-reckoning robot at every reading. On the truth's timeline
     *  a robot that waits is then scored where the team believes it waits, not on a line
     *  drawn from one arrival to its next (doc/formation.md, "Along the march"). */
    common::Trajectories estimates() const override;
    /** The dead-reckoning robot: seed 003's baseline, never pooled with the formation. */
    std::set<std::string> baselineRobots() const override { return {kDeadReckoningRobot}; }
    /** The team's scans (<robot>.obstacles) and arrival messages (<robot>.arrived): used
     *  are those of robots in [formation]. */
    common::ObservationUse observationUse() const override;
    nlohmann::json methodMetrics() const override;
    nlohmann::json truthMetrics(const common::Trajectories& truth) const override;
    void writeOutputs(const std::string& outDir, const common::Trajectories& truth) const override;

    const FormationConfig& config() const { return config_; }
    const Team& team() const { return *team_; }

 private:
    /** A formation robot's odometry: notes when it leaves rest (moveStart_). */
    void noteMotion(const mrpt::obs::CObservation::Ptr& obs, double t);

    FormationConfig config_;
    size_t teamSeen_ = 0, teamUsed_ = 0;
    std::optional<Team> team_;
    common::Trajectories estimates_;  ///< at the start and at each vertex reached
    /** estimates_ with the holds: each robot's last pose again when another robot's move
     *  begins (the previous arrival of any robot), so that its own move starts from there. */
    common::Trajectories track_;
    double lastArrival_ = -1;  ///< time of the team's latest arrival or first sighting (s)
    /** Per robot, from its own odometry (<robot>.odom): the last reading at rest before it
     *  began to move, since its last estimate; its move starts from its held pose there. */
    std::map<std::string, double> moveStart_;
    /** The held estimate a move started from, and the robot's odometry then. */
    std::map<std::string, std::pair<mrpt::poses::CPose2D, mrpt::poses::CPose2D>> moveFrom_;
    struct Reading {
        double t = 0;
        mrpt::poses::CPose2D pose;
        bool moving = false;
    };
    std::map<std::string, Reading> lastReading_;  ///< each robot's latest odometry reading
    double lastTime_ = -1;  ///< time of the latest observation (s): the holds run to it
    std::optional<TPoint2D> deadReckoned_;  ///< the dead-reckoning robot's estimate
    size_t cameraLostMoves_ = 0;            ///< "formation: <robot> lost the beacons"
};

}  // namespace mrloc::formation
