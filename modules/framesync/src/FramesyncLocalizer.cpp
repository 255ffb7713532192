#include <mrloc/common/AtomicFile.h>
#include <mrloc/framesync/FramesyncFiles.h>
#include <mrloc/framesync/FramesyncLocalizer.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrpt/obs/CObservationComment.h>

namespace mrloc::framesync {

void FramesyncLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    config_.loadFromConfigFile(ini, "framesync");
    team_ = std::make_unique<FrameTeam>(config_.team);
    recordedRedefinitions_ = 0;
}

void FramesyncLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    config_.saveToConfigFile(target, "framesync");
}

void FramesyncLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    if (const auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obs)) {
        if (isRedefinitionText(c->text)) ++recordedRedefinitions_;
        return;
    }
    team_->process(obs);
}

common::ObservationUse FramesyncLocalizer::observationUse() const {
    common::ObservationUse use;
    use.kind = "sonar readings (CObservationRange, <robot>.sonar)";
    use.seen = team_->readings();
    use.used = team_->readings() - team_->unplacedReadings();
    use.unmatched.push_back({"sonar readings before the robot's first odometry (no pose to place "
                             "them at)",
                             team_->unplacedReadings()});
    return use;
}

nlohmann::json FramesyncLocalizer::methodMetrics() const {
    nlohmann::json m, robots = nlohmann::json::object();
    size_t walls = 0;
    for (const auto& [name, node] : team_->robots()) {
        const auto c = node->detectorCounts();
        size_t redefinitions = 0;
        for (const auto& e : team_->events()) redefinitions += e.robot == name;
        robots[name] = {{"walls", c.walls},
                        {"redefinitions", redefinitions},
                        {"frame_version", node->manager().version()},
                        {"erps", c.erps},
                        {"pairs_without_wall", c.noWall},
                        {"pairs_out_of_cone", c.outOfCone},
                        {"pairs_ambiguous", c.ambiguous},
                        {"groups_too_short", c.tooShort},
                        {"groups_off_line", c.offLine},
                        {"groups_not_perpendicular", c.notPerpendicular}};
        walls += c.walls;
    }
    m["robots"] = robots;
    m["sharing"] = config_.team.sharing;
    m["sonar_readings"] = team_->readings();
    m["sonar_readings_before_odometry"] = team_->unplacedReadings();
    m["walls"] = walls;
    m["redefinitions"] = team_->events().size();
    m["redefinitions_recorded_on_board"] = recordedRedefinitions_;
    return m;
}

nlohmann::json FramesyncLocalizer::truthMetrics(const common::Trajectories& truth) const {
    const auto pairs = endFigures(team_->estimates(), team_->odometry(), truth);
    if (pairs.empty()) return nlohmann::json::object();
    // the mean over pairs; each pair is in framesync.run.txt and the report's table
    const auto [shared, odometry] = meanPairErrors(pairs);
    return {{"end_relative_error_shared_m", shared},
            {"end_relative_error_odometry_m", odometry},
            {"robot_pairs", pairs.size()}};
}

void FramesyncLocalizer::writeOutputs(const std::string& outDir,
                                      const common::Trajectories& truth) const {
    FramesyncRunFile f;
    for (const auto& [name, node] : team_->robots())
        f.walls.insert(f.walls.end(), node->walls().begin(), node->walls().end());
    f.events = team_->events();
    f.pairs = endFigures(team_->estimates(), team_->odometry(), truth);
    f.write(outDir);  // odometry alone: odometry.<robot>.txt, written for every method
}

}  // namespace mrloc::framesync
