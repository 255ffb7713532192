#pragma once
// The framesync method's localizer: the robots' on-board systems (FrameTeam) run again on
// the log's odometry and sonar. Its estimates: each robot in its shared frame at every
// odometry reading; beside them, the walls and redefinitions (framesync.run.txt). The
// framework writes odometry alone (odometry.<robot>.txt) for every method. A log of one
// robot, an MRPT rawlog with sonar say, gives its walls and its odometry: there is nobody to
// share a frame with.
#include <mrloc/common/Localizer.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/framesync/Team.h>

#include <memory>

namespace mrloc::framesync {

class FramesyncLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    common::Trajectories estimates() const override { return team_->estimates(); }
    /** Sonar readings: used are those placed on the robot's odometry (a reading before the
     *  first odometry has no pose to be placed at). */
    common::ObservationUse observationUse() const override;
    nlohmann::json methodMetrics() const override;
    nlohmann::json truthMetrics(const common::Trajectories& truth) const override;
    void writeOutputs(const std::string& outDir, const common::Trajectories& truth) const override;

    const FramesyncConfig& config() const { return config_; }
    const FrameTeam& team() const { return *team_; }

 private:
    FramesyncConfig config_;
    std::unique_ptr<FrameTeam> team_;
    size_t recordedRedefinitions_ = 0;  ///< the on-board decision layers' comments in the log
};

}  // namespace mrloc::framesync
