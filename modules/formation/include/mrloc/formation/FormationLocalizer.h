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

#include <optional>

namespace mrloc::formation {

class FormationLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    common::Trajectories estimates() const override { return estimates_; }
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
    FormationConfig config_;
    size_t teamSeen_ = 0, teamUsed_ = 0;
    std::optional<Team> team_;
    common::Trajectories estimates_;
    std::optional<TPoint2D> deadReckoned_;  ///< the dead-reckoning robot's estimate
    size_t cameraLostMoves_ = 0;            ///< "formation: <robot> lost the beacons"
};

}  // namespace mrloc::formation
